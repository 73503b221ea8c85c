/* SPDX-License-Identifier: MIT */
/* caustics.c — the caustics stage (Wyman & Davis 2006, caustic maps; Unger
 * 3.5 names light refracted onto surfaces as beyond its scope): the receiver
 * plane's light map holds its irradiance in units of the light's colour, the
 * direct light where the shadow map leaves it lit (caustics_maps.c) plus the
 * photons through each glass object (caustics_photons.c), flux-correct as the
 * 2D lightmap's lines are (src/lm2d); the opaque objects are receivers too,
 * by a caustic map in the light frame. All are drawn lit in the view
 * (caustics_receiver.c); the maps are reused while light, glass, opaque
 * objects and receiver are still. */
#include "render/caustics_private.h"
#include "core/ctx.h"
#include "core/light_map.h"
#include "core/program.h"
#include "mesh/bvh_gpu.h"
#include "water/water_draw.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int finite3(const float v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

snell_status snell__caustics_validate(snell_ctx *ctx, const snell_frame_desc *fd)
{
    const snell_light *l = &fd->light;
    const snell_receiver *rc = &fd->receiver;
    int k;
    if ((int)l->type < SNELL_LIGHT_NONE || (int)l->type > SNELL_LIGHT_SPOT)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.type %d is not a snell_light_type", (int)l->type);
    if (l->type != SNELL_LIGHT_NONE) {
        if (!finite3(l->direction) || l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                                              l->direction[2] * l->direction[2] < 1e-12f)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.direction must be finite and not zero");
        for (k = 0; k < 3; k++)
            if (!isfinite(l->color[k]) || l->color[k] < 0.0f)
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.color[%d] %g: finite and >= 0", k, l->color[k]);
        if (l->photons < 16 || l->photons > 1024)
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.photons %d outside 16..1024", l->photons);
        if (l->type == SNELL_LIGHT_SPOT && !finite3(l->position))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.position must be finite");
        if (l->type == SNELL_LIGHT_SPOT && !(l->spot_angle > 0.0f && l->spot_angle <= 1.5f))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.spot_angle %g outside (0, 1.5] radians",
                               l->spot_angle);
    }
    if (!isfinite(rc->extent) || rc->extent < 0.0f)
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "receiver.extent %g: finite and >= 0 (0 = none)", rc->extent);
    if (rc->extent > 0.0f) {
        if (!isfinite(rc->height) || !isfinite(rc->center[0]) || !isfinite(rc->center[1]))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "receiver.height and center must be finite");
        for (k = 0; k < 3; k++)
            if (!(rc->albedo[k] >= 0.0f && rc->albedo[k] <= 1.0f))
                return snell__fail(ctx, SNELL_E_INVALID_ARG, "receiver.albedo[%d] %g outside 0..1", k, rc->albedo[k]);
    }
    if ((rc->extent > 0.0f || (l->type != SNELL_LIGHT_NONE && fd->opaque_count > 0)) &&
        (rc->map_size < 16 || rc->map_size > 2048))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "receiver.map_size %d outside 16..2048", rc->map_size);
    return SNELL_OK;
}

int snell__caustics_wanted(const snell_frame_desc *fd, char *why, size_t n)
{
    if (fd->light.type == SNELL_LIGHT_NONE) {
        snell__why(why, n, "no light");
        return 0;
    }
    if (fd->receiver.extent <= 0.0f && fd->opaque_count == 0 && !fd->water) {
        snell__why(why, n, "no receiver");
        return 0;
    }
    return 1;
}

/* A glass object that changes light: not IOR 1 without absorption or tint
 * (scene.c skips those). A thin wall casts too: its photons go straight on
 * through each wall as a slab (caustics_photon.vert). */
int snell__caustics_casts(const snell__object *o)
{
    const snell_glass_material *m = &o->glass->material;
    int tinted = m->tint[0] != 1.0f || m->tint[1] != 1.0f || m->tint[2] != 1.0f;
    return m->ior != 1.0f || o->glass->absorbs || tinted;
}

/* --- the reuse key: everything the light map depends on ------------------ */
static void put(float *k, int *n, const void *v, size_t bytes)
{
    if ((size_t)*n * sizeof(float) + bytes > SNELL__CAUSTICS_KEY * sizeof(float)) return;
    memcpy(k + *n, v, bytes);
    *n += (int)((bytes + sizeof(float) - 1) / sizeof(float));
}

static int make_key(float *k, const snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    int n = 0, i;
    memset(k, 0, SNELL__CAUSTICS_KEY * sizeof(float));
    put(k, &n, &c->maps_only, sizeof c->maps_only);
    put(k, &n, &fd->light, sizeof fd->light);
    put(k, &n, &fd->receiver, sizeof fd->receiver);
    put(k, &n, &sc->count, sizeof sc->count);
    for (i = 0; i < sc->count; i++) {
        const snell__object *o = &sc->obj[i];
        put(k, &n, &o->mesh, sizeof o->mesh);
        put(k, &n, &o->mesh->version, sizeof o->mesh->version);
        put(k, &n, o->model, sizeof o->model);
        put(k, &n, &o->glass->material.ior, sizeof(float));
        put(k, &n, &o->glass->material.thickness, sizeof(float));
        put(k, &n, o->glass->material.tint, 3 * sizeof(float));
        put(k, &n, o->glass->absorption, 3 * sizeof(float));
        put(k, &n, &o->glass->material.method, sizeof o->glass->material.method); /* the photons' path */
        put(k, &n, &o->glass->material.exact, sizeof o->glass->material.exact);
    }
    put(k, &n, &fd->opaque_count, sizeof fd->opaque_count);
    for (i = 0; i < fd->opaque_count; i++) {
        const snell_opaque *o = &fd->opaque[i];
        static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        put(k, &n, &o->mesh, sizeof o->mesh);
        put(k, &n, &o->mesh->version, sizeof o->mesh->version);
        put(k, &n, o->model ? o->model : id, 16 * sizeof(float));
    }
    return n;
}

/* --- GL resources ---------------------------------------------------------- */
static snell_status programs(snell_ctx *ctx, snell__caustics *c)
{
    snell_status st = SNELL_OK;
    if (!c->map_prog) st = snell__program_build(ctx, "object.vert", "caustics_map.frag", NULL, &c->map_prog);
    if (st == SNELL_OK && !c->photon_prog)
        st = snell__program_build(ctx, "caustics_photon.vert", "caustics_splat.frag", "#define SNELL_PHOTON_BVH 0\n",
                                  &c->photon_prog);
    if (st == SNELL_OK && !c->direct_prog)
        st = snell__program_build(ctx, "caustics_quad.vert", "caustics_direct.frag", NULL, &c->direct_prog);
    if (st == SNELL_OK && !c->receiver_prog)
        st = snell__program_build(ctx, "caustics_quad.vert", "caustics_receiver.frag",
                                  "#define SNELL_RECEIVER_VIEW 1\n", &c->receiver_prog);
    if (st == SNELL_OK && !c->opaque_prog)
        st = snell__program_build(ctx, "object.vert", "caustics_opaque.frag", NULL, &c->opaque_prog);
    if (!c->vao) glGenVertexArrays(1, &c->vao);
    return st;
}

/* What the stage made, said in its reason. */
static void say_made(const snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc,
                     const snell__caustics_counts *n, snell_frame_stats *s)
{
    int size = fd->receiver.map_size, plane = fd->receiver.extent > 0.0f, opaque = fd->opaque_count > 0, i;
    char map[112], chains[64] = "";
    if (plane) {
        /* a texel wider than a quarter of the smallest caster's radius blurs its shadow and caustic away:
         * said, since the frame looks merely unshadowed (a 2000-unit square in 256 texels, a unit sphere) */
        float texel = 2.0f * fd->receiver.extent / (float)size, smallest = 0.0f;
        for (i = 0; i < sc->count; i++)
            if (snell__caustics_casts(&sc->obj[i]) && (smallest == 0.0f || sc->obj[i].bsphere[3] < smallest))
                smallest = sc->obj[i].bsphere[3];
        snprintf(map, sizeof map, "%dx%d %s light map%s", size, size, snell__light_map_str(c->map_format),
                 n->casters > 0 && texel > 0.25f * smallest ? " (texels > caster radius/4: blurred)" : "");
    } else
        snprintf(map, sizeof map, "no plane");
    /* the chain path only where beams overlap (single casters keep their own path) */
    if (n->chained) snprintf(chains, sizeof chains, ", %d chained (beams overlap: %d group%s)", n->chained,
                             n->groups, n->groups > 1 ? "s" : "");
    if (n->alone_over) snprintf(chains + strlen(chains), sizeof chains - strlen(chains),
                                ", %d alone: over %d overlap", n->alone_over, SNELL__CAUSTICS_CHAIN);
    /* what changes the picture first (no photons, a blurred map), the counts of paths last: a long
     * reason is cut at its end (SNELL_REASON_SIZE, "...") and the water floor appends after it */
    snell__why(s->caustics_reason, sizeof s->caustics_reason, "made: %d glass casting%s%s; %s; %d opaque lit%s; paths: "
               "%d BVH, %d depth maps%s",
               n->casters, n->shot < n->casters ? " (the spot light inside a bounding sphere: no photons)" : "",
               sc->count > n->casters ? " (clear ones pass)" : "", map, fd->opaque_count,
               opaque ? " (light-frame caustic map)" : "", n->by_bvh, n->shot - n->by_bvh - n->chain_shot, chains);
}

/* The plane and the opaque objects: their light maps made or reused, then drawn. */
static snell_status receiver_run(snell_ctx *ctx, snell__caustics *c,
                                 const snell_frame_desc *fd, const snell__scene *sc, snell_frame_stats *s)
{
    GLint fbo = 0, viewport[4];
    int size = fd->receiver.map_size, i, key_len;
    int plane = fd->receiver.extent > 0.0f, opaque = fd->opaque_count > 0;
    snell_status st;
    snell__caustics_light L;
    snell__caustics_frame F;
    snell__caustics_counts n = {0};
    if (!c->map_format) c->map_format = snell__light_map_format(ctx);
    key_len = make_key(c->scratch, c, fd, sc);
    if (c->valid && key_len == c->key_len && memcmp(c->scratch, c->key, (size_t)key_len * sizeof(float)) == 0) {
        s->caustics_reused = 1;
        snell__why(s->caustics_reason, sizeof s->caustics_reason, "reused: nothing moved (light, glass, receivers)");
        return snell__caustics_draw_view(c, fd, sc);
    }
    c->valid = c->made_plane = c->made_opaque = 0;
    c->made++; /* what lit the opaque objects changes: a dynamic environment showing them is redrawn */
    snell__caustics_resolve_light(&fd->light, &L);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_VIEWPORT, viewport);
    for (i = 0; i < fd->opaque_count; i++)
        if ((st = snell__mesh_upload((snell_mesh *)fd->opaque[i].mesh)) != SNELL_OK) return st;
    for (i = 0; i < sc->count; i++)
        if ((st = snell__mesh_upload(sc->obj[i].mesh)) != SNELL_OK) return st;
    snell__caustics_make_frame(fd, sc, &L, &F);
    memcpy(c->frame_vp, F.vp, sizeof c->frame_vp);
    c->frame_lin[0] = F.near_, c->frame_lin[1] = F.far_, c->frame_lin[2] = (float)L.spot, c->frame_lin[3] = F.texel;
    st = programs(ctx, c);
    if (st == SNELL_OK && plane) st = snell__caustics_map_target(ctx, c, size);
    if (st == SNELL_OK) st = snell__caustics_glass_targets(ctx, c, fd->light.photons);
    if (st == SNELL_OK) st = snell__caustics_draw_shadows(ctx, c, fd, sc, &F);
    if (st == SNELL_OK && opaque) st = snell__caustics_draw_receivers(ctx, c, fd, &F);
    if (st == SNELL_OK) {
        if (plane) snell__caustics_draw_direct(c, fd, &L, &F);
        st = snell__caustics_photons(ctx, c, fd, sc, &L, &F, s, &n);
        s->passes += 1 + plane + 2 * opaque + (2 + plane + opaque) * n.shot;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glDepthMask(GL_TRUE);
    if (st != SNELL_OK) return st;
    memcpy(c->key, c->scratch, (size_t)key_len * sizeof(float));
    c->key_len = key_len;
    c->valid = 1, c->made_plane = plane, c->made_opaque = opaque;
    c->light = fd->light;
    say_made(c, fd, sc, &n, s);
    return snell__caustics_draw_view(c, fd, sc);
}

snell_status snell__caustics_read_opaque(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size)
{
    if (!c->valid || !c->made_opaque) return snell__fail(ctx, SNELL_E_INVALID_ARG, "caustics: no caustic map made yet");
    snell_status st;
    size_t i, n = (size_t)c->recv_size * (size_t)c->recv_size * 4;
    *size = c->recv_size;
    st = snell__read_light_map(ctx, c->map_format, c->cm_fbo, c->recv_size, rgba, "the caustic map");
    /* an RGB10_A2 map holds a spot's intensity as irradiance at the frame's far
     * plane (caustics_photon.vert): back to the units of a float map */
    if (st == SNELL_OK && c->map_format == GL_RGB10_A2 && c->frame_lin[2] > 0.5f)
        for (i = 0; i < n; i++) rgba[i] *= c->frame_lin[1] * c->frame_lin[1];
    return st;
}

/* The receiver plane and the opaque objects, then the water's floor
 * (water/water_caustics.c), which adds its part to the reason. */
snell_status snell__caustics_run(snell_ctx *ctx, snell__caustics *c,
                                 const snell_frame_desc *fd, const snell__scene *sc, snell_frame_stats *s)
{
    snell_status st =
        fd->receiver.extent > 0.0f || fd->opaque_count > 0 ? receiver_run(ctx, c, fd, sc, s) : SNELL_OK;
#if SNELL_WITH_WATER
    if (st == SNELL_OK && fd->water)
        st = snell__water_caustics(ctx, fd->water, &fd->light, fd->opaque, fd->opaque_count, s);
#endif
    return st;
}

snell_status snell__caustics_read(snell_ctx *ctx, snell__caustics *c, float *rgba, int *size)
{
    if (!c->valid || !c->made_plane) return snell__fail(ctx, SNELL_E_INVALID_ARG, "caustics: no light map made yet");
    *size = c->map_size;
    return snell__read_light_map(ctx, c->map_format, c->map_fbo, c->map_size, rgba, "the caustics light map");
}

void snell__caustics_destroy(snell__caustics *c)
{
    int i;
    if (c->map_prog) glDeleteProgram(c->map_prog);
    if (c->opaque_prog) glDeleteProgram(c->opaque_prog);
    if (c->recv_fbo) glDeleteFramebuffers(1, &c->recv_fbo);
    if (c->recv_z) glDeleteTextures(1, &c->recv_z);
    if (c->cm_fbo) glDeleteFramebuffers(1, &c->cm_fbo);
    if (c->cm_tex) glDeleteTextures(1, &c->cm_tex);
    if (c->photon_prog) glDeleteProgram(c->photon_prog);
    if (c->photon_chain_prog) glDeleteProgram(c->photon_chain_prog);
    snell__gpu_bvh_free(c->chain_bvh, 1);
    snell__free(&c->chain_alloc, c->chain_geo);
    snell__free(&c->chain_alloc, c->chain_idx);
    for (i = 0; i < 4; i++)
        if (c->photon_bvh_prog[i >> 1][i & 1]) glDeleteProgram(c->photon_bvh_prog[i >> 1][i & 1]);
    if (c->direct_prog) glDeleteProgram(c->direct_prog);
    if (c->receiver_prog) glDeleteProgram(c->receiver_prog);
    if (c->vao) glDeleteVertexArrays(1, &c->vao);
    for (i = 0; i < 2; i++) {
        if (c->glass_fbo[i]) glDeleteFramebuffers(1, &c->glass_fbo[i]);
        if (c->glass_n[i]) glDeleteTextures(1, &c->glass_n[i]);
        if (c->glass_z[i]) glDeleteTextures(1, &c->glass_z[i]);
    }
    if (c->shadow_fbo) glDeleteFramebuffers(1, &c->shadow_fbo);
    if (c->shadow_z) glDeleteTextures(1, &c->shadow_z);
    if (c->map_fbo) glDeleteFramebuffers(1, &c->map_fbo);
    if (c->map_tex) glDeleteTextures(1, &c->map_tex);
    memset(c, 0, sizeof *c);
}
