/* SPDX-License-Identifier: MIT */
/* caustics_photons.c — the caustics stage's photons (render/caustics.c): per
 * glass object a grid of them from the light, refracted in and out of it
 * (caustics_photon.vert: a convex mesh by an image-space exit search in its
 * farthest-surface map; any other by the exact method's BVH of the mesh,
 * through every interface; a thin wall straight on, a slab each wall), each
 * stopped at the first opaque object and splatted flux-correct onto the plane
 * or the opaque surface the light sees. Casters whose beams overlap go
 * together (the chain, ref_caustics.c chain): one world-space BVH of their
 * meshes, each photon counted only where the light meets its caster first. */
#include "render/caustics_private.h"
#include "core/ctx.h"
#include "core/program.h"
#include "mesh/mesh.h"
#include "mesh/bvh_gpu.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The light's views of one glass object: RGB10_A2 normals + 32F depth, size^2. */
snell_status snell__caustics_glass_targets(snell_ctx *ctx, snell__caustics *c, int size)
{
    int i;
    snell_status st = SNELL_OK;
    if (c->glass_size == size) return SNELL_OK;
    for (i = 0; i < 2 && st == SNELL_OK; i++) {
        if (!c->glass_fbo[i]) {
            glGenFramebuffers(1, &c->glass_fbo[i]);
            glGenTextures(1, &c->glass_n[i]);
            glGenTextures(1, &c->glass_z[i]);
        }
        glBindTexture(GL_TEXTURE_2D, c->glass_n[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB10_A2, size, size, 0, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, NULL);
        snell__texture_nearest(GL_TEXTURE_2D, 1);
        glBindTexture(GL_TEXTURE_2D, c->glass_z[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
        snell__texture_nearest(GL_TEXTURE_2D, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, c->glass_fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->glass_n[i], 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->glass_z[i], 0);
        st = snell__caustics_complete(ctx, "glass map");
    }
    c->glass_size = st == SNELL_OK ? size : 0;
    return st;
}

/* How a glass object's photons find their way through it: the depth maps'
 * one crossing (prog 0), or, where the mesh is not convex (or has no
 * analysis) or its material is the exact method's (whose interfaces ask for
 * TIR bounces), the mesh's BVH (mesh/bvh_gpu.h: built once, refitted when
 * deformed, the one an exact object of the same mesh walks; bvh, prog: the
 * photon program of its node format and the material's walk). A convex mesh
 * keeps the maps: one crossing is its whole path there, at a fraction of
 * the cost. */
static snell_status photon_path(snell_ctx *ctx, snell__caustics *c, const snell__object *o, snell__gpu_bvh *bvh,
                                GLuint *prog)
{
    const snell_glass_material *m = &o->glass->material;
    const snell_mesh_analysis *an = NULL;
    int stack = snell__exact_walk_stack(ctx->cost, m->exact.walk); /* the device's default walk too */
    snell_status st;
    char def[96];
    GLuint *p;
    *prog = 0;
    if (c->maps_only ||
        (m->method != SNELL_METHOD_EXACT && snell__mesh_analysis(o->mesh, &an) == SNELL_OK && an->convex))
        return SNELL_OK;
    if ((st = snell__mesh_gpu_bvh(ctx, o->mesh, m->exact.node_format, bvh)) != SNELL_OK) return st;
    p = &c->photon_bvh_prog[bvh->q16][stack];
    snprintf(def, sizeof def, "#define SNELL_PHOTON_BVH 1\n#define SNELL_NODES_Q16 %d\n#define SNELL_STACK_WALK %d\n",
             bvh->q16, stack);
    if (!*p && (st = snell__program_build(ctx, "caustics_photon.vert", "caustics_splat.frag", def, p)) != SNELL_OK)
        return st;
    *prog = *p;
    return SNELL_OK;
}

/* The material's exact parameters as the photons walk by them: resolved by
 * the registry where the exact method is built, its defaults where not. */
static int photon_budget(const snell_glass_material *m)
{
    return m->exact.node_budget > 0 ? m->exact.node_budget : SNELL_EXACT_DEFAULT_BUDGET;
}

static int photon_interfaces(const snell_glass_material *m)
{
    return m->exact.max_interfaces > 0 ? m->exact.max_interfaces : SNELL_EXACT_DEFAULT_INTERFACES;
}

/* The photon program's uniforms of the BVH path (bvh.glsl, the path's cap
 * and budget: the material's exact parameters), its texture on unit 5. */
static void bvh_texture_uniforms(GLuint p, const snell__gpu_bvh *bvh)
{
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_2D, bvh->texture);
    glUniform1i(glGetUniformLocation(p, "u_bvh"), 5);
    glUniform1i(glGetUniformLocation(p, "u_node_count"), bvh->node_count);
    glUniform1i(glGetUniformLocation(p, "u_tri_base"), bvh->tri_base);
    glUniform3fv(glGetUniformLocation(p, "u_qlo"), 1, bvh->qlo);
    glUniform3fv(glGetUniformLocation(p, "u_qstep"), 1, bvh->qstep);
}

static void bvh_uniforms(GLuint p, const snell__object *o, const snell__gpu_bvh *bvh)
{
    bvh_texture_uniforms(p, bvh);
    glUniform1i(glGetUniformLocation(p, "u_node_budget"), photon_budget(&o->glass->material));
    glUniform1i(glGetUniformLocation(p, "u_max_interfaces"), photon_interfaces(&o->glass->material));
    glUniform1f(glGetUniformLocation(p, "u_eps"), SNELL__BVH_EPS(o->bsphere[3]));
    glUniformMatrix4fv(glGetUniformLocation(p, "u_model"), 1, GL_FALSE, (const GLfloat *)o->model);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_inv_model"), 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniformMatrix3fv(glGetUniformLocation(p, "u_normal_matrix"), 1, GL_FALSE, (const GLfloat *)o->normal_matrix);
}

/* --- light through the casters in sequence ---------------------------------- */
/* Casters whose beams overlap in the light's view (one above another, or
 * side by side under a low light): light may meet one before or after the
 * other. Each one's photons alone would count the light the other meets
 * first twice and pass it unbent through the other; together (the chain
 * path) each photon of caster g counts only if the light meets g first,
 * and goes on through whatever caster of the group it meets next, by that
 * one's optics (ref_caustics.c chain), by a world-space BVH of the group's
 * meshes (exact's format, common/bvh.glsl) whose triangles say their object. */
typedef struct chain {
    snell__gpu_bvh bvh;
    int count, first[SNELL__CAUSTICS_CHAIN + 1]; /* its casters; their triangles' ranges in the merged mesh */
    const snell__object *obj[SNELL__CAUSTICS_CHAIN];
    float sphere[4];                             /* a sphere holding them: the directional photons start before it */
    int budget;                                  /* node visits a photon may take: all their exact.node_budget */
} chain;

/* Whether the bounding spheres a and b overlap seen from light L (along a
 * directional light, or in angle from a spot; a spot inside one: yes). */
static int beams_overlap(const snell__caustics_light *L, const float a[4], const float b[4])
{
    float w[3], t = 0.0f, la = 0.0f, lb = 0.0f, dot = 0.0f;
    int k;
    if (!L->spot) {
        for (k = 0; k < 3; k++) t += (b[k] - a[k]) * L->d[k];
        for (k = 0; k < 3; k++) w[k] = b[k] - a[k] - L->d[k] * t, dot += w[k] * w[k];
        return dot < (a[3] + b[3]) * (a[3] + b[3]);
    }
    for (k = 0; k < 3; k++) {
        la += (a[k] - L->pos[k]) * (a[k] - L->pos[k]);
        lb += (b[k] - L->pos[k]) * (b[k] - L->pos[k]);
        dot += (a[k] - L->pos[k]) * (b[k] - L->pos[k]);
    }
    la = sqrtf(la), lb = sqrtf(lb);
    if (la <= a[3] || lb <= b[3]) return 1;
    return acosf(fminf(fmaxf(dot / (la * lb), -1.0f), 1.0f)) < asinf(a[3] / la) + asinf(b[3] / lb);
}

/* The casters' groups: group[i] the lowest index of caster i's group of
 * casters linked by overlapping beams (-1: not a caster), size[] each
 * group's count at its lowest index. */
static void chain_groups(const snell__scene *sc, const snell__caustics_light *L, int *group, int *size)
{
    int i, j, k, merged = 1;
    for (i = 0; i < sc->count; i++) group[i] = snell__caustics_casts(&sc->obj[i]) ? i : -1, size[i] = 0;
    while (merged) /* to the fixed point: a link lowers a group to its lower end */
        for (merged = 0, i = 0; i < sc->count; i++)
            for (j = i + 1; j < sc->count; j++)
                if (group[i] >= 0 && group[j] >= 0 && group[i] != group[j] &&
                    beams_overlap(L, sc->obj[i].bsphere, sc->obj[j].bsphere)) {
                    int lo = group[i] < group[j] ? group[i] : group[j], hi = group[i] + group[j] - lo;
                    for (k = 0; k < sc->count; k++)
                        if (group[k] == hi) group[k] = lo;
                    merged = 1;
                }
    for (i = 0; i < sc->count; i++)
        if (group[i] >= 0) size[group[i]]++;
}

/* Group `leader`'s casters merged into one world-space mesh (positions by
 * their model matrices, normals by their normal matrices) and its BVH. */
static snell_status chain_make(snell_ctx *ctx, snell__caustics *c, const snell__scene *sc, const int *group,
                               int leader, chain *ch)
{
    size_t nv = 0, nt = 0, v0 = 0, t0 = 0;
    snell_mesh m;
    int i, k, j;
    ch->count = 0, ch->budget = 0;
    for (i = 0; i < sc->count; i++)
        if (group[i] == leader) {
            nv += sc->obj[i].mesh->vertex_count, nt += sc->obj[i].mesh->triangle_count;
            ch->obj[ch->count++] = &sc->obj[i];
        }
    if (nt >= (1u << 24))
        return snell__fail(ctx, SNELL_E_LIMIT, "caustics: %zu triangles in a chain (2^24 at most)", nt);
    if (6 * nv > c->chain_geo_cap || 3 * nt > c->chain_idx_cap) {
        int ok;
        c->chain_alloc = ctx->alloc;
        snell__free(&ctx->alloc, c->chain_geo), snell__free(&ctx->alloc, c->chain_idx);
        c->chain_geo = (float *)snell__calloc(&ctx->alloc, 6 * nv, sizeof(float));
        c->chain_idx = (uint32_t *)snell__calloc(&ctx->alloc, 3 * nt, sizeof(uint32_t));
        ok = c->chain_geo && c->chain_idx; /* either failing: both grown again next time */
        c->chain_geo_cap = ok ? 6 * nv : 0, c->chain_idx_cap = ok ? 3 * nt : 0;
        if (!ok) return snell__fail(ctx, SNELL_E_NOMEM, "caustics: out of memory for a chain");
    }
    memcpy(ch->sphere, ch->obj[0]->bsphere, sizeof ch->sphere);
    for (k = 0; k < ch->count; k++) {
        const snell__object *o = ch->obj[k];
        const snell_mesh *me = o->mesh;
        vec3 d;
        for (i = 0; i < (int)me->vertex_count; i++) {
            glm_mat4_mulv3((vec4 *)o->model, me->positions + 3 * (size_t)i, 1.0f, c->chain_geo + 3 * (v0 + (size_t)i));
            glm_mat3_mulv((vec3 *)o->normal_matrix, me->normals + 3 * (size_t)i,
                          c->chain_geo + 3 * (nv + v0 + (size_t)i));
        }
        for (i = 0; i < 3 * (int)me->triangle_count; i++)
            c->chain_idx[3 * t0 + (size_t)i] = me->indices[i] + (uint32_t)v0;
        ch->first[k] = (int)t0;
        v0 += me->vertex_count, t0 += me->triangle_count;
        ch->budget += photon_budget(&o->glass->material);
        glm_vec3_sub((float *)o->bsphere, ch->sphere, d);
        ch->sphere[3] = fmaxf(ch->sphere[3], glm_vec3_norm(d) + o->bsphere[3]);
    }
    for (j = ch->count; j <= SNELL__CAUSTICS_CHAIN; j++) ch->first[j] = (int)nt;
    memset(&m, 0, sizeof m);
    m.positions = c->chain_geo, m.normals = c->chain_geo + 3 * nv, m.indices = c->chain_idx;
    m.vertex_count = (uint32_t)nv, m.triangle_count = (uint32_t)nt;
    return snell__gpu_bvh_make(ctx, &m, &c->chain_bvh, &ch->bvh);
}

/* The chain program's uniforms for caster o's photons: the group's BVH
 * (world space: identity matrices), its casters' materials and ranges. */
static void chain_uniforms(GLuint p, const chain *ch, const snell__object *o)
{
    static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, id3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    float ior[SNELL__CAUSTICS_CHAIN], thick[SNELL__CAUSTICS_CHAIN], eps[SNELL__CAUSTICS_CHAIN];
    float sigma[3 * SNELL__CAUSTICS_CHAIN], tint[3 * SNELL__CAUSTICS_CHAIN];
    int maxif[SNELL__CAUSTICS_CHAIN], k, self = 0;
    memset(sigma, 0, sizeof sigma), memset(tint, 0, sizeof tint);
    for (k = 0; k < SNELL__CAUSTICS_CHAIN; k++) {
        const snell__object *h = ch->obj[k < ch->count ? k : 0];
        if (h == o && k < ch->count) self = k;
        ior[k] = h->glass->material.ior, thick[k] = h->glass->material.thickness;
        eps[k] = SNELL__BVH_EPS(h->bsphere[3]);
        maxif[k] = h->glass->material.exact.max_interfaces;
        memcpy(sigma + 3 * k, h->glass->absorption, 3 * sizeof(float));
        memcpy(tint + 3 * k, h->glass->material.tint, 3 * sizeof(float));
    }
    bvh_texture_uniforms(p, &ch->bvh);
    glUniform1i(glGetUniformLocation(p, "u_node_budget"), ch->budget);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_model"), 1, GL_FALSE, id);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_inv_model"), 1, GL_FALSE, id);
    glUniformMatrix3fv(glGetUniformLocation(p, "u_normal_matrix"), 1, GL_FALSE, id3);
    glUniform1i(glGetUniformLocation(p, "u_chain_self"), self);
    glUniform1iv(glGetUniformLocation(p, "u_chain_first"), SNELL__CAUSTICS_CHAIN + 1, ch->first);
    glUniform1fv(glGetUniformLocation(p, "u_chain_ior"), SNELL__CAUSTICS_CHAIN, ior);
    glUniform1fv(glGetUniformLocation(p, "u_chain_thick"), SNELL__CAUSTICS_CHAIN, thick);
    glUniform1fv(glGetUniformLocation(p, "u_chain_eps"), SNELL__CAUSTICS_CHAIN, eps);
    glUniform1iv(glGetUniformLocation(p, "u_chain_maxif"), SNELL__CAUSTICS_CHAIN, maxif);
    glUniform3fv(glGetUniformLocation(p, "u_chain_sigma"), SNELL__CAUSTICS_CHAIN, sigma);
    glUniform3fv(glGetUniformLocation(p, "u_chain_tint"), SNELL__CAUSTICS_CHAIN, tint);
    glUniform4fv(glGetUniformLocation(p, "u_chain_sphere"), 1, ch->sphere);
}

/* One glass object's photons: its nearest and farthest surfaces seen from
 * the light, then the photons added into the plane's light map (plane) and
 * into the opaque receivers' caustic map (F). Returns how many were shot
 * (0: a spot light inside its bounding sphere). */
static int draw_photons(snell__caustics *c, const snell_frame_desc *fd, const snell__object *o,
                        const snell__caustics_light *L, const snell__caustics_frame *F, GLuint prog,
                        const snell__gpu_bvh *bvh, const chain *ch)
{
    const snell_receiver *rc = &fd->receiver;
    int n = fd->light.photons, i, k, plane = rc->extent > 0.0f, target;
    float r = o->bsphere[3], lo[2] = {-r, -r}, hi[2] = {r, r}, flux[3], flux_recv[3];
    float texel = plane ? 2.0f * rc->extent / (float)c->map_size : 1.0f;
    float cell = 2.0f * r / (float)n, tan_half = 0.0f;
    mat4 vp, inv;
    if (L->spot) {
        /* a perspective view from the light just holding the bounding sphere;
         * a photon's cell is cell^2 on the image plane at distance 1 */
        float dist = sqrtf((o->bsphere[0] - L->pos[0]) * (o->bsphere[0] - L->pos[0]) +
                           (o->bsphere[1] - L->pos[1]) * (o->bsphere[1] - L->pos[1]) +
                           (o->bsphere[2] - L->pos[2]) * (o->bsphere[2] - L->pos[2]));
        if (dist <= r * 1.001f) return 0;
        tan_half = r / sqrtf(dist * dist - r * r);
        lo[0] = lo[1] = -tan_half, hi[0] = hi[1] = tan_half;
        snell__caustics_spot_view(L->pos, o->bsphere, lo, hi, (dist - r) * 0.5f, dist + r + 1.0f, vp);
        cell = 2.0f * tan_half / (float)n;
    } else {
        snell__caustics_light_view(L->d, o->bsphere, r + 1.0f, lo, hi, 0.5f, 2.0f * r + 1.5f, vp);
    }
    glm_mat4_inv(vp, inv);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glViewport(0, 0, n, n);
    glUseProgram(c->map_prog);
    for (i = 0; i < 2; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, c->glass_fbo[i]);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClearDepthf(i ? 0.0f : 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDepthFunc(i ? GL_GREATER : GL_LESS); /* nearest surfaces, then farthest */
        snell__caustics_draw_mesh(c->map_prog, o->mesh, (const float *)o->model, (const float *)vp);
    }
    glClearDepthf(1.0f);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    if (ch) chain_uniforms(prog, ch, o);
    else if (bvh) bvh_uniforms(prog, o, bvh);
    for (i = 0; i < 5; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, i == 4 ? c->recv_z : (i & 1) ? c->glass_z[i >> 1] : c->glass_n[i >> 1]);
    }
    glUniform1i(glGetUniformLocation(prog, "u_front_n"), 0);
    glUniform1i(glGetUniformLocation(prog, "u_front_z"), 1);
    glUniform1i(glGetUniformLocation(prog, "u_back_n"), 2);
    glUniform1i(glGetUniformLocation(prog, "u_back_z"), 3);
    glUniform1i(glGetUniformLocation(prog, "u_recv_z"), 4);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_light_vp"), 1, GL_FALSE, (const GLfloat *)vp);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_light_inv"), 1, GL_FALSE, (const GLfloat *)inv);
    glUniform1i(glGetUniformLocation(prog, "u_size"), n);
    snell__caustics_light_uniforms(prog, L);
    glUniform1f(glGetUniformLocation(prog, "u_tan"), tan_half);
    glUniform1f(glGetUniformLocation(prog, "u_ior"), o->glass->material.ior);
    glUniform3fv(glGetUniformLocation(prog, "u_sigma"), 1, o->glass->absorption);
    glUniform3fv(glGetUniformLocation(prog, "u_tint"), 1, o->glass->material.tint);
    glUniform1f(glGetUniformLocation(prog, "u_thickness"), o->glass->material.thickness);
    /* each photon carries the light's flux through its cell of the beam
     * (cell^2 facing the light; spot: its solid angle, the shader's share);
     * per texel area that is the irradiance it adds (the plane), or the flux
     * per area facing the light (a light-frame texel: the opaque receivers) */
    for (k = 0; k < 3; k++) {
        flux[k] = L->col[k] * o->glass->material.tint[k] * cell * cell / (texel * texel);
        flux_recv[k] = L->col[k] * o->glass->material.tint[k] * cell * cell / F->area;
    }
    glUniform3fv(glGetUniformLocation(prog, "u_flux"), 1, flux);
    glUniform3fv(glGetUniformLocation(prog, "u_flux_recv"), 1, flux_recv);
    snell__caustics_plane_uniform(prog, rc);
    glUniform1f(glGetUniformLocation(prog, "u_reach"), 2.0f * r);
    glUniform1i(glGetUniformLocation(prog, "u_has_plane"), plane);
    glUniform1i(glGetUniformLocation(prog, "u_recv"), fd->opaque_count > 0);
    glUniform1f(glGetUniformLocation(prog, "u_recv_reach"), F->reach);
    snell__caustics_frame_uniforms(prog, c);
    glBindVertexArray(c->vao);
    for (target = plane ? 0 : 1; target <= (fd->opaque_count > 0); target++) {
        glBindFramebuffer(GL_FRAMEBUFFER, target ? c->cm_fbo : c->map_fbo);
        glViewport(0, 0, target ? F->size : c->map_size, target ? F->size : c->map_size);
        glUniform1i(glGetUniformLocation(prog, "u_target"), target);
        glDrawArrays(GL_POINTS, 0, n * n);
    }
    glDisable(GL_BLEND);
    return n * n;
}

/* Group leader's casters' photons by the chain path (their merged BVH made
 * once for the group); *shot counts the casters that shot any. */
static snell_status chain_draw(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc,
                               const snell__caustics_light *L, const snell__caustics_frame *F, const int *group,
                               int leader, snell_frame_stats *s, int *shot)
{
    chain ch;
    char def[128];
    int k, n;
    snell_status st = chain_make(ctx, c, sc, group, leader, &ch);
    snprintf(def, sizeof def, "#define SNELL_PHOTON_BVH 1\n#define SNELL_PHOTON_CHAIN %d\n#define SNELL_NODES_Q16 0\n"
             "#define SNELL_STACK_WALK 1\n", SNELL__CAUSTICS_CHAIN);
    if (st == SNELL_OK && !c->photon_chain_prog)
        st = snell__program_build(ctx, "caustics_photon.vert", "caustics_splat.frag", def, &c->photon_chain_prog);
    for (k = 0; k < ch.count && st == SNELL_OK; k++) {
        n = draw_photons(c, fd, ch.obj[k], L, F, c->photon_chain_prog, NULL, &ch);
        s->caustics_photons += n;
        *shot += n > 0;
    }
    return st;
}

/* Every casting glass object's photons into the maps: casters whose beams
 * overlap together by the chain path (up to SNELL__CAUSTICS_CHAIN of
 * them), any other alone by its own path. */
snell_status snell__caustics_photons(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                     const snell__scene *sc, const snell__caustics_light *L,
                                     const snell__caustics_frame *F, snell_frame_stats *s, snell__caustics_counts *n)
{
    int group[SNELL_MAX_GLASS], gsize[SNELL_MAX_GLASS], i;
    snell_status st = SNELL_OK;
    memset(n, 0, sizeof *n);
    for (i = 0; i < sc->count; i++) group[i] = -1;
    if (!c->maps_only) chain_groups(sc, L, group, gsize);
    for (i = 0; i < sc->count && st == SNELL_OK; i++)
        if (snell__caustics_casts(&sc->obj[i])) {
            snell__gpu_bvh bvh;
            GLuint prog = 0;
            int shot, together = group[i] >= 0 ? gsize[group[i]] : 1;
            if (together >= 2 && together <= SNELL__CAUSTICS_CHAIN) {
                if (group[i] == i) st = chain_draw(ctx, c, fd, sc, L, F, group, i, s, &n->chain_shot);
                n->chained++, n->groups += group[i] == i, n->casters++;
                continue;
            }
            n->alone_over += together > SNELL__CAUSTICS_CHAIN;
            if ((st = photon_path(ctx, c, &sc->obj[i], &bvh, &prog)) != SNELL_OK) break;
            shot = draw_photons(c, fd, &sc->obj[i], L, F, prog ? prog : c->photon_prog, prog ? &bvh : NULL, NULL);
            s->caustics_photons += shot;
            n->shot += shot > 0;
            n->by_bvh += prog && shot > 0;
            n->casters++;
        }
    n->shot += n->chain_shot;
    return st;
}
