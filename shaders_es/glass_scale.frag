// glass_scale.frag - an object's colour at full resolution from its glass
// shaded at a resolution scale (render/glass_scale.c), drawn as any kernel
// is (forward on its faces, or on the frame's G-buffer), so which pixels are
// glass and their depth are the full raster's. It reads the small target's
// colour and window depth (1.0 where the object did not cover the texel):
// bilinear among the four nearest texels that the object covers, so no
// background from outside the silhouette (the small target holds black
// there). Where it covers none of the four (a sliver thinner than a texel),
// the nearest covered texel of the 4x4 around. (A depth weight as well, joint
// bilateral upsampling with the texels within 2% of the pixel's view depth,
// changed no glass PSNR against FULL on the bunny by 0.01 dB at scales 2 and
// 4: left out.)
precision highp float;

#include "common/output.glsl"
#include "common/surface.glsl"

uniform highp sampler2D u_small_color; // the small target's colour (RGBA8)
uniform highp sampler2D u_small_depth; // ... and window depth, 1.0 = not covered
uniform highp vec2 u_ratio;            // its texels per full-resolution pixel
uniform highp ivec2 u_max;             // its last texel used (the grid's size - 1)

bool covered(ivec2 t) { return texelFetch(u_small_depth, t, 0).r < 1.0; }

void main()
{
    highp vec3 pos, normal;
    snell_surface(pos, normal); // screen space: other objects' pixels discarded, depth written if needed
    highp vec2 q = gl_FragCoord.xy * u_ratio - 0.5;
    highp vec2 f = fract(q);
    ivec2 b = ivec2(floor(q));
    highp vec4 sum = vec4(0.0);
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < 2; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
            if (covered(t)) sum += w * vec4(texelFetch(u_small_color, t, 0).rgb, 1.0);
        }
    }
    if (sum.a > 0.0) {
        o_color = vec4(sum.rgb / sum.a, 1.0);
        return;
    }
    highp float best = 1e9;
    vec3 c = vec3(0.0); // nothing of the object within two texels (a feature the grid missed): black
    for (int j = -1; j < 3; j++) {
        for (int i = -1; i < 3; i++) {
            ivec2 t = clamp(b + ivec2(i, j), ivec2(0), u_max);
            highp vec2 d = vec2(b + ivec2(i, j)) - q;
            if (covered(t) && dot(d, d) < best) {
                best = dot(d, d);
                c = texelFetch(u_small_color, t, 0).rgb;
            }
        }
    }
    o_color = vec4(c, 1.0);
}
