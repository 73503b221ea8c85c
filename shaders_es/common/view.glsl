// SPDX-License-Identifier: MIT
// The view ray at a world point p, as the frame's projection makes it: from
// the eye through p (perspective), or the camera's axis at every point
// (orthographic: u_view_axis.w = 1). frame/camera.c resolves the camera.
uniform highp vec3 u_eye;       // the camera's position (orthographic: a point on its axis)
uniform highp vec4 u_view_axis; // xyz: the direction it looks along; w: 1 orthographic, 0 perspective

highp vec3 snell_view_vec(highp vec3 p)
{
    return u_view_axis.w > 0.5 ? u_view_axis.xyz : p - u_eye;
}

highp vec3 snell_view_ray(highp vec3 p)
{
    return u_view_axis.w > 0.5 ? u_view_axis.xyz : normalize(p - u_eye);
}
