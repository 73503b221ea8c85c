// SPDX-License-Identifier: MIT
// dispersion.glsl - a glass kernel with a dispersive material (u_ior_rgb,
// frame/material.c). The kernel's trace for one IOR is
//     vec3 snell_glass_trace(out highp vec3 exit_dir)
// and main() here calls it as SNELL_DISPERSION says: 0 once at u_ior; 1 once per
// channel (PER_CHANNEL); 2 once at green with red and blue refracted along its
// path (ONE_PATH: snell_disp_enter, snell_disp_cross, snell_disp_cross3,
// snell_disp_exit). The exit direction written is the green one's. More:
// docs/methods.md, "Design notes by file".
#ifndef SNELL_DISPERSION
#define SNELL_DISPERSION 0
#endif

uniform float u_ior;
uniform vec3 u_ior_rgb;

float snell_ior; // the IOR the trace uses (set by main below)

vec3 snell_glass_trace(out highp vec3 exit_dir);

#if SNELL_DISPERSION == 2
mat3 snell_disp_dirs; // the red, green and blue directions along the traced path
#endif

// The view ray v enters at the front surface of normal n (facing v).
void snell_disp_enter(vec3 v, vec3 n)
{
#if SNELL_DISPERSION == 2
    mat3 t;
    snell_refract_rgb(mat3(v, v, v), mat3(n, n, n), 1.0 / u_ior_rgb, t);
    snell_disp_dirs = mat3(normalize(t[0]), normalize(t[1]), normalize(t[2]));
#endif
}

// The traced ray meets an interface: refracted says whether it went through
// (else it was totally reflected), from_inside whether it came from inside
// the glass; n holds each channel's normal there (facing its ray).
void snell_disp_cross3(mat3 n, bool refracted, bool from_inside)
{
#if SNELL_DISPERSION == 2
    mat3 t;
    if (refracted)
        snell_refract_rgb(snell_disp_dirs, n, from_inside ? u_ior_rgb : 1.0 / u_ior_rgb, t);
    else
        t = mat3(snell_reflect(snell_disp_dirs[0], n[0]), snell_reflect(snell_disp_dirs[1], n[1]),
                 snell_reflect(snell_disp_dirs[2], n[2]));
    snell_disp_dirs = mat3(normalize(t[0]), normalize(t[1]), normalize(t[2]));
#endif
}

// The same with the traced ray's normal n (facing it) for every channel.
void snell_disp_cross(vec3 n, bool refracted, bool from_inside)
{
    snell_disp_cross3(mat3(n, n, n), refracted, from_inside);
}

// What the traced path sees leaving the object at p along dir (snell_exit,
// common/beyond.glsl; dir is updated as it updates it): in the one-path
// variant per channel, along that channel's direction from the same point.
vec3 snell_disp_exit(highp vec3 p, inout highp vec3 dir)
{
#if SNELL_DISPERSION == 2
    highp vec3 d_red = snell_disp_dirs[0], d_blue = snell_disp_dirs[2];
    vec3 green = snell_exit(p, dir);
    return vec3(snell_exit(p, d_red).r, green.g, snell_exit(p, d_blue).b);
#else
    return snell_exit(p, dir);
#endif
}

// The kernel's colour as SNELL_DISPERSION says, and the exit direction to write.
vec3 snell_disp_trace(out highp vec3 exit_dir)
{
#if SNELL_DISPERSION == 1
    vec3 color;
    snell_ior = u_ior_rgb.r;
    color.r = snell_glass_trace(exit_dir).r;
    snell_ior = u_ior_rgb.b;
    color.b = snell_glass_trace(exit_dir).b;
    snell_ior = u_ior_rgb.g; // last: its exit direction is the one written
    color.g = snell_glass_trace(exit_dir).g;
#elif SNELL_DISPERSION == 2
    snell_ior = u_ior_rgb.g;
    vec3 color = snell_glass_trace(exit_dir);
#else
    snell_ior = u_ior;
    vec3 color = snell_glass_trace(exit_dir);
#endif
    return color;
}

// A kernel that writes more than colour and direction defines SNELL_KERNEL_MAIN
// and a main of its own around snell_disp_trace (exact.frag).
#ifndef SNELL_KERNEL_MAIN
void main()
{
    highp vec3 exit_dir;
    vec3 color = snell_disp_trace(exit_dir);
    snell_write(color, exit_dir);
}
#endif
