/* SPDX-License-Identifier: MIT */
/* env.c — environments: the built-in procedural sky/floor, six face images or
 * one equirectangular image, all turned into six RGBA8 faces kept on the CPU
 * (so references sample exactly the GPU's texels) and a GL cubemap. */
#include "frame/env.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"

#include <math.h>
#include <string.h>

#define ENV_DEFAULT_SIZE 512
#define ENV_MAX_SIZE 4096

/* GL cube face selection (OpenGL ES 3.0 spec table 3.21, Unger 2.2.2 table 1).
 * Ties between axes go to X, then Y, as Mesa does. */
void snell__cube_coords(const double d[3], int *face, double *s, double *t)
{
    double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]), sc, tc, ma;
    if (ax >= ay && ax >= az) {
        ma = ax;
        *face = d[0] >= 0 ? 0 : 1;
        sc = d[0] >= 0 ? -d[2] : d[2];
        tc = -d[1];
    } else if (ay >= az) {
        ma = ay;
        *face = d[1] >= 0 ? 2 : 3;
        sc = d[0];
        tc = d[1] >= 0 ? d[2] : -d[2];
    } else {
        ma = az;
        *face = d[2] >= 0 ? 4 : 5;
        sc = d[2] >= 0 ? d[0] : -d[0];
        tc = -d[1];
    }
    if (ma <= 0.0) ma = 1.0;
    *s = 0.5 * (sc / ma + 1.0);
    *t = 0.5 * (tc / ma + 1.0);
}

void snell__cube_dir(int face, double s, double t, double d[3])
{
    double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0, len;
    switch (face) {
    case 0: d[0] = 1; d[1] = -tc; d[2] = -sc; break;
    case 1: d[0] = -1; d[1] = -tc; d[2] = sc; break;
    case 2: d[0] = sc; d[1] = 1; d[2] = tc; break;
    case 3: d[0] = sc; d[1] = -1; d[2] = -tc; break;
    case 4: d[0] = sc; d[1] = -tc; d[2] = 1; break;
    default: d[0] = -sc; d[1] = -tc; d[2] = -1; break;
    }
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    d[0] /= len; d[1] /= len; d[2] /= len;
}

/* ---------------------------------------------------------------- procedural */

static double clamp01(double v) { return v < 0 ? 0 : v > 1 ? 1 : v; }
static double mixd(double a, double b, double t) { return a + (b - a) * t; }

/* The built-in world: a blue sky gradient with a sun, over an infinite checkered
 * floor one unit below the origin. The floor's colours differ by side (red-ish
 * towards +X, blue-ish towards -X, and a yellow band towards -Z) so that the
 * flip and bend of an image seen through glass are unambiguous. Distance fog
 * blends the floor into the horizon colour to keep it alias-free. */
static void procedural_radiance(const double d[3], double rgb[3])
{
    static const double sun[3] = {0.48, 0.55, -0.683}; /* roughly unit, high on the -Z side */
    const double horizon[3] = {0.88, 0.90, 0.95};
    int k;
    if (d[1] >= 0.0) {
        const double zenith[3] = {0.18, 0.38, 0.78};
        double h = pow(clamp01(d[1]), 0.6);
        double cs = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
        double glow = pow(clamp01(cs), 64.0) * 0.45, disc = cs > 0.9985 ? 1.0 : 0.0;
        for (k = 0; k < 3; k++) rgb[k] = mixd(horizon[k], zenith[k], h);
        rgb[0] += glow + disc;
        rgb[1] += glow * 0.9 + disc;
        rgb[2] += glow * 0.7 + disc;
    } else {
        double dist = 1.0 / -d[1]; /* floor plane y = -1 */
        double x = d[0] * dist, z = d[2] * dist;
        int cx = (int)floor(x * 1.0), cz = (int)floor(z * 1.0);
        int dark = (cx + cz) & 1;
        double fog = 1.0 - exp(-dist * 0.06);
        double light[3] = {0.92, 0.90, 0.85}, col[3];
        if (x > 0) { col[0] = 0.75; col[1] = 0.18; col[2] = 0.15; }       /* red side */
        else { col[0] = 0.12; col[1] = 0.25; col[2] = 0.70; }             /* blue side */
        if (z < 0 && fabs(x) < 1.0) { col[0] = 0.90; col[1] = 0.75; col[2] = 0.10; } /* yellow lane */
        for (k = 0; k < 3; k++) rgb[k] = mixd(dark ? col[k] : light[k], horizon[k] * 0.9, fog);
    }
    for (k = 0; k < 3; k++) rgb[k] = clamp01(rgb[k]);
}

void snell_env_procedural_radiance(const double dir[3], double rgb[3])
{
    double len, d[3];
    if (!rgb) return;
    len = dir ? sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) : 0.0;
    if (!(len > 0.0) || !isfinite(len)) {
        rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    d[0] = dir[0] / len; d[1] = dir[1] / len; d[2] = dir[2] / len;
    procedural_radiance(d, rgb);
}

static uint8_t to_u8(double v) { return (uint8_t)(clamp01(v) * 255.0 + 0.5); }

/* Texel centres supersampled 3x3 so the checker edges are antialiased. */
static void fill_procedural(snell_env *env)
{
    int f, x, y, i, j, n = env->size;
    for (f = 0; f < 6; f++)
        for (y = 0; y < n; y++)
            for (x = 0; x < n; x++) {
                double acc[3] = {0, 0, 0}, d[3], c[3];
                uint8_t *px = env->faces[f] + 4 * ((size_t)y * n + x);
                for (j = 0; j < 3; j++)
                    for (i = 0; i < 3; i++) {
                        snell__cube_dir(f, (x + (i + 0.5) / 3.0) / n, (y + (j + 0.5) / 3.0) / n, d);
                        procedural_radiance(d, c);
                        acc[0] += c[0]; acc[1] += c[1]; acc[2] += c[2];
                    }
                px[0] = to_u8(acc[0] / 9); px[1] = to_u8(acc[1] / 9); px[2] = to_u8(acc[2] / 9); px[3] = 255;
            }
}

/* ------------------------------------------------------------------ images */

/* snell_image_read reports on the thread-local slot; move it to the context. */
static snell_status image_failure(snell_ctx *ctx, snell_status st)
{
    if (ctx) snell__fail(ctx, st, "%s", snell_last_error(NULL));
    return st;
}

static snell_status load_faces(snell_ctx *ctx, snell_env *env, const char *const paths[6])
{
    int f, w, h;
    for (f = 0; f < 6; f++) {
        uint8_t *img = NULL;
        snell_status st;
        if (!paths[f]) return snell__fail(ctx, SNELL_E_INVALID_ARG, "environment face %d has no path", f);
        st = snell__image_read_budget(paths[f], snell__ctx_budget(ctx), &w, &h, &img);
        if (st != SNELL_OK) return image_failure(ctx, st);
        if (w != h || (f > 0 && w != env->size) || w > ENV_MAX_SIZE) {
            snell_image_free(img);
            return snell__fail(ctx, SNELL_E_INVALID_ARG,
                               "cube face \"%s\" is %dx%d: faces must be square, equal and at most %d",
                               paths[f], w, h, ENV_MAX_SIZE);
        }
        if (f == 0) {
            int k;
            env->size = w;
            for (k = 0; k < 6; k++) {
                env->faces[k] = (uint8_t *)snell__malloc(&env->alloc, (size_t)w * w * 4);
                if (!env->faces[k]) {
                    snell_image_free(img);
                    return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for %d^2 cube faces", w);
                }
            }
        }
        memcpy(env->faces[f], img, (size_t)w * w * 4);
        snell_image_free(img);
    }
    return SNELL_OK;
}

/* Bilinear lookup in a lat-long image, longitude wrapping, latitude clamped.
 * Direction (0,0,-1) maps to the image centre, +Y to the top row. */
static void equirect_sample(const uint8_t *img, int w, int h, const double d[3], double rgb[3])
{
    double u = (atan2(d[0], -d[2]) / (2.0 * SNELL_PI) + 0.5) * w - 0.5;
    double v = (acos(d[1] < -1 ? -1 : d[1] > 1 ? 1 : d[1]) / SNELL_PI) * h - 0.5;
    int x0 = (int)floor(u), y0 = (int)floor(v), k, i;
    double fx = u - x0, fy = v - y0;
    for (k = 0; k < 3; k++) rgb[k] = 0;
    for (i = 0; i < 4; i++) {
        int x = x0 + (i & 1), y = y0 + (i >> 1);
        double wgt = ((i & 1) ? fx : 1 - fx) * ((i >> 1) ? fy : 1 - fy);
        x = ((x % w) + w) % w;
        y = y < 0 ? 0 : y >= h ? h - 1 : y;
        for (k = 0; k < 3; k++) rgb[k] += wgt * img[4 * ((size_t)y * w + x) + k] / 255.0;
    }
}

/* Resamples a lat-long RGBA8 image into the six faces. */
static snell_status equirect_to_faces(snell_ctx *ctx, snell_env *env, const uint8_t *img, int w, int h)
{
    int f, x, y;
    for (f = 0; f < 6; f++) {
        env->faces[f] = (uint8_t *)snell__malloc(&env->alloc, (size_t)env->size * env->size * 4);
        if (!env->faces[f]) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for cube faces");
        for (y = 0; y < env->size; y++)
            for (x = 0; x < env->size; x++) {
                double d[3], c[3];
                uint8_t *px = env->faces[f] + 4 * ((size_t)y * env->size + x);
                snell__cube_dir(f, (x + 0.5) / env->size, (y + 0.5) / env->size, d);
                equirect_sample(img, w, h, d, c);
                px[0] = to_u8(c[0]); px[1] = to_u8(c[1]); px[2] = to_u8(c[2]); px[3] = 255;
            }
    }
    return SNELL_OK;
}

static snell_status load_equirect(snell_ctx *ctx, snell_env *env, const snell_env_desc *d)
{
    int w, h;
    uint8_t *img = NULL;
    snell_status st;
    if (!d->equirect_path) {
        if (!d->equirect_rgba)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "equirectangular environment needs a path or pixels");
        /* the limits of a decoded image (snell_image_read) */
        if (d->equirect_width <= 0 || d->equirect_height <= 0 || d->equirect_width > 16384 ||
            d->equirect_height > 16384 || (size_t)d->equirect_width * (size_t)d->equirect_height > ((size_t)1 << 25))
            return snell__fail(ctx, SNELL_E_LIMIT,
                               "equirectangular pixels %dx%d: each side 1..16384 and at most 2^25 pixels",
                               d->equirect_width, d->equirect_height);
        return equirect_to_faces(ctx, env, d->equirect_rgba, d->equirect_width, d->equirect_height);
    }
    st = snell__image_read_budget(d->equirect_path, snell__ctx_budget(ctx), &w, &h, &img);
    if (st != SNELL_OK) return image_failure(ctx, st);
    st = equirect_to_faces(ctx, env, img, w, h);
    snell_image_free(img);
    return st;
}

/* -------------------------------------------------------------------- GL */

static snell_status upload(snell_ctx *ctx, snell_env *env)
{
    int f;
    GLint prev_tex = 0;
    snell__pixel_store unpack;
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &prev_tex);
    /* From client memory, tightly packed, whatever pixel buffer or unpack state the host has set. */
    snell__pixel_unpack_begin(&unpack, 4);
    glGenTextures(1, &env->texture);
    glBindTexture(GL_TEXTURE_CUBE_MAP, env->texture);
    for (f = 0; f < 6; f++)
        glTexImage2D((GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_RGBA8, env->size, env->size, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, env->faces[f]);
    /* GL_LINEAR without mipmaps: the CPU references reproduce this filter exactly. */
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_CUBE_MAP, (GLuint)prev_tex);
    snell__pixel_unpack_end(&unpack);
    if (glGetError() != GL_NO_ERROR)
        return snell__fail(ctx, SNELL_E_GL, "GL error creating a %d^2 cubemap", env->size);
    return SNELL_OK;
}

unsigned snell__cube_texture_create(int size, int filter)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, size, size);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return tex;
}

/* The host's cube map, borrowed: a texture of this context bound as a cube map without error. */
static snell_status borrow(snell_ctx *ctx, snell_env *env, const snell_env_desc *d)
{
    GLint prev = 0;
    GLenum err;
    if (!ctx || !d->gl_texture || !glIsTexture(d->gl_texture) || !d->face_size)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "SNELL_ENV_GL_TEXTURE: a context, gl_texture (a texture of it, "
                           "%u given) and its face_size are required", d->gl_texture);
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &prev);
    glBindTexture(GL_TEXTURE_CUBE_MAP, d->gl_texture);
    err = glGetError();
    glBindTexture(GL_TEXTURE_CUBE_MAP, (GLuint)prev);
    if (err != GL_NO_ERROR)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "SNELL_ENV_GL_TEXTURE: texture %u is not a cube map",
                           d->gl_texture);
    env->texture = d->gl_texture;
    env->borrowed = 1;
    return SNELL_OK;
}

snell_status snell_env_create(snell_ctx *ctx, const snell_env_desc *desc, snell_env **out)
{
    snell_env_desc d;
    snell_env *env;
    snell_status st = SNELL_OK;
    unsigned host_errors = 0;
    int f;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_env_create: out is NULL");
    *out = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if (d.face_size < 0 || d.face_size > ENV_MAX_SIZE)
        return snell__fail(ctx, SNELL_E_LIMIT, "environment face size %d outside 1..%d", d.face_size, ENV_MAX_SIZE);
    if (ctx && (st = snell__ctx_check_current(ctx, "snell_env_create")) != SNELL_OK) return st;
    if (ctx && (st = snell__ctx_limit(ctx, SNELL__LIM_CUBE, d.face_size, "environment face size")) != SNELL_OK) return st;
    env = (snell_env *)snell__calloc(snell__ctx_alloc(ctx), 1, sizeof *env);
    if (!env) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    env->ctx = ctx;
    snell__ctx_retain(ctx); /* released by snell_env_destroy */
    env->alloc = *snell__ctx_alloc(ctx);
    env->size = d.face_size ? d.face_size : ENV_DEFAULT_SIZE;
    if (ctx) host_errors = snell__gl_errors_take(); /* the host's wait outside (core/glstate.h) */
    switch (d.source) {
    case SNELL_ENV_PROCEDURAL:
        for (f = 0; f < 6 && st == SNELL_OK; f++) {
            env->faces[f] = (uint8_t *)snell__malloc(&env->alloc, (size_t)env->size * env->size * 4);
            if (!env->faces[f]) st = snell__fail(ctx, SNELL_E_NOMEM, "out of memory for cube faces");
        }
        if (st == SNELL_OK) fill_procedural(env);
        break;
    case SNELL_ENV_FACES: st = load_faces(ctx, env, d.face_paths); break;
    case SNELL_ENV_EQUIRECT: st = load_equirect(ctx, env, &d); break;
    case SNELL_ENV_GL_TEXTURE: st = borrow(ctx, env, &d); break;
    default: st = snell__fail(ctx, SNELL_E_INVALID_ARG, "unknown environment source %d", (int)d.source);
    }
    if (st == SNELL_OK && ctx && !env->borrowed) st = upload(ctx, env);
    if (st != SNELL_OK) snell_env_destroy(env);
    else *out = env;
    if (ctx) snell__gl_errors_give(host_errors);
    return st;
}

void snell_env_destroy(snell_env *env)
{
    int f;
    snell_alloc al;
    if (!env) return;
    if (env->texture) {
        /* In its context; after snell_ctx_destroy the texture is gone with it. */
        snell__gl_scope sc;
        if (snell__gl_scope_enter(env->ctx, &sc)) {
            if (!env->borrowed) glDeleteTextures(1, &env->texture);
            if (env->paraboloid) glDeleteTextures(1, &env->paraboloid);
        }
        snell__gl_scope_leave(&sc);
    }
    snell__ctx_release(env->ctx);
    al = env->alloc;
    for (f = 0; f < 6; f++) snell__free(&al, env->faces[f]);
    snell__free(&al, env);
}

int snell_env_face_size(const snell_env *env) { return env ? env->size : 0; }

void snell_env_sample_d(const snell_env *env, const double dir[3], double rgb[3])
{
    int face, x0, y0, i, k, n;
    double s, t, u, v, fx, fy;
    const uint8_t *tex;
    if (!rgb) return;
    /* No environment, or no direction to look in: black, like the other getters' zero. */
    if (!env || !env->faces[0] || !dir || !isfinite(dir[0]) || !isfinite(dir[1]) || !isfinite(dir[2])) {
        rgb[0] = rgb[1] = rgb[2] = 0.0;
        return;
    }
    n = env->size;
    snell__cube_coords(dir, &face, &s, &t);
    tex = env->faces[face];
    /* GL_LINEAR: texel centres at (i + 0.5) / n, CLAMP_TO_EDGE within the face. */
    u = s * n - 0.5;
    v = t * n - 0.5;
    x0 = (int)floor(u);
    y0 = (int)floor(v);
    fx = u - x0;
    fy = v - y0;
    for (k = 0; k < 3; k++) rgb[k] = 0.0;
    for (i = 0; i < 4; i++) {
        int x = x0 + (i & 1), y = y0 + (i >> 1);
        double w = ((i & 1) ? fx : 1.0 - fx) * ((i >> 1) ? fy : 1.0 - fy);
        x = x < 0 ? 0 : x >= n ? n - 1 : x;
        y = y < 0 ? 0 : y >= n ? n - 1 : y;
        for (k = 0; k < 3; k++) rgb[k] += w * tex[4 * ((size_t)y * n + x) + k] * (1.0 / 255.0);
    }
}

void snell_env_sample(const snell_env *env, const float dir[3], float rgb[3])
{
    double d[3], c[3];
    if (!rgb) return;
    if (!dir) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    d[0] = dir[0]; d[1] = dir[1]; d[2] = dir[2];
    snell_env_sample_d(env, d, c);
    rgb[0] = (float)c[0]; rgb[1] = (float)c[1]; rgb[2] = (float)c[2];
}
