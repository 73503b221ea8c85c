// SPDX-License-Identifier: MIT
// water_caustics.frag - a triangle of the refracted surface grid on the
// floor's light map (water_caustics.vert): the light's irradiance times the ratio
// of the triangle's beam area to its floor area (exact screen derivatives:
// Wallace's dFdx/dFdy) times v_carry; added, so folds sum. u_columns: shadowed
// by the opaque objects' columns, COLUMN_STEPS samples a stretch. More:
// docs/ARCHITECTURE.md, "Design notes by file".
precision highp float;

in highp vec2 v_beam;
in vec3 v_carry;
in highp vec3 v_surface, v_floor, v_light;

uniform vec3 u_color;        // the light's colour
uniform highp int u_spot;
uniform float u_cos_cone;    // spot: cosine of its half angle
uniform float u_texel_area;  // one texel of the map on the floor, world units^2
uniform bool u_columns;      // opaque objects shadow the floor
uniform highp sampler2D u_column_high, u_column_low; // their highest and lowest surfaces' depth over the floor
uniform highp float u_column_top, u_column_range;    // depth 0 at y = top, 1 at y = top - range
uniform highp float u_water_half;

uniform highp float u_water_rim;
uniform highp vec3 u_pos;        // a spot light's position

#define COLUMN_STEPS 32

// Distance along r (unit) from p, inside the box, to its walls (x or z); the
// caller compares it with the distance to the rim's plane.
float to_walls(vec3 p, vec3 r)
{
    float s = 3.0e38;
    if (r.x != 0.0) s = min(s, ((r.x > 0.0 ? u_water_half : -u_water_half) - p.x) / r.x);
    if (r.z != 0.0) s = min(s, ((r.z > 0.0 ? u_water_half : -u_water_half) - p.z) / r.z);
    return s;
}

// Lit where the way back to the light leaves the box over the rim (or the
// light is in it): per fragment, so the rim's shadow is as sharp as the map.
bool over_rim(highp vec3 p, highp vec3 back)
{
    highp float reach = u_spot == 1 ? length(u_pos - p) : 3.0e38;
    return min((u_water_rim - p.y) / max(back.y, 1e-30), reach) <= to_walls(p, back);
}

// Whether a point of the segment a..b lies inside a column.
bool shadowed(highp vec3 a, highp vec3 b)
{
    ivec2 size = textureSize(u_column_high, 0);
    for (int k = 0; k < COLUMN_STEPS; k++) {
        highp vec3 q = mix(a, b, (float(k) + 0.5) / float(COLUMN_STEPS));
        highp vec2 uv = q.xz / (2.0 * u_water_half) + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        ivec2 t = ivec2(uv * vec2(size));
        highp float high = u_column_top - texelFetch(u_column_high, t, 0).r * u_column_range;
        highp float low = u_column_top - texelFetch(u_column_low, t, 0).r * u_column_range;
        if (q.y <= high && q.y >= low) return true;
    }
    return false;
}

layout(location = 0) out vec4 o_color;

void main()
{
    highp vec2 bx = dFdx(v_beam), by = dFdy(v_beam);
    float ratio = abs(bx.x * by.y - bx.y * by.x) / u_texel_area;
    vec3 e = over_rim(v_surface, normalize(v_light)) ? u_color * v_carry * ratio : vec3(0.0);
    if (u_columns) {
        // back to the light up to the columns' top (v_light.y > 0 where lit)
        highp vec3 up = v_surface + v_light * max((u_column_top - v_surface.y) / max(v_light.y, 1e-6), 0.0);
        if (shadowed(v_floor, v_surface) || shadowed(v_surface, up)) e = vec3(0.0);
    }
    if (u_spot == 1) {
        float c = inversesqrt(1.0 + dot(v_beam, v_beam)); // cosine off the axis
        e *= c >= u_cos_cone ? c * c * c : 0.0;
    }
    o_color = vec4(e, (e.r + e.g + e.b) / 3.0);
#ifdef SNELL_LIGHT_RANGE
    // an RGB10_A2 map (core/glstate.h): cells overlap where the surface folds
    // the light, so their sum is rounded at random as caustics_splat.frag's
    highp uint h = (uint(gl_FragCoord.x) * 2654435761u ^ uint(gl_FragCoord.y) * 2246822519u ^
              floatBitsToUint(v_beam.x)) * 3266489917u;
    h ^= h >> 15;
    o_color = (floor(o_color * (1023.0 / SNELL_LIGHT_RANGE) + float(h >> 8) / 16777216.0) + 0.25) / 1023.0;
#endif
}
