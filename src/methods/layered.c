/* SPDX-License-Identifier: MIT */
/* layered.c — multi-layer refraction through layered distance cube maps
 * (Umenhoffer, Patow and Szirmay-Kalos 2007, GPU Gems 3 ch. 17): prepared once
 * per (mesh version, face size, layers) by depth peeling the mesh from its
 * analysed centre into RGBA16F layers of one 2D array texture (layered_bake.frag),
 * fold rims pinched, plus count slices; per frame one pass of layered.frag.
 * Rigid meshes pay no per-frame peel. More: docs/methods.md, "Design notes by
 * file". */
#include "frame/glass_program.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/program.h"
#include "frame/ndcube.h"
#include "frame/pass.h"
#include "core/glstate.h"
#include "core/pack.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define DEFAULT_LAYERS 4
#define DEFAULT_FACE 128
#define DEFAULT_LINEAR 24
#define DEFAULT_BINARY 6
/* convex_steps' default: on a convex mesh that one layer holds, the
 * tangent-plane steps to each exit. Two: one step leaves a ray that starts
 * over one face and exits through another far off (a cube), and more gain
 * little on smooth meshes (bench/notes/code.md, "layered.c"). */
#define DEFAULT_CONVEX_STEPS 2
#define DEFAULT_INTERFACES 8

/* llvmpipe: the march costs so much per pixel that full 4x4 blocks of the
 * screen-space stage pay at any density (as for cubemap.c and peel.c). The
 * convex program costs less, so forward shading pays on large triangles
 * (no G-buffer pass): it won at 89 estimated pixels a front triangle and lost
 * at 22; 48 lies between, not measured itself (bench/notes/code.md,
 * "layered.c"). */
#define LAYERED_SOFTWARE_SCREEN_PPT 1e9f
#define LAYERED_SOFTWARE_SCREEN_PPT_CONVEX 48.0f

/* One mesh version's layers (the prepared resource). */
typedef struct layered_prepared {
    unsigned layers_tex;        /* GL_TEXTURE_2D_ARRAY, RGBA16F, face_size^2 x 6 * (layers + groups): slice
                                 * face * layers + l: layer l's (normal, distance / radius); slice 6 * layers +
                                 * face * groups + g: layers 4g..4g+3's distances (4: none), one look-up for
                                 * the march's count of four layers */
    int face_size, layers;      /* as allocated */
    int groups;                 /* (layers + 3) / 4 */
    int used;                   /* layers holding a surface somewhere (the shader reads these) */
    int capped;                 /* 1: the last layer is not empty: surfaces beyond it are not held */
    float centre[3], radius;    /* object space */
} layered_prepared;

/* A program's own uniforms (over its cache slot's loc); its key: key: layers, linear, binary, absorb, reentry, screen, dispersion */
typedef struct layered_locs {
    int stride, groups, dist_base, inv_model, model, centre, radius, max_interfaces;
} layered_locs;
SNELL__PROGRAM_LOCS_FIT(layered_locs);

typedef struct layered_state {
    snell__output_kind out;
    snell__program_cache *programs; /* the renderer's */
    unsigned bake_prog;
    unsigned nearest;           /* sampler object: the inner Fresnel's environment look-ups (SNELL__UNIT_ENV_NEAREST) */
    int u_view_proj, u_centre, u_inv_radius, u_first, u_prev;
} layered_state;

static void layered_destroy(snell_ctx *ctx, void *state);

static snell_status layered_create(snell_ctx *ctx, snell__output_kind out, snell__program_cache *programs,
                                 void **state)
{
    layered_state *s = (layered_state *)snell__calloc(&ctx->alloc, 1, sizeof *s);
    snell_status st;
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "out of memory");
    s->out = out;
    s->programs = programs;
    st = snell__program_build(ctx, "ndcube_bake.vert", "layered_bake.frag", NULL, &s->bake_prog);
    if (st != SNELL_OK) {
        layered_destroy(ctx, s);
        return st;
    }
    s->u_view_proj = glGetUniformLocation(s->bake_prog, "u_view_proj");
    s->u_centre = glGetUniformLocation(s->bake_prog, "u_centre");
    s->u_inv_radius = glGetUniformLocation(s->bake_prog, "u_inv_radius");
    s->u_first = glGetUniformLocation(s->bake_prog, "u_first");
    s->u_prev = glGetUniformLocation(s->bake_prog, "u_prev");
    glGenSamplers(1, &s->nearest);
    glSamplerParameteri(s->nearest, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(s->nearest, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(s->nearest, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->nearest, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->nearest, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    *state = s;
    return SNELL_OK;
}

static void layered_destroy(snell_ctx *ctx, void *state)
{
    layered_state *s = (layered_state *)state;
    if (!s) return;
    if (s->bake_prog) glDeleteProgram(s->bake_prog);
    if (s->nearest) glDeleteSamplers(1, &s->nearest);
    snell__free(&ctx->alloc, s);
}

/* Correct in kind for any mesh with its analysis (open and non-manifold ones
 * too: a crossing is where the count of surfaces below changes, whatever the
 * topology; a hole lets the ray leave). Not AUTO's pick until its
 * measurements say where it pays (bench/BENCHMARKS.md). */
static snell__fit layered_fit(const snell_mesh_analysis *an, const snell_glass_resolved *g, char *why, size_t n)
{
    (void)g;
    if (!an) {
        snell__why(why, n, "needs the mesh analysis (its centre), which failed");
        return SNELL__FIT_FAILS;
    }
    if (an->convex) {
        /* AUTO tries it before the cubemap (the registry's order): on a
         * convex mesh it is both cheaper and nearer FULL (DEFAULT_CONVEX_STEPS) */
        snell__why(why, n, "convex: one layer from the centre, tangent-plane steps to each exit");
        return SNELL__FIT_ADEQUATE;
    }
    snell__why(why, n, "%s, depth complexity %d: runs, not AUTO's pick without a budget (peel measured more "
                       "accurate)", an->closed ? "closed" : "open", an->depth_complexity);
    return SNELL__FIT_RUNS;
}

static void layered_key(const snell__object *o, int key[4])
{
    key[0] = o->glass->material.layered.face_size;
    key[1] = o->glass->material.layered.layers;
    key[2] = key[3] = 0;
}

/* A finite float of magnitude at most 65504 as IEEE half, rounded to nearest. */
static uint16_t half_of(float f)
{
    uint32_t x, m;
    uint16_t sign = f < 0.0f ? 0x8000u : 0u;
    float a = fabsf(f);
    int e;
    if (!(a > 0.0f)) return sign;
    memcpy(&x, &a, sizeof x);
    e = (int)((x >> 23) & 0xffu) - 127 + 15;
    m = x & 0x7fffffu;
    if (e <= 0) return (uint16_t)(sign | (uint16_t)(a * 16777216.0f + 0.5f)); /* subnormal: m * 2^-24 */
    m = (m + 0x1000u) >> 13;
    if (m == 0x400u) {
        m = 0;
        e++;
    }
    return (uint16_t)(sign | (e >= 31 ? 0x7bffu : ((unsigned)e << 10 | m)));
}

static void release_scratch(unsigned *fbo, unsigned next[2], unsigned *depth_rb, unsigned *query)
{
    if (*fbo) glDeleteFramebuffers(1, fbo);
    if (next[0]) glDeleteTextures(2, next);
    if (*depth_rb) glDeleteRenderbuffers(1, depth_rb);
    if (*query) glDeleteQueries(1, query);
    *fbo = *depth_rb = *query = next[0] = next[1] = 0;
}

/* depth 0: a 2D texture; else a 2D array of depth slices. */
static unsigned make_texture(GLenum format, int size, int depth, GLint filter)
{
    GLenum target = depth ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
    unsigned tex;
    glGenTextures(1, &tex);
    glBindTexture(target, tex);
    if (depth)
        glTexStorage3D(target, 1, format, size, size, depth);
    else
        glTexStorage2D(target, 1, format, size, size);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

/* Closes the gaps at the rims of folds: where a texel holds fewer layers
 * than a neighbour (of the 8 in its face), the layers it lacks, taken in
 * pairs from its own count up (a fold's two surfaces end together at its
 * rim, seen from the centre), get the mean of the neighbour's pair's
 * distances (averaged over such neighbours) and the neighbour's normals,
 * instead of "none" (4). Filtered, the fold's two surfaces then meet at the
 * rim, so a ray passing outside it crosses both at once (an even change of
 * the count, no surface), where filtering towards 4 made each a wall of its
 * own. dist and out: layers x size^2 floats; half: the layers' RGBA halves
 * (the normals of filled texels are set). */
static void pinch(int size, int layers, const float *dist, float *out, uint16_t *half)
{
    size_t texels = (size_t)size * (size_t)size, x;
    int l;
    memcpy(out, dist, sizeof *out * (size_t)layers * texels);
    for (x = 0; x < texels; x++) {
        int xi = (int)(x % (size_t)size), yi = (int)(x / (size_t)size), nx = 0, dx, dy;
        while (nx < layers && dist[(size_t)nx * texels + x] < 2.0f) nx++;
        if (nx == layers) continue;
        for (l = nx; l < layers; l++) {
            int partner = nx + ((l - nx) ^ 1), top = l > partner ? l : partner, k = 0;
            float sum = 0.0f;
            size_t src = 0;
            if (partner >= layers) continue;
            for (dy = -1; dy <= 1; dy++)
                for (dx = -1; dx <= 1; dx++) {
                    size_t y;
                    if ((!dx && !dy) || xi + dx < 0 || xi + dx >= size || yi + dy < 0 || yi + dy >= size) continue;
                    y = (size_t)(yi + dy) * (size_t)size + (size_t)(xi + dx);
                    if (!(dist[(size_t)top * texels + y] < 2.0f)) continue;
                    sum += 0.5f * (dist[(size_t)l * texels + y] + dist[(size_t)partner * texels + y]);
                    if (!k) src = y;
                    k++;
                }
            if (!k) continue;
            out[(size_t)l * texels + x] = sum / (float)k;
            memcpy(half + 4 * ((size_t)l * texels + x), half + 4 * ((size_t)l * texels + src), 3 * sizeof *half);
        }
    }
}

/* Peels layer after layer of each face, nearest first (every face drawn,
 * culling off): a pass keeps, per texel, the nearest surface behind the
 * previous layer's (ping-pong textures of its 24-bit distance). Each pass's
 * normal (16+16 bits, octahedral) and distance are read back and packed as
 * half floats for the filtered layers (once per mesh version: the stalls
 * are part of the bake). An ANY_SAMPLES_PASSED query per pass counts the
 * layers that hold something; a face's later layers are drawn empty. */
static snell_status bake(snell_ctx *ctx, layered_state *s, snell_mesh *mesh, layered_prepared *p,
                         snell_object_stats *stats)
{
    static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    unsigned fbo = 0, normal_tex = 0, next[2] = {0, 0}, depth_rb = 0, query = 0;
    snell__pass pass;
    snell__pixel_store pack, unpack;
    snell_status st = SNELL_OK;
    int face, l, size = p->face_size;
    size_t i, texels = (size_t)size * (size_t)size;
    size_t nl = (size_t)p->layers;
    uint8_t *normal_px = (uint8_t *)snell__malloc(&ctx->alloc, 8 * texels), *dist_px = normal_px + 4 * texels;
    /* a face's layers: half RGBA (normal, distance), then their distances as floats twice (read, pinched) */
    uint16_t *half = (uint16_t *)snell__malloc(&ctx->alloc, (8 + 8 * nl + 8 * nl) * texels);
    uint16_t *group = half ? half + 4 * nl * texels : NULL; /* the distances of a group of four layers */
    float *dist = half ? (float *)(group + 4 * texels) : NULL, *pinched = dist ? dist + nl * texels : NULL;
    GLenum fst;
    if (!normal_px || !half) {
        snell__free(&ctx->alloc, normal_px);
        snell__free(&ctx->alloc, half);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory for the layered bake's read-back");
    }
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
    glActiveTexture(GL_TEXTURE1);
    normal_tex = make_texture(GL_RGBA8, size, 0, GL_NEAREST);
    next[0] = make_texture(GL_RGBA8, size, 0, GL_NEAREST);
    next[1] = make_texture(GL_RGBA8, size, 0, GL_NEAREST);
    glGenQueries(1, &query);
    /* client memory, tight rows, whatever pixel buffers or store state a host set */
    snell__pixel_pack_begin(&pack, 1);
    snell__pixel_unpack_begin(&unpack, 1);
    if (glGetError() != GL_NO_ERROR) st = snell__fail(ctx, SNELL_E_GL, "cannot make the layered bake's %dx%d targets",
                                                      size, size);
    snell__pass_begin(&pass, fbo, size, size, 0, GL_LESS, 1.0f);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, normal_tex, 0);
    glDrawBuffers(2, bufs);
    glUseProgram(s->bake_prog);
    glUniform3fv(s->u_centre, 1, p->centre);
    glUniform1f(s->u_inv_radius, 1.0f / p->radius);
    glUniform1i(s->u_prev, 1);
    glBindVertexArray(mesh->vao);
    p->used = 0;
    for (face = 0; face < 6 && st == SNELL_OK; face++) {
        mat4 vp;
        /* near: surfaces closer than 1e-4 radius to the centre are clipped;
         * far: every vertex lies within the radius */
        snell__cube_face_view_proj(face, p->centre, p->radius * 1e-4f, p->radius * 1.01f, vp);
        glUniformMatrix4fv(s->u_view_proj, 1, GL_FALSE, (const GLfloat *)vp);
        for (l = 0; l < p->layers && st == SNELL_OK; l++) {
            uint16_t *out = half + 4 * (size_t)l * texels;
            GLuint any = 0;
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, next[l & 1], 0);
            if (face == 0 && l == 0 && (fst = glCheckFramebufferStatus(GL_FRAMEBUFFER)) != GL_FRAMEBUFFER_COMPLETE) {
                st = snell__fail(ctx, SNELL_E_GL, "layered bake framebuffer incomplete (0x%x)", (unsigned)fst);
                break;
            }
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glActiveTexture(GL_TEXTURE1);
            glBindTexture(GL_TEXTURE_2D, next[(l + 1) & 1]); /* the previous layer's */
            glUniform1i(s->u_first, l == 0);
            glBeginQuery(GL_ANY_SAMPLES_PASSED, query);
            snell__mesh_draw(mesh);
            glEndQuery(GL_ANY_SAMPLES_PASSED);
            glGetQueryObjectuiv(query, GL_QUERY_RESULT, &any);
            if (any && l + 1 > p->used) p->used = l + 1;
            stats->passes++;
            glReadBuffer(GL_COLOR_ATTACHMENT0);
            glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, normal_px);
            glReadBuffer(GL_COLOR_ATTACHMENT1);
            glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, dist_px);
            /* Half floats: the distance 2^-11 relative (at most 2^-12 of the
             * radius); 4 where the layer is empty, beyond any point of the
             * bounding sphere, so filtering towards an empty texel moves
             * the surface out, not in. */
            for (i = 0; i < texels; i++) {
                const uint8_t *b = dist_px + 4 * i;
                float n[3];
                snell_unpack_dir_rgba8(normal_px + 4 * i, n);
                out[4 * i + 0] = half_of(n[0]);
                out[4 * i + 1] = half_of(n[1]);
                out[4 * i + 2] = half_of(n[2]);
                dist[(size_t)l * texels + i] =
                    b[3] ? (float)((uint32_t)b[0] << 16 | (uint32_t)b[1] << 8 | b[2]) / 16777215.0f : 4.0f;
            }
        }
        if (st != SNELL_OK) break;
        pinch(size, p->layers, dist, pinched, half);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D_ARRAY, p->layers_tex);
        for (l = 0; l < p->layers; l++) {
            uint16_t *out = half + 4 * (size_t)l * texels;
            if ((l & 3) == 0)
                for (i = 0; i < 4 * texels; i++) group[i] = half_of(4.0f);
            for (i = 0; i < texels; i++) {
                out[4 * i + 3] = half_of(pinched[(size_t)l * texels + i]);
                group[4 * i + (l & 3)] = out[4 * i + 3];
            }
            glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, face * p->layers + l, size, size, 1, GL_RGBA, GL_HALF_FLOAT,
                            out);
            if ((l & 3) == 3 || l == p->layers - 1)
                glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 6 * p->layers + face * p->groups + (l >> 2), size, size,
                                1, GL_RGBA, GL_HALF_FLOAT, group);
        }
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0, 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glDrawBuffers(1, bufs);
    snell__pass_end(&pass);
    release_scratch(&fbo, next, &depth_rb, &query);
    if (normal_tex) glDeleteTextures(1, &normal_tex);
    snell__pixel_pack_end(&pack);
    snell__pixel_unpack_end(&unpack);
    snell__free(&ctx->alloc, normal_px);
    snell__free(&ctx->alloc, half);
    p->capped = p->used == p->layers;
    if (st == SNELL_OK && glGetError() != GL_NO_ERROR) st = snell__fail(ctx, SNELL_E_GL, "GL error baking the layers");
    return st;
}

static void layered_release(void *prepared)
{
    layered_prepared *p = (layered_prepared *)prepared;
    if (p->layers_tex) glDeleteTextures(1, &p->layers_tex);
    p->layers_tex = 0;
}

/* The centre the layers are baked about. Distance maps are exact where the
 * centre's rays meet the surface head-on and worst where they graze it (a
 * texel's distance then stands for a long stretch of surface): the cubemap's
 * centre (the analysis', chosen to see the most surface as the farthest)
 * lies in a torus's tube, whose walls its rays graze; the box centre lies in
 * the hole, from where they meet the walls square. So among a few
 * candidates (the analysis' centre, the box centre and the box centre moved
 * a quarter of the box along each axis) the one whose rays meet the surface
 * most squarely: the largest area-weighted mean |cos| between a triangle's
 * normal and the ray from the centre to it. O(triangles) per candidate,
 * once per mesh version. */
static void choose_centre(const snell_mesh *m, const snell_mesh_analysis *an, float centre[3])
{
    float cand[8][3], best_score = -1.0f;
    int nc = 0, c, k;
    uint32_t t;
    for (k = 0; k < 3; k++) cand[0][k] = 0.5f * (m->bmin[k] + m->bmax[k]);
    nc = 1;
    for (k = 0; k < 6; k++) {
        int axis = k / 2;
        memcpy(cand[nc], cand[0], sizeof cand[0]);
        cand[nc][axis] += (k & 1 ? -0.25f : 0.25f) * (m->bmax[axis] - m->bmin[axis]);
        nc++;
    }
    if (an) memcpy(cand[nc++], an->centre, sizeof cand[0]);
    memcpy(centre, an ? an->centre : cand[0], 3 * sizeof(float));
    for (c = 0; c < nc; c++) {
        double sum = 0.0, area_sum = 0.0;
        for (t = 0; t < m->triangle_count; t++) {
            const float *a = m->positions + 3 * m->indices[3 * t], *b = m->positions + 3 * m->indices[3 * t + 1],
                        *d = m->positions + 3 * m->indices[3 * t + 2];
            float e1[3], e2[3], n[3], r[3], nn, rr;
            for (k = 0; k < 3; k++) {
                e1[k] = b[k] - a[k];
                e2[k] = d[k] - a[k];
                r[k] = (a[k] + b[k] + d[k]) / 3.0f - cand[c][k];
            }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            nn = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            rr = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
            if (!(nn > 0.0f) || !(rr > 0.0f)) continue;
            sum += fabsf(n[0] * r[0] + n[1] * r[1] + n[2] * r[2]) / rr; /* area * 2 * |cos| */
            area_sum += nn;
        }
        if (area_sum > 0.0 && (float)(sum / area_sum) > best_score) {
            best_score = (float)(sum / area_sum);
            memcpy(centre, cand[c], 3 * sizeof(float));
        }
    }
}

/* About the centre choose_centre picks (inside the mesh or not: the layers
 * hold whatever lies around it). */
static snell_status layered_prepare(snell_ctx *ctx, void *state, const snell__object *o, void *prepared,
                                    snell_object_stats *stats)
{
    layered_state *s = (layered_state *)state;
    layered_prepared *p = (layered_prepared *)prepared;
    const snell_mesh_analysis *an = o->analysis;
    const snell_layered_params *lp = &o->glass->material.layered;
    uint32_t v;
    float r2 = 0.0f;
    int layers, convex;
    snell_status st;
    choose_centre(o->mesh, an, p->centre);
    for (v = 0; v < o->mesh->vertex_count; v++) {
        const float *q = o->mesh->positions + 3 * v;
        float dx = q[0] - p->centre[0], dy = q[1] - p->centre[1], dz = q[2] - p->centre[2];
        if (dx * dx + dy * dy + dz * dz > r2) r2 = dx * dx + dy * dy + dz * dz;
    }
    /* 1e-4 margin: the farthest vertex stays strictly inside the range */
    p->radius = sqrtf(r2) * 1.0001f;
    if (!(p->radius > 0.0f)) p->radius = 1.0f;
    /* a convex mesh holds one surface along every direction from a centre inside it: one layer */
    convex = an && an->convex;
    layers = convex ? 1 : lp->layers;
    if (!p->layers_tex || p->face_size != lp->face_size || p->layers != layers) {
        int groups = (layers + 3) / 4;
        size_t bytes = (size_t)lp->face_size * (size_t)lp->face_size * 48u * (size_t)(layers + groups);
        st = snell__budget_check(ctx, bytes, "the layered method's distance cube maps");
        if (st == SNELL_OK) st = snell__ctx_limit(ctx, SNELL__LIM_LAYERS, 6 * (layers + groups), "layered: array layers");
        if (st != SNELL_OK) return st;
        layered_release(p);
        glActiveTexture(GL_TEXTURE1);
        p->layers_tex = make_texture(GL_RGBA16F, lp->face_size, 6 * (layers + groups), GL_LINEAR);
        p->face_size = lp->face_size;
        p->layers = layers;
        p->groups = groups;
        if (glGetError() != GL_NO_ERROR) {
            layered_release(p);
            return snell__fail(ctx, SNELL_E_GL, "cannot make %d layers of %d^2 cube faces", layers, lp->face_size);
        }
    }
    st = bake(ctx, s, o->mesh, p, stats);
    if (convex) p->capped = 0; /* its one layer holds every surface */
    return st;
}

static snell_status build_prog(snell_ctx *ctx, layered_state *s, const int key[8], snell__program_slot *p)
{
    char def[320];
    snell_status st;
    snprintf(def, sizeof def,
             "#define SNELL_LAYERS %d\n#define SNELL_LINEAR %d\n#define SNELL_BINARY %d\n#define SNELL_ABSORB %d\n"
             "#define SNELL_REENTRY %d\n#define SNELL_DISPERSION %d\n#define SNELL_INNER_FRESNEL %d\n"
             "#define SNELL_ENV_NEAREST 1\n",
             key[0], key[1], key[2], key[3], key[4], key[6], key[7]);
    st = snell__glass_program_build(ctx, "layered.frag", s->out, def, key[5], &p->g);
    if (st != SNELL_OK) return st;
    layered_locs *loc = SNELL__PROGRAM_LOCS_OF(layered_locs, p);
    loc->stride = glGetUniformLocation(p->g.prog, "u_stride");
    loc->groups = glGetUniformLocation(p->g.prog, "u_groups");
    loc->dist_base = glGetUniformLocation(p->g.prog, "u_dist_base");
    loc->inv_model = glGetUniformLocation(p->g.prog, "u_inv_model");
    loc->model = glGetUniformLocation(p->g.prog, "u_model");
    loc->centre = glGetUniformLocation(p->g.prog, "u_centre");
    loc->radius = glGetUniformLocation(p->g.prog, "u_radius");
    loc->max_interfaces = glGetUniformLocation(p->g.prog, "u_max_interfaces");
    return SNELL_OK;
}

static snell_status layered_draw(snell_ctx *ctx, void *state, const snell__view *v, const snell__object *o,
                                 snell_object_stats *stats)
{
    layered_state *s = (layered_state *)state;
    const snell_layered_params *lp = &o->glass->material.layered;
    const layered_prepared *lpr = (const layered_prepared *)o->prepared;
    snell__program_slot *p;
    snell_status st = SNELL_OK;
    int hit, nearest_unit;
    int convex = o->analysis && o->analysis->convex;
    /* Compile-time constants of the march: the layers read (those that hold
     * something: a sphere needs 1), steps, absorption, whether a ray that
     * left can meet the mesh again (not on a convex one; with one layer that
     * selects the convex program, layered.frag's STAR), the variant, and
     * the exit's Fresnel (auto: on convex meshes, as the cubemap's: there the
     * march is nearly exact and the missing internal reflection is the
     * largest error left). */
    const int one_layer_convex = convex && lpr->used <= 1; /* layered.frag's convex program */
    const int steps = one_layer_convex ? lp->convex_steps : lp->binary_steps;
    const int key[8] = {lpr->used > 0 ? lpr->used : 1, lp->linear_steps, steps, o->glass->absorbs,
                        !convex, snell__glass_variant(o), snell__dispersion_variant(o->glass),
                        lp->inner_fresnel == SNELL_INNER_FRESNEL_ON ||
                            (lp->inner_fresnel == SNELL_INNER_FRESNEL_AUTO && convex)};
    p = snell__program_cache_get(s->programs, SNELL_METHOD_LAYERED, key, 8, &hit);
    if (!hit) st = build_prog(ctx, s, key, p);
    if (st != SNELL_OK) return st;
    snell__glass_program_use(&p->g, v, o);
    snell__glass_program_bind(&p->g, "u_layers", GL_TEXTURE_2D_ARRAY, lpr->layers_tex, 0);
    /* the environment again, nearest (the inner Fresnel's look-ups); the
     * sampler is unbound after the draw, as a frame starts (core/glstate.c) */
    nearest_unit = snell__samplers_unit(&p->g.samplers, "u_env_nearest");
    snell__glass_program_bind(&p->g, "u_env_nearest", o->env_paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP,
                              o->env_texture, s->nearest);
    const layered_locs *loc = SNELL__PROGRAM_LOCS_OF(const layered_locs, p);
    glUniformMatrix4fv(loc->inv_model, 1, GL_FALSE, (const GLfloat *)o->inv_model);
    glUniformMatrix4fv(loc->model, 1, GL_FALSE, (const GLfloat *)o->model);
    glUniform3fv(loc->centre, 1, lpr->centre);
    glUniform1f(loc->radius, lpr->radius);
    glUniform1i(loc->stride, lpr->layers);
    glUniform1i(loc->groups, lpr->groups);
    glUniform1i(loc->dist_base, 6 * lpr->layers);
    glUniform1i(loc->max_interfaces, lp->max_interfaces);
    snell__draw_surface(o, stats);
    if (nearest_unit >= 0) glBindSampler((unsigned)nearest_unit, 0);
    stats->passes++;
    stats->counters[0] = lpr->used;
    stats->counters[1] = lpr->capped;
    stats->counters[2] =
        (int)((size_t)lpr->face_size * (size_t)lpr->face_size * 48u * (size_t)(lpr->layers + lpr->groups) / 1024u);
    return SNELL_OK;
}

static const snell_param_info g_params[] = {
    {.name = "layers",
     .offset = offsetof(snell_glass_material, layered.layers),
     .help = "distance-map layers baked from the centre (the first surfaces along each direction)",
     .min = 1, .max = SNELL_LAYERED_MAX_LAYERS, .def = DEFAULT_LAYERS},
    {.name = "face_size",
     .offset = offsetof(snell_glass_material, layered.face_size),
     .help = "cube face size of every layer, texels",
     .min = 16, .max = 1024, .def = DEFAULT_FACE},
    {.name = "linear_steps",
     .offset = offsetof(snell_glass_material, layered.linear_steps),
     .help = "linear march steps from a point to the bounding sphere's far side",
     .min = 1, .max = 64, .def = DEFAULT_LINEAR},
    {.name = "binary_steps",
     .offset = offsetof(snell_glass_material, layered.binary_steps),
     .help = "binary steps at each crossing the march finds",
     .min = 1, .max = 16, .def = DEFAULT_BINARY},
    {.name = "convex_steps",
     .offset = offsetof(snell_glass_material, layered.convex_steps),
     .help = "on a convex mesh that one layer holds: tangent-plane steps to each exit (half as many for the "
             "inner Fresnel's reflection)",
     .min = 1, .max = 16, .def = DEFAULT_CONVEX_STEPS},
    {.name = "max_interfaces",
     .offset = offsetof(snell_glass_material, layered.max_interfaces),
     .help = "surfaces processed per path (1 = single surface; exits, re-entries, TIR bounces)",
     .min = 1, .max = SNELL_LAYERED_MAX_INTERFACES, .def = DEFAULT_INTERFACES},
    {.name = "inner_fresnel",
     .offset = offsetof(snell_glass_material, layered.inner_fresnel),
     .help = "Fresnel at the last exit too (1 - F out, the internal reflection followed by one more march): auto (on for convex meshes), off, on",
     .min = 0, .max = 2, .def = SNELL_INNER_FRESNEL_AUTO, .value_names = snell__inner_fresnel_names},
};


static const snell_counter_info g_counters[] = {
    {"layers_used", "layers that hold a surface in some direction (the march reads these)"},
    {"layers_capped", "1 if the last layer baked holds surfaces: more lie beyond it, unseen"},
    {"layers_kib", "memory of the baked layers, KiB"},
};

/* Its path goes on through re-entries as FULL's dominant branch does (as
 * peel's): snell-bench measures it against FULL too. */
static const snell_method_info g_info = {
    .method = SNELL_METHOD_LAYERED,
    .name = "layered",
    .summary = "multi-layer, view-independent: depth-peeled distance cube map layers from the centre, a march through them, TIR, re-entries (Umenhoffer et al. 2007)",
    .needs = "the mesh analysis (its centre); baked once per mesh version, nothing per frame",
    .param_count = (int)(sizeof g_params / sizeof *g_params),
    .params = g_params,
    .counter_count = (int)(sizeof g_counters / sizeof *g_counters),
    .counters = g_counters,
    .ref_interfaces = 0,
    .ref_chord_absorption = 0,
    .default_sweep = "linear_steps=12,24,48",
};

/* AUTO by budget's rungs (frame/method.h): method, parameter, value; frame
 * time over single's and glass PSNR vs FULL for a convex, a bunny-like, a
 * torus-like and an open mesh; resolution scale (bench/notes/budget_rungs.md). */
static const snell_budget_rung g_rungs[] = {
    {SNELL_METHOD_LAYERED, NULL, 0, {2.07f, 5.58f, 12.41f, 5.17f}, {40.61f, 19.63f, 25.68f, 18.38f}, 1, NULL},
    {SNELL_METHOD_LAYERED, NULL, 0, {2.76f, 3.45f, 5.64f, 3.28f}, {34.42f, 17.92f, 23.85f, 17.34f}, 2, NULL},
};

const snell__method snell__method_layered = {
    .info = &g_info,
    .needs_analysis = 1,
    .fit = layered_fit,
    .create = layered_create,
    .destroy = layered_destroy,
    .prepared_size = sizeof(layered_prepared),
    .key = layered_key,
    .prepare = layered_prepare,
    .release = layered_release,
    .draw = layered_draw,
    .software_screen_ppt = LAYERED_SOFTWARE_SCREEN_PPT,
    .software_screen_ppt_convex = LAYERED_SOFTWARE_SCREEN_PPT_CONVEX,
    .rungs = g_rungs,
    .rung_count = (int)(sizeof g_rungs / sizeof *g_rungs),
};
