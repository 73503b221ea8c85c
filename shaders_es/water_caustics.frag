// water_caustics.frag - a triangle of the refracted surface grid on the
// floor's light map (water_caustics.vert): its irradiance is the light's
// (directional: per unit area across the beam; spot: its intensity per unit
// solid angle, a beam area on the plane at distance 1 being cos^3 of its
// solid angle) times the ratio of the triangle's area in the beam to its
// area on the floor (both positions are affine over the triangle, so their
// screen derivatives are exact: Wallace's dFdx/dFdy), times what the water
// lets through (v_carry). Added: folded triangles sum, as the light does.
precision highp float;

in highp vec2 v_beam;
in vec3 v_carry;

uniform vec3 u_color;        // the light's colour
uniform highp int u_spot;
uniform float u_cos_cone;    // spot: cosine of its half angle
uniform float u_texel_area;  // one texel of the map on the floor, world units^2

layout(location = 0) out vec4 o_color;

void main()
{
    highp vec2 bx = dFdx(v_beam), by = dFdy(v_beam);
    float ratio = abs(bx.x * by.y - bx.y * by.x) / u_texel_area;
    vec3 e = u_color * v_carry * ratio;
    if (u_spot == 1) {
        float c = inversesqrt(1.0 + dot(v_beam, v_beam)); // cosine off the axis
        e *= c >= u_cos_cone ? c * c * c : 0.0;
    }
    o_color = vec4(e, (e.r + e.g + e.b) / 3.0);
}
