/* SPDX-License-Identifier: MIT */
/* env_dynamic.c — dynamic environment (Unger 4.1: rendered from the centre with
 * the background and the other objects, at a lower resolution). Re-rendered only
 * when an opaque object, its model or colour, the glass centre, the static
 * environment or the caustics stage's maps changed, not every frame as in the
 * seed. With the dual-paraboloid look-up, two maps from that cube or rendered
 * straight (SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT). Lit opaque objects are
 * drawn lit here too, so the glass shows them as the view does. */
#include "render/env_dynamic.h"
#include "frame/env.h"
#include "frame/pass.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "frame/ndcube.h"
#include "render/caustics.h"

#include <math.h>
#include <string.h>

static const float k_identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

void snell__env_dynamic_destroy(snell_ctx *ctx, snell__env_dynamic *d)
{
    int i;
    if (d->views)
        for (i = 0; i < SNELL_MAX_GLASS; i++) {
            if (d->views[i].texture) glDeleteTextures(1, &d->views[i].texture);
            if (d->views[i].paraboloid) glDeleteTextures(1, &d->views[i].paraboloid);
        }
    snell__free(&ctx->alloc, d->views);
    if (d->fbo) glDeleteFramebuffers(1, &d->fbo);
    if (d->depth_rb) glDeleteRenderbuffers(1, &d->depth_rb);
    if (d->dp_depth_rb) glDeleteRenderbuffers(1, &d->dp_depth_rb);
    memset(d, 0, sizeof *d);
}

/* Which lighting the opaque objects are drawn with: 0 from above, else the
 * caustics stage's maps as last made. */
static unsigned lighting(const snell__caustics *lit) { return lit ? lit->made : 0u; }

/* Did anything the cubemap shows change since it was rendered? */
static int changed(const snell__env_view *v, const snell_env *env, const snell_opaque *list, int count,
                   const float centre[3], int size, const snell__caustics *lit)
{
    int i;
    /* a host's cube (SNELL_ENV_GL_TEXTURE) may have changed since the last frame */
    if (!v->valid || v->size != size || v->env != env || env->borrowed || v->count != count ||
        v->lit != lighting(lit) ||
        memcmp(v->centre, centre, sizeof v->centre))
        return 1;
    for (i = 0; i < count; i++) {
        const snell_opaque *o = &list[i];
        if (v->mesh[i] != o->mesh || v->version[i] != o->mesh->version ||
            memcmp(v->model[i], o->model ? o->model : k_identity, sizeof v->model[i]) ||
            memcmp(v->color[i], o->color, sizeof v->color[i]))
            return 1;
    }
    return 0;
}

static void remember(snell__env_view *v, const snell_env *env, const snell_opaque *list, int count,
                     const float centre[3], const snell__caustics *lit)
{
    int i;
    v->valid = 1;
    v->env = env;
    v->lit = lighting(lit);
    memcpy(v->centre, centre, sizeof v->centre);
    v->count = count;
    for (i = 0; i < count; i++) {
        v->mesh[i] = list[i].mesh;
        v->version[i] = list[i].mesh->version;
        memcpy(v->model[i], list[i].model ? list[i].model : k_identity, sizeof v->model[i]);
        memcpy(v->color[i], list[i].color, sizeof v->color[i]);
    }
}

/* The view's cube, or with dp its dual-paraboloid maps, made from the cube
 * once per re-render (one pass per map). */
static snell_status paraboloid_of(snell_ctx *ctx, snell__env_view *v, snell__paraboloid_gen *dp, unsigned *texture,
                                  snell_object_stats *stats)
{
    snell_status st;
    *texture = v->texture;
    if (!dp) return SNELL_OK;
    if (!v->paraboloid_valid) {
        st = snell__paraboloid_from_cube(ctx, dp, v->texture, snell__paraboloid_size(v->size), &v->paraboloid,
                                         &v->paraboloid_size);
        if (st != SNELL_OK) return st;
        v->paraboloid_valid = 1;
        stats->passes += 2;
    }
    *texture = v->paraboloid;
    return SNELL_OK;
}

/* The two maps rendered straight from centre (no cube): per map the opaque
 * objects projected per vertex, then the static environment where nothing
 * was drawn (its maps' texels from its cube). Maps of snell__paraboloid_size(size). */
static snell_status render_paraboloid_views(snell_ctx *ctx, snell__env_dynamic *d, snell__composite *comp,
                                            snell__paraboloid_gen *dp, snell__env_view *v, const snell_env *env,
                                            const snell_opaque *list, int count, const float centre[3],
                                            float z_near, float z_far, int size, const snell__caustics *lit,
                                            snell_object_stats *stats)
{
    snell__pass pass;
    snell_status st = SNELL_OK;
    int n = snell__paraboloid_size(size), layer;
    if (!d->fbo) glGenFramebuffers(1, &d->fbo);
    if (!d->dp_depth_rb) glGenRenderbuffers(1, &d->dp_depth_rb);
    if (d->dp_depth_size != n) {
        glBindRenderbuffer(GL_RENDERBUFFER, d->dp_depth_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, n, n);
        d->dp_depth_size = n;
    }
    snell__paraboloid_texture(n, &v->paraboloid, &v->paraboloid_size);
    snell__pass_begin(&pass, d->fbo, n, n, 0, GL_LESS, 1.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, d->dp_depth_rb);
    for (layer = 0; layer < 2 && st == SNELL_OK; layer++) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, v->paraboloid, 0, layer);
        if (layer == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            st = snell__fail(ctx, SNELL_E_GL, "dynamic dual-paraboloid framebuffer incomplete");
            break;
        }
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        st = snell__composite_opaque_paraboloid(ctx, comp, list, count, centre, layer, n, z_near, z_far, lit);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        if (st == SNELL_OK) st = snell__paraboloid_draw_layer(ctx, dp, env->texture, layer, n);
        glDepthFunc(GL_LESS);
        stats->passes += 1 + (count > 0);
    }
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, 0);
    snell__pass_end(&pass);
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR)
        st = snell__fail(ctx, SNELL_E_GL, "GL error rendering dynamic dual-paraboloid maps");
    if (st == SNELL_OK) v->paraboloid_valid = 1;
    return st;
}

static snell_status make_targets(snell_ctx *ctx, snell__env_dynamic *d, snell__env_view *v, int size)
{
    if (!d->fbo) glGenFramebuffers(1, &d->fbo);
    if (!d->depth_rb) glGenRenderbuffers(1, &d->depth_rb);
    if (d->depth_size != size) {
        glBindRenderbuffer(GL_RENDERBUFFER, d->depth_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
        d->depth_size = size;
    }
    if (v->size != size) {
        if (v->texture) glDeleteTextures(1, &v->texture);
        v->texture = snell__cube_texture_create(size, GL_LINEAR);
        v->size = size;
        v->valid = 0;
    }
    return glGetError() == GL_NO_ERROR
               ? SNELL_OK
               : snell__fail(ctx, SNELL_E_GL, "cannot create a %dx%d dynamic environment", size, size);
}

snell_status snell__env_dynamic_update(snell_ctx *ctx, snell__env_dynamic *d, snell__composite *comp, int slot,
                                       const snell_env *env, const snell_opaque *list, int count,
                                       const float centre[3], float radius, int size, snell__paraboloid_gen *dp,
                                       int direct, const snell__caustics *lit, unsigned *texture,
                                       snell_object_stats *stats)
{
    snell__env_view *v;
    snell__pass pass;
    snell_status st = SNELL_OK;
    float z_near, z_far;
    int face;
    if (!size) {
        /* Unger 4.1: lower resolution than the static map; half of it, capped. */
        size = env->size / 2;
        if (size > 256) size = 256;
        if (size < 16) size = 16;
    }
    if (!d->views) {
        d->views = (snell__env_view *)snell__calloc(&ctx->alloc, SNELL_MAX_GLASS, sizeof *d->views);
        if (!d->views) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for dynamic environments");
    }
    v = &d->views[slot];
    /* A renderer's look-up is fixed at its creation, so a slot's view is
     * always made the same way: valid means its textures show what is
     * remembered, a cube (and maps made from it) or directly rendered maps. */
    if (!changed(v, env, list, count, centre, size, lit)) {
        stats->skipped |= SNELL_SKIP_ENV_UPDATE;
        return paraboloid_of(ctx, v, dp, texture, stats);
    }
    /* Seen from the glass centre: objects beyond the glass's own bounding
     * sphere matter; the near plane sits at 1% of its radius. */
    z_near = radius > 0.0f ? 0.01f * radius : 0.01f;
    z_far = 1e4f * z_near + 1000.0f;
    if (dp && direct) {
        st = render_paraboloid_views(ctx, d, comp, dp, v, env, list, count, centre, z_near, z_far, size, lit, stats);
        if (st != SNELL_OK) return st;
        remember(v, env, list, count, centre, lit);
        v->size = size;
        stats->env_updated = 1;
        *texture = v->paraboloid;
        return SNELL_OK;
    }
    if ((st = make_targets(ctx, d, v, size)) != SNELL_OK) return st;
    snell__pass_begin(&pass, d->fbo, size, size, 0, GL_LESS, 1.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, d->depth_rb);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_CUBE_MAP, env->texture);
    for (face = 0; face < 6 && st == SNELL_OK; face++) {
        mat4 vp, rot_vp;
        const float origin[3] = {0, 0, 0};
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                               v->texture, 0);
        if (face == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            st = snell__fail(ctx, SNELL_E_GL, "dynamic environment framebuffer incomplete");
            break;
        }
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        snell__cube_face_view_proj(face, centre, z_near, z_far, vp);
        st = snell__composite_opaque(ctx, comp, SNELL__OUT_COLOR, list, count, (const float *)vp, centre, NULL, lit);
        snell__cube_face_view_proj(face, origin, z_near, z_far, rot_vp);
        if (st == SNELL_OK) st = snell__composite_background(ctx, comp, SNELL__OUT_COLOR, (const float *)rot_vp);
        stats->passes += 1 + (count > 0);
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    snell__pass_end(&pass);
    if (st != SNELL_OK) return st;
    if (glGetError() != GL_NO_ERROR) return snell__fail(ctx, SNELL_E_GL, "GL error rendering a dynamic environment");
    remember(v, env, list, count, centre, lit);
    v->paraboloid_valid = 0;
    stats->env_updated = 1;
    return paraboloid_of(ctx, v, dp, texture, stats);
}
