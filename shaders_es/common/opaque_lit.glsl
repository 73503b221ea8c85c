// SPDX-License-Identifier: MIT
// opaque_lit.glsl - the irradiance of an opaque surface point under the
// frame's light (render/caustics.c): the direct light where the shadow map leaves
// it lit, plus the light through the glass from the light-space caustic map
// (Wyman & Davis 2006) over the texels whose receiver is this surface. One
// function for opaque objects seen directly and through glass, so that behind
// glass of index 1 they look the same. More: docs/ARCHITECTURE.md, "Design
// notes by file".
uniform highp vec3 u_light;          // the light's colour (directional: irradiance; spot: intensity)
uniform highp vec3 u_dir;            // directional: the unit direction it travels
uniform int u_spot;                  // 1: a spot light at u_pos, axis u_axis, cone cosine u_cos_cone
uniform highp vec3 u_pos, u_axis;
uniform highp float u_cos_cone;
uniform highp sampler2DShadow u_shadow;
uniform highp sampler2D u_recv_z;    // the opaque receivers' nearest depth per texel of the light frame
uniform highp sampler2D u_caustic;   // the light through glass on them (caustics_photon.vert, u_target 1)
uniform highp mat4 u_recv_vp;        // world -> the light frame's clip space (the shadow map's)
uniform highp vec4 u_recv_lin;       // near, far, 1 = perspective, texel side (world; spot: at distance 1)
uniform highp float u_bias;          // depth bias, shadow map units

highp float recv_lin(highp float z01)
{
    highp float n = u_recv_lin.x, f = u_recv_lin.y;
    return u_recv_lin.z > 0.5 ? n * f / (f - z01 * (f - n)) : n + z01 * (f - n);
}

highp vec3 light_frame(highp vec3 p)
{
    highp vec4 c = u_recv_vp * vec4(p, 1.0);
    return c.xyz / c.w * 0.5 + 0.5;
}

// The irradiance at p of outward unit normal n.
highp vec3 snell_lit_irradiance(highp vec3 p, highp vec3 n)
{
    highp vec3 l = u_dir;
    highp float fall = 1.0, cone = 1.0;
    if (u_spot == 1) {
        l = p - u_pos;
        fall = 1.0 / dot(l, l);
        l = normalize(l);
        cone = dot(l, u_axis) >= u_cos_cone ? 1.0 : 0.0;
    }
    highp float cosl = max(0.0, -dot(n, l));
    highp vec3 e = vec3(0.0);
    // a spot light's frame looks straight down: a point at or above its near
    // plane is outside it (no shadow map there): the direct light unshadowed, no caustic
    bool framed = u_recv_lin.z < 0.5 || u_pos.y - p.y > u_recv_lin.x;
    if (!framed) e = u_light * (fall * cone * cosl);
    if (cosl > 0.0 && framed) {
        highp vec3 s = light_frame(p);
        highp float lp = recv_lin(s.z), tw = u_recv_lin.w * (u_recv_lin.z > 0.5 ? lp : 1.0);
        // direct: the shadow map at the point moved half a texel along its
        // normal, its depth compared less a slope-scaled bias (the surface's
        // depth changes by tw tan(theta) over a texel, 1.5 of them for the 2 x 2
        // filter; tan at most 8) against self-shadowing: a normal move alone
        // leaves acne on walls at grazing light, and a larger move shifts the
        // shadow's edges (test_caustics_opaque; bench/notes/code.md, "opaque_lit.glsl")
        highp vec3 so = light_frame(p + n * 0.5 * tw);
        highp float n_ = u_recv_lin.x, f_ = u_recv_lin.y;
        highp float slope = 1.5 * tw * min(8.0, sqrt(max(0.0, 1.0 - cosl * cosl)) / cosl);
        slope *= u_recv_lin.z > 0.5 ? n_ * f_ / (lp * lp * (f_ - n_)) : 1.0 / (f_ - n_);
        e = u_light * (fall * cone * cosl) * texture(u_shadow, vec3(so.xy, so.z - u_bias - slope));
        // through glass: the caustic map's texels about the point on its own surface
        ivec2 size = textureSize(u_caustic, 0);
        highp vec2 t = s.xy * vec2(size) - 0.5;
        ivec2 b = ivec2(floor(t));
        highp vec2 f = t - floor(t);
        highp vec3 acc = vec3(0.0);
        highp float w = 0.0;
        for (int k = 0; k < 4; k++) {
            ivec2 o = ivec2(k & 1, k >> 1), q = clamp(b + o, ivec2(0), size - 1);
            highp float z = texelFetch(u_recv_z, q, 0).r;
            highp float wk = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
            if (z < 1.0 && abs(recv_lin(z) - lp) < 3.0 * tw) {
                acc += wk * texelFetch(u_caustic, q, 0).rgb;
                w += wk;
            }
        }
#ifdef SNELL_LIGHT_RANGE
        acc *= SNELL_LIGHT_RANGE; // an RGB10_A2 map holds irradiance / range (core/glstate.h)
        if (u_recv_lin.z > 0.5) acc *= u_recv_lin.y * u_recv_lin.y; // a spot's: at the far plane (caustics_photon.vert)
#endif
        if (w > 0.0) e += acc / w * (fall * cosl);
    }
    return e;
}
