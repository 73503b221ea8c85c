// SPDX-License-Identifier: MIT
// env.glsl - the environment's radiance along a direction (Unger 2.2.2: a
// cubemap indexed by direction only). Every kernel looks it up through snell_env,
// so another representation changes one place. SNELL_ENV_DUAL_PARABOLOID: two
// paraboloid maps (Heidrich and Seidel 1998) in a 2D array texture,
// st = d.xy / (1 + |d.z|), rim SNELL_DP_MARGIN texels inside the edge. Why that
// projection and its margin: docs/ARCHITECTURE.md, "Design notes by file".

#define SNELL_DP_MARGIN 2.0

// The texture coordinate (xy, layer in z) of direction dir in size^2 maps.
highp vec3 snell_dp_coords(highp vec3 dir, highp float size)
{
    highp vec3 d = normalize(dir);
    highp vec2 st = d.xy / (1.0 + abs(d.z));
    highp float scale = 0.5 * (size - 2.0 * SNELL_DP_MARGIN) / size;
    return vec3(0.5 + scale * st, d.z < 0.0 ? 1.0 : 0.0);
}

// The unit direction of texture coordinate uv in map layer (0: +Z, 1: -Z);
// the inverse of snell_dp_coords, continued past the rim.
highp vec3 snell_dp_dir(highp vec2 uv, highp float layer, highp float size)
{
    highp float scale = 0.5 * (size - 2.0 * SNELL_DP_MARGIN) / size;
    highp vec2 st = (uv - 0.5) / scale;
    highp float r2 = dot(st, st);
    highp float z = (1.0 - r2) / (1.0 + r2);
    return vec3(2.0 * st / (1.0 + r2), layer > 0.5 ? -z : z);
}

// SNELL_ENV_NEAREST (a kernel's define): snell_env_nearest looks the same
// environment up through a nearest-texel sampler object on its own unit
// (u_env_nearest, bound by the kernel: methods/layered.c), for light of
// small weight whose filtering costs more than it shows (layered.c: the
// exit's internal reflection).
#ifdef SNELL_ENV_DUAL_PARABOLOID
uniform highp sampler2DArray u_env;
#ifdef SNELL_ENV_NEAREST
uniform highp sampler2DArray u_env_nearest;
#endif

vec3 snell_env_from(highp sampler2DArray s, vec3 dir)
{
    return texture(s, snell_dp_coords(dir, float(textureSize(s, 0).x))).rgb;
}
#else
uniform samplerCube u_env;
#ifdef SNELL_ENV_NEAREST
uniform samplerCube u_env_nearest;
#endif

vec3 snell_env_from(samplerCube s, vec3 dir)
{
    return texture(s, dir).rgb;
}
#endif

// SNELL_PREMULTIPLIED (premultiplied alpha output, common/output.glsl):
// the kernel runs twice, with the environment 0 and 1 everywhere.
#ifdef SNELL_PREMULTIPLIED
float snell_env_level;
#endif

vec3 snell_env(vec3 dir)
{
#ifdef SNELL_PREMULTIPLIED
    return vec3(snell_env_level);
#else
    return snell_env_from(u_env, dir);
#endif
}

#ifdef SNELL_ENV_NEAREST
vec3 snell_env_nearest(vec3 dir)
{
#ifdef SNELL_PREMULTIPLIED
    return vec3(snell_env_level);
#else
    return snell_env_from(u_env_nearest, dir);
#endif
}
#endif
