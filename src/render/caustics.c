/* SPDX-License-Identifier: MIT */
/* caustics.c — the caustics stage (Wyman & Davis 2006, caustic
 * maps; Unger 3.5 names light refracted onto surfaces as beyond its scope):
 * the receiver plane's light map holds its irradiance, in units of the
 * light's colour: the direct light where a shadow map of every glass and
 * opaque object leaves it lit (caustics_direct.frag), plus, per glass object,
 * a grid of photons from the light refracted in and out of it
 * (caustics_photon.vert: a convex mesh by an image-space exit search in its
 * farthest-surface map; any other by the exact method's BVH of the mesh,
 * borrowed from the prepared cache, through every interface: TIR, exits and
 * re-entries up to the material's exact.max_interfaces; a thin wall's
 * straight on through each of its walls, a slab each) and splatted onto
 * the plane, each carrying the light's flux through its cell of the beam
 * (flux-correct: energy is conserved, as the 2D lightmap's lines are,
 * src/lm2d). Casters whose beams overlap seen from the light (up to
 * SNELL__CAUSTICS_CHAIN) take the chain path together: one world-space BVH
 * of their meshes, each photon counted only where the light meets its
 * caster first and going on through the next one it meets (ref_caustics.c
 * chain); the others keep their own path. The opaque objects are receivers too: a photon
 * stops at the first one (marched through their depth map in the light
 * frame, the shadow map's view), and one that lands where the light sees
 * the surface is splatted into their caustic map in that frame; they are
 * then drawn lit over the opaque stage's colours (caustics_opaque.frag).
 * The receiver plane is drawn in the view with its map. The maps are
 * reused while light, glass, opaque objects and receiver are still. */
#include "render/caustics.h"
#include "core/ctx.h"
#include "core/gl.h"
#include "core/glstate.h"
#include "core/program.h"
#include "frame/glass_program.h"
#include "frame/method.h"
#include "mesh/mesh.h"
#include "mesh/bvh_gpu.h"
#include "water/water_draw.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define SHADOW_BIAS 2e-4f /* depth bias of the shadow look-ups (plane, opaque objects), shadow map units */

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
        if (l->photons != 0 && (l->photons < 16 || l->photons > 1024))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.photons %d outside 16..1024 (0 = %d)", l->photons,
                               SNELL_DEFAULT_PHOTONS);
        if (l->type == SNELL_LIGHT_SPOT && !finite3(l->position))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.position must be finite");
        if (l->type == SNELL_LIGHT_SPOT && (!isfinite(l->spot_angle) || l->spot_angle < 0.0f || l->spot_angle > 1.5f))
            return snell__fail(ctx, SNELL_E_INVALID_ARG, "light.spot_angle %g outside 0..1.5 radians (0 = 0.5)",
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
    if ((rc->extent > 0.0f || (l->type != SNELL_LIGHT_NONE && fd->opaque_count > 0)) && rc->map_size != 0 &&
        (rc->map_size < 16 || rc->map_size > 2048))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "receiver.map_size %d outside 16..2048 (0 = %d)", rc->map_size,
                           SNELL_DEFAULT_RECEIVER_MAP);
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
static int casts(const snell__object *o)
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

static void tex_params(GLenum filter)
{
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

static snell_status complete(snell_ctx *ctx, const char *what)
{
    GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (s != GL_FRAMEBUFFER_COMPLETE)
        return snell__fail(ctx, SNELL_E_GL, "caustics: %s framebuffer incomplete (0x%x)", what, (unsigned)s);
    return SNELL_OK;
}

/* The light's views of one glass object: RGB10_A2 normals + 32F depth, size^2. */
static snell_status glass_targets(snell_ctx *ctx, snell__caustics *c, int size)
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
        tex_params(GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, c->glass_z[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
        tex_params(GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, c->glass_fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->glass_n[i], 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->glass_z[i], 0);
        st = complete(ctx, "glass map");
    }
    c->glass_size = st == SNELL_OK ? size : 0;
    return st;
}

static snell_status shadow_target(snell_ctx *ctx, snell__caustics *c, int size)
{
    GLenum none = GL_NONE;
    if (c->shadow_size == size) return SNELL_OK;
    if (!c->shadow_fbo) {
        glGenFramebuffers(1, &c->shadow_fbo);
        glGenTextures(1, &c->shadow_z);
    }
    glBindTexture(GL_TEXTURE_2D, c->shadow_z);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    tex_params(GL_LINEAR); /* with the compare mode: 2 x 2 percentage-closer filtering */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindFramebuffer(GL_FRAMEBUFFER, c->shadow_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->shadow_z, 0);
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    if (complete(ctx, "shadow map") != SNELL_OK) return SNELL_E_GL;
    c->shadow_size = size;
    return SNELL_OK;
}

static snell_status map_target(snell_ctx *ctx, snell__caustics *c, int size)
{
    if (c->map_size == size) return SNELL_OK;
    if (!c->map_fbo) {
        glGenFramebuffers(1, &c->map_fbo);
        glGenTextures(1, &c->map_tex);
    }
    glBindTexture(GL_TEXTURE_2D, c->map_tex);
    snell__light_map_image(c->map_format, size);
    tex_params(GL_NEAREST); /* read bilinearly by caustics_receiver.frag (32F need not filter) */
    glBindFramebuffer(GL_FRAMEBUFFER, c->map_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->map_tex, 0);
    if (complete(ctx, "light map") != SNELL_OK) return SNELL_E_GL;
    c->map_size = size;
    return SNELL_OK;
}

/* --- the light's frame ------------------------------------------------------ */
/* The frame's light, resolved: unit direction (directional) or position,
 * unit axis and cone (spot), and its colour (all zero = 1). */
typedef struct light_res {
    int spot;
    float d[3], pos[3], cos_cone, col[3];
} light_res;

static void resolve_light(const snell_light *l, light_res *o)
{
    float len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                      l->direction[2] * l->direction[2]);
    int k;
    o->spot = l->type == SNELL_LIGHT_SPOT;
    for (k = 0; k < 3; k++) {
        o->d[k] = l->direction[k] / len;
        o->pos[k] = l->position[k];
        o->col[k] = l->color[k];
    }
    o->cos_cone = cosf(l->spot_angle);
}

/* A perspective view from eye towards target (spot lights), frustum
 * x/-z in [lo[0], hi[0]], y/-z in [lo[1], hi[1]]. */
static void spot_view(const float eye[3], const float target[3], const float lo[2], const float hi[2], float near_,
                      float far_, mat4 vp)
{
    vec3 up = {0.0f, 1.0f, 0.0f}, dir;
    mat4 view, proj;
    glm_vec3_sub((float *)target, (float *)eye, dir);
    glm_vec3_normalize(dir);
    if (fabsf(dir[1]) > 0.99f) up[0] = 0.0f, up[1] = 0.0f, up[2] = 1.0f;
    glm_lookat((float *)eye, (float *)target, up, view);
    glm_frustum(lo[0] * near_, hi[0] * near_, lo[1] * near_, hi[1] * near_, near_, far_, proj);
    glm_mat4_mul(proj, view, vp);
}

/* An orthographic view along unit d centred on `centre`: x, y in [-half,
 * half] and depths [near, far] from an eye at centre - d * back. */
static void light_view(const float d[3], const float centre[3], float back, float lo[2], float hi[2], float near_,
                       float far_, mat4 vp)
{
    vec3 eye, up = {0.0f, 1.0f, 0.0f};
    mat4 view, proj;
    if (fabsf(d[1]) > 0.99f) up[0] = 1.0f, up[1] = 0.0f;
    eye[0] = centre[0] - d[0] * back, eye[1] = centre[1] - d[1] * back, eye[2] = centre[2] - d[2] * back;
    glm_lookat(eye, (float *)centre, up, view);
    glm_ortho(lo[0], hi[0], lo[1], hi[1], near_, far_, proj);
    glm_mat4_mul(proj, view, vp);
}

static void draw_mesh(GLuint prog, const snell_mesh *m, const float *model, const float vp[16])
{
    mat4 mm, inv;
    mat3 nm;
    if (model) memcpy(mm, model, sizeof mm);
    else glm_mat4_identity(mm);
    glm_mat4_inv(mm, inv);
    glm_mat4_transpose(inv);
    glm_mat4_pick3(inv, nm);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_model"), 1, GL_FALSE, (const GLfloat *)mm);
    glUniformMatrix3fv(glGetUniformLocation(prog, "u_normal_matrix"), 1, GL_FALSE, (const GLfloat *)nm);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, vp);
    snell__mesh_draw(m);
}

static void plane_uniform(GLuint prog, const snell_receiver *rc)
{
    glUniform4f(glGetUniformLocation(prog, "u_plane"), rc->height, rc->center[0], rc->center[1], rc->extent);
}

/* The light frame: the one view from the light that the shadow map, the
 * opaque receivers' depth map and their caustic map share (directional:
 * orthographic along the light; spot: a perspective view from it looking
 * straight down), its window holding the receiver plane's corners and the
 * opaque receivers' bounding spheres. */
typedef struct light_frame {
    mat4 vp;
    float near_, far_;
    float texel;  /* the larger side of a texel (directional: world; spot: on the plane at distance 1) */
    float area;   /* a texel's area, in the same units */
    float reach;  /* the longest way a photon is marched when no plane ends it */
    int size;
} light_frame;

static void opaque_sphere(const snell_opaque *o, float b[4])
{
    mat4 m;
    if (o->model) memcpy(m, o->model, sizeof m);
    else glm_mat4_identity(m);
    snell__bounding_sphere(o->mesh, m, b);
}

static void grow(float lo[2], float hi[2], float x, float y)
{
    if (x < lo[0]) lo[0] = x;
    if (x > hi[0]) hi[0] = x;
    if (y < lo[1]) lo[1] = y;
    if (y > hi[1]) hi[1] = y;
}

static void make_frame(const snell_frame_desc *fd, const snell__scene *sc, const light_res *L, light_frame *F)
{
    const snell_receiver *rc = &fd->receiver;
    int plane = rc->extent > 0.0f, i, k;
    float centre[3] = {rc->center[0], rc->height, rc->center[1]};
    float back = 1.0f, lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f}, far_ = 0.0f, b[4];
    mat4 view;
    const float *d = L->d;
    F->size = rc->map_size;
    F->size = F->size * 2 > 2048 ? 2048 : F->size * 2;
    if (!plane) { /* the opaque receivers' mean centre */
        centre[0] = centre[1] = centre[2] = 0.0f;
        for (i = 0; i < fd->opaque_count; i++) {
            opaque_sphere(&fd->opaque[i], b);
            for (k = 0; k < 3; k++) centre[k] += b[k] / (float)fd->opaque_count;
        }
    }
    if (L->spot) {
        float below[3] = {L->pos[0], L->pos[1] - 1.0f, L->pos[2]}, up[3] = {0.0f, 0.0f, 1.0f};
        glm_lookat((float *)L->pos, below, up, view);
    } else {
        /* behind every caster: the eye's distance from the centre along -d */
        for (i = 0; i < sc->count + fd->opaque_count; i++) {
            float t;
            if (i < sc->count) memcpy(b, sc->obj[i].bsphere, sizeof b);
            else opaque_sphere(&fd->opaque[i - sc->count], b);
            t = -((b[0] - centre[0]) * d[0] + (b[1] - centre[1]) * d[1] + (b[2] - centre[2]) * d[2]) + b[3];
            if (t + 1.0f > back) back = t + 1.0f;
        }
        {
            vec3 eye, up = {0.0f, 1.0f, 0.0f};
            if (fabsf(d[1]) > 0.99f) up[0] = 1.0f, up[1] = 0.0f;
            for (k = 0; k < 3; k++) eye[k] = centre[k] - d[k] * back;
            glm_lookat(eye, centre, up, view);
        }
    }
    /* the square's corners in the light's view fix the window and the far plane */
    for (k = 0; k < 4 && plane; k++) {
        vec4 p = {rc->center[0] + ((k & 1) ? rc->extent : -rc->extent), rc->height,
                  rc->center[1] + ((k & 2) ? rc->extent : -rc->extent), 1.0f}, q;
        glm_mat4_mulv(view, p, q);
        if (L->spot) { /* directions x/-z, y/-z; the plane is below the light (else nothing is lit) */
            float z = -q[2] > 1e-3f ? -q[2] : 1e-3f;
            q[0] /= z, q[1] /= z;
        }
        grow(lo, hi, q[0], q[1]);
        if (-q[2] > far_) far_ = -q[2];
    }
    /* and the opaque receivers' bounding spheres (spot: their boxes' corners; one
     * above the light widens the window to its limit) */
    for (i = 0; i < fd->opaque_count; i++) {
        vec4 c, q;
        opaque_sphere(&fd->opaque[i], b);
        c[0] = b[0], c[1] = b[1], c[2] = b[2], c[3] = 1.0f;
        glm_mat4_mulv(view, c, q);
        if (-q[2] + b[3] > far_) far_ = -q[2] + b[3];
        if (!L->spot) {
            grow(lo, hi, q[0] - b[3], q[1] - b[3]);
            grow(lo, hi, q[0] + b[3], q[1] + b[3]);
        } else {
            for (k = 0; k < 8; k++) {
                float x = q[0] + ((k & 1) ? b[3] : -b[3]), y = q[1] + ((k & 2) ? b[3] : -b[3]);
                float z = -q[2] + ((k & 4) ? b[3] : -b[3]);
                if (z > 1e-3f) grow(lo, hi, x / z, y / z);
                else grow(lo, hi, x < 0.0f ? -1e3f : 1e3f, y < 0.0f ? -1e3f : 1e3f);
            }
        }
    }
    if (L->spot) {
        float h = plane ? L->pos[1] - rc->height : 0.0f, t = 12.0f; /* at most ~170 degrees across */
        float wx, wy;
        for (i = 0; i < 2; i++) {
            if (lo[i] < -t) lo[i] = -t;
            if (hi[i] > t) hi[i] = t;
        }
        if (fd->opaque_count > 0 && far_ > h) h = far_;
        if (h <= 1e-3f) h = 1e-3f;
        F->near_ = h * 0.01f, F->far_ = h * 1.01f + 1e-3f;
        spot_view(L->pos, (float[3]){L->pos[0], L->pos[1] - 1.0f, L->pos[2]}, lo, hi, F->near_, F->far_, F->vp);
        wx = fmaxf(-lo[0], hi[0]), wy = fmaxf(-lo[1], hi[1]);
        F->reach = F->far_ * sqrtf(1.0f + wx * wx + wy * wy);
    } else {
        F->near_ = 0.01f, F->far_ = far_ + 1.0f;
        light_view(d, centre, back, lo, hi, F->near_, F->far_, F->vp);
        F->reach = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (F->far_ - F->near_) * (F->far_ - F->near_));
    }
    F->texel = fmaxf(hi[0] - lo[0], hi[1] - lo[1]) / (float)F->size;
    F->area = (hi[0] - lo[0]) * (hi[1] - lo[1]) / ((float)F->size * (float)F->size);
}

/* The shadow map in the light frame: every casting glass and opaque object. */
/* A depth-only pass from the light into fbo (size x size), cleared, with the depth program. */
static void begin_depth_pass(const snell__caustics *c, GLuint fbo, int size)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size, size);
    glDepthMask(GL_TRUE);
    glClearDepthf(1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(c->map_prog);
}

static snell_status draw_shadows(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                 const snell__scene *sc, const light_frame *F)
{
    snell_status st;
    int i;
    if ((st = shadow_target(ctx, c, F->size)) != SNELL_OK) return st;
    begin_depth_pass(c, c->shadow_fbo, F->size);
    for (i = 0; i < sc->count; i++)
        if (casts(&sc->obj[i])) draw_mesh(c->map_prog, sc->obj[i].mesh, (const float *)sc->obj[i].model, (const float *)F->vp);
    for (i = 0; i < fd->opaque_count; i++) draw_mesh(c->map_prog, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)F->vp);
    return SNELL_OK;
}

/* The opaque receivers in the light frame: their nearest depth (where
 * photons stop, and which surface a caustic texel belongs to), and their
 * caustic map cleared for the photons. */
static snell_status draw_receivers(snell_ctx *ctx, snell__caustics *c, const snell_frame_desc *fd,
                                   const light_frame *F)
{
    int i;
    if (c->recv_size != F->size) {
        snell_status st;
        if (!c->recv_fbo) {
            glGenFramebuffers(1, &c->recv_fbo);
            glGenTextures(1, &c->recv_z);
            glGenFramebuffers(1, &c->cm_fbo);
            glGenTextures(1, &c->cm_tex);
        }
        glBindTexture(GL_TEXTURE_2D, c->recv_z);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, F->size, F->size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, NULL);
        tex_params(GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, c->cm_tex);
        snell__light_map_image(c->map_format, F->size);
        tex_params(GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, c->cm_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->cm_tex, 0);
        if ((st = complete(ctx, "caustic map")) != SNELL_OK) return st;
        glBindFramebuffer(GL_FRAMEBUFFER, c->recv_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, c->recv_z, 0);
        {
            GLenum none = GL_NONE;
            glDrawBuffers(1, &none);
            glReadBuffer(GL_NONE);
        }
        if ((st = complete(ctx, "receiver depth")) != SNELL_OK) return st;
        c->recv_size = F->size;
    }
    begin_depth_pass(c, c->recv_fbo, F->size);
    for (i = 0; i < fd->opaque_count; i++) draw_mesh(c->map_prog, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)F->vp);
    glBindFramebuffer(GL_FRAMEBUFFER, c->cm_fbo);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    return SNELL_OK;
}

static void light_uniforms(GLuint prog, const light_res *L)
{
    glUniform1i(glGetUniformLocation(prog, "u_spot"), L->spot);
    glUniform3fv(glGetUniformLocation(prog, "u_dir"), 1, L->d);
    glUniform3fv(glGetUniformLocation(prog, "u_pos"), 1, L->pos);
    glUniform3fv(glGetUniformLocation(prog, "u_axis"), 1, L->d);
    glUniform1f(glGetUniformLocation(prog, "u_cos_cone"), L->cos_cone);
}

/* The direct light into the light map (replacing what it held). */
static void draw_direct(snell__caustics *c, const snell_frame_desc *fd, const light_res *L, const light_frame *F)
{
    glBindFramebuffer(GL_FRAMEBUFFER, c->map_fbo);
    glViewport(0, 0, c->map_size, c->map_size);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glUseProgram(c->direct_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, c->shadow_z);
    glUniform1i(glGetUniformLocation(c->direct_prog, "u_shadow"), 0);
    glUniformMatrix4fv(glGetUniformLocation(c->direct_prog, "u_shadow_vp"), 1, GL_FALSE, (const GLfloat *)F->vp);
    plane_uniform(c->direct_prog, &fd->receiver);
    glUniform3fv(glGetUniformLocation(c->direct_prog, "u_color"), 1, L->col);
    light_uniforms(c->direct_prog, L);
    glUniform1f(glGetUniformLocation(c->direct_prog, "u_texel"), 2.0f / (float)c->map_size);
    glUniform1f(glGetUniformLocation(c->direct_prog, "u_bias"), SHADOW_BIAS);
    glBindVertexArray(c->vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

/* The light frame's uniforms (photons and lit opaque shading). */
static void frame_uniforms(GLuint prog, const snell__caustics *c)
{
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_recv_vp"), 1, GL_FALSE, c->frame_vp);
    glUniform4fv(glGetUniformLocation(prog, "u_recv_lin"), 1, c->frame_lin);
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
    int stack = m->exact.walk != SNELL_EXACT_WALK_STACKLESS;
    snell_status st;
    char def[96];
    GLuint *p;
    *prog = 0;
    if (c->maps_only || (m->method != SNELL_METHOD_EXACT && snell__mesh_analysis(o->mesh, &an) == SNELL_OK && an->convex))
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
static int beams_overlap(const light_res *L, const float a[4], const float b[4])
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
static void chain_groups(const snell__scene *sc, const light_res *L, int *group, int *size)
{
    int i, j, k, merged = 1;
    for (i = 0; i < sc->count; i++) group[i] = casts(&sc->obj[i]) ? i : -1, size[i] = 0;
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
    if (nt >= (1u << 24)) return snell__fail(ctx, SNELL_E_LIMIT, "caustics: %zu triangles in a chain (2^24 at most)", nt);
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
            glm_mat3_mulv((vec3 *)o->normal_matrix, me->normals + 3 * (size_t)i, c->chain_geo + 3 * (nv + v0 + (size_t)i));
        }
        for (i = 0; i < 3 * (int)me->triangle_count; i++) c->chain_idx[3 * t0 + (size_t)i] = me->indices[i] + (uint32_t)v0;
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
static int draw_photons(snell__caustics *c, const snell_frame_desc *fd, const snell__object *o, const light_res *L,
                        const light_frame *F, GLuint prog, const snell__gpu_bvh *bvh, const chain *ch)
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
        spot_view(L->pos, o->bsphere, lo, hi, (dist - r) * 0.5f, dist + r + 1.0f, vp);
        cell = 2.0f * tan_half / (float)n;
    } else {
        light_view(L->d, o->bsphere, r + 1.0f, lo, hi, 0.5f, 2.0f * r + 1.5f, vp);
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
        draw_mesh(c->map_prog, o->mesh, (const float *)o->model, (const float *)vp);
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
    light_uniforms(prog, L);
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
    plane_uniform(prog, rc);
    glUniform1f(glGetUniformLocation(prog, "u_reach"), 2.0f * r);
    glUniform1i(glGetUniformLocation(prog, "u_has_plane"), plane);
    glUniform1i(glGetUniformLocation(prog, "u_recv"), fd->opaque_count > 0);
    glUniform1f(glGetUniformLocation(prog, "u_recv_reach"), F->reach);
    frame_uniforms(prog, c);
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
                               const light_res *L, const light_frame *F, const int *group, int leader,
                               snell_frame_stats *s, int *shot)
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

/* The opaque objects lit (caustics_opaque.frag), over what the opaque stage
 * drew: the same vertices (object.vert), depth LEQUAL. */
static void draw_lit_opaque(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    GLuint p = c->opaque_prog;
    int i;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(p);
    snell__lit_opaque_uniforms(p, c, 0);
    glUniform3fv(glGetUniformLocation(p, "u_eye"), 1, sc->view.eye);
    glUniform4fv(glGetUniformLocation(p, "u_view_axis"), 1, sc->view.view_axis);
    for (i = 0; i < fd->opaque_count; i++) {
        glUniform3fv(glGetUniformLocation(p, "u_color"), 1, fd->opaque[i].color);
        draw_mesh(p, fd->opaque[i].mesh, fd->opaque[i].model, (const float *)sc->view.view_proj);
    }
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}

static snell_status draw_receiver(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    const snell_receiver *rc = &fd->receiver;
    float albedo[3];
    memcpy(albedo, rc->albedo, sizeof rc->albedo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(c->receiver_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, c->map_tex);
    glUniform1i(glGetUniformLocation(c->receiver_prog, "u_plane_map"), 0);
    glUniform3fv(glGetUniformLocation(c->receiver_prog, "u_plane_albedo"), 1, albedo);
    glUniform3fv(glGetUniformLocation(c->receiver_prog, "u_eye"), 1, sc->view.eye);
    glUniform4fv(glGetUniformLocation(c->receiver_prog, "u_view_axis"), 1, sc->view.view_axis);
    glUniformMatrix4fv(glGetUniformLocation(c->receiver_prog, "u_view_proj"), 1, GL_FALSE,
                       (const GLfloat *)sc->view.view_proj);
    plane_uniform(c->receiver_prog, rc);
    glBindVertexArray(c->vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    return SNELL_OK;
}

/* The receivers in the view with the light maps: the plane, the opaque objects lit. */
static snell_status draw_view(snell__caustics *c, const snell_frame_desc *fd, const snell__scene *sc)
{
    if (c->made_opaque) draw_lit_opaque(c, fd, sc);
    return c->made_plane ? draw_receiver(c, fd, sc) : SNELL_OK;
}

/* The plane and the opaque objects: their light maps made or reused, then drawn. */
static snell_status receiver_run(snell_ctx *ctx, snell__caustics *c,
                                 const snell_frame_desc *fd, const snell__scene *sc, snell_frame_stats *s)
{
    GLint fbo = 0, viewport[4];
    int size = fd->receiver.map_size, i, casters = 0, shot = 0, key_len, by_bvh = 0;
    int group[SNELL_MAX_GLASS], gsize[SNELL_MAX_GLASS], chained = 0, chain_shot = 0, groups = 0, alone_over = 0;
    int plane = fd->receiver.extent > 0.0f, opaque = fd->opaque_count > 0;
    char map[112], chains[64] = "";
    snell_status st;
    light_res L;
    light_frame F;
    if (!c->map_format) c->map_format = snell__light_map_format(ctx);
    key_len = make_key(c->scratch, c, fd, sc);
    if (c->valid && key_len == c->key_len && memcmp(c->scratch, c->key, (size_t)key_len * sizeof(float)) == 0) {
        s->caustics_reused = 1;
        snell__why(s->caustics_reason, sizeof s->caustics_reason, "reused: nothing moved (light, glass, receivers)");
        return draw_view(c, fd, sc);
    }
    c->valid = c->made_plane = c->made_opaque = 0;
    c->made++; /* what lit the opaque objects changes: a dynamic environment showing them is redrawn */
    resolve_light(&fd->light, &L);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_VIEWPORT, viewport);
    for (i = 0; i < fd->opaque_count; i++)
        if ((st = snell__mesh_upload((snell_mesh *)fd->opaque[i].mesh)) != SNELL_OK) return st;
    for (i = 0; i < sc->count; i++)
        if ((st = snell__mesh_upload(sc->obj[i].mesh)) != SNELL_OK) return st;
    make_frame(fd, sc, &L, &F);
    memcpy(c->frame_vp, F.vp, sizeof c->frame_vp);
    c->frame_lin[0] = F.near_, c->frame_lin[1] = F.far_, c->frame_lin[2] = (float)L.spot, c->frame_lin[3] = F.texel;
    st = programs(ctx, c);
    if (st == SNELL_OK && plane) st = map_target(ctx, c, size);
    if (st == SNELL_OK) st = glass_targets(ctx, c, fd->light.photons);
    if (st == SNELL_OK) st = draw_shadows(ctx, c, fd, sc, &F);
    if (st == SNELL_OK && opaque) st = draw_receivers(ctx, c, fd, &F);
    if (st == SNELL_OK) {
        if (plane) draw_direct(c, fd, &L, &F);
        for (i = 0; i < sc->count; i++) group[i] = -1;
        if (!c->maps_only) chain_groups(sc, &L, group, gsize);
        for (i = 0; i < sc->count && st == SNELL_OK; i++)
            if (casts(&sc->obj[i])) {
                snell__gpu_bvh bvh;
                GLuint prog = 0;
                int n, together = group[i] >= 0 ? gsize[group[i]] : 1;
                if (together >= 2 && together <= SNELL__CAUSTICS_CHAIN) {
                    if (group[i] == i) st = chain_draw(ctx, c, fd, sc, &L, &F, group, i, s, &chain_shot);
                    chained++, groups += group[i] == i, casters++;
                    continue;
                }
                alone_over += together > SNELL__CAUSTICS_CHAIN;
                if ((st = photon_path(ctx, c, &sc->obj[i], &bvh, &prog)) != SNELL_OK) break;
                n = draw_photons(c, fd, &sc->obj[i], &L, &F, prog ? prog : c->photon_prog, prog ? &bvh : NULL, NULL);
                s->caustics_photons += n;
                shot += n > 0;
                by_bvh += prog && n > 0;
                casters++;
            }
        shot += chain_shot;
        s->passes += 1 + plane + 2 * opaque + (2 + plane + opaque) * shot;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glDepthMask(GL_TRUE);
    if (st != SNELL_OK) return st;
    memcpy(c->key, c->scratch, (size_t)key_len * sizeof(float));
    c->key_len = key_len;
    c->valid = 1, c->made_plane = plane, c->made_opaque = opaque;
    c->light = fd->light;
    if (plane) {
        /* a texel wider than a quarter of the smallest caster's radius blurs its shadow and caustic away:
         * said, since the frame looks merely unshadowed (a 2000-unit square in 256 texels, a unit sphere) */
        float texel = 2.0f * fd->receiver.extent / (float)size, smallest = 0.0f;
        for (i = 0; i < sc->count; i++)
            if (casts(&sc->obj[i]) && (smallest == 0.0f || sc->obj[i].bsphere[3] < smallest))
                smallest = sc->obj[i].bsphere[3];
        snprintf(map, sizeof map, "%dx%d %s light map%s", size, size, snell__light_map_str(c->map_format),
                 casters > 0 && texel > 0.25f * smallest ? " (texels > caster radius/4: blurred)" : "");
    } else
        snprintf(map, sizeof map, "no plane");
    /* the chain path only where beams overlap (single casters keep their own path) */
    if (chained) snprintf(chains, sizeof chains, ", %d chained (beams overlap: %d group%s)", chained, groups,
                          groups > 1 ? "s" : "");
    if (alone_over) snprintf(chains + strlen(chains), sizeof chains - strlen(chains),
                             ", %d alone: over %d overlap", alone_over, SNELL__CAUSTICS_CHAIN);
    /* what changes the picture first (no photons, a blurred map), the counts of paths last: a long
     * reason is cut at its end (SNELL_REASON_SIZE, "...") and the water floor appends after it */
    snell__why(s->caustics_reason, sizeof s->caustics_reason, "made: %d glass casting%s%s; %s; %d opaque lit%s; paths: "
               "%d BVH, %d depth maps%s",
               casters, shot < casters ? " (the spot light inside a bounding sphere: no photons)" : "",
               sc->count > casters ? " (clear ones pass)" : "", map, fd->opaque_count,
               opaque ? " (light-frame caustic map)" : "", by_bvh, shot - by_bvh - chain_shot, chains);
    return draw_view(c, fd, sc);
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

/* --- the glass kernels' hook SNELL_RECEIVER ------------------------------ */
void snell__receiver_view(snell__view *v, const snell__caustics *c, const snell_receiver *rc)
{
    if (c->made_opaque) {
        v->lit_opaque = c;
        snell__textures_publish(&v->textures, "u_shadow", GL_TEXTURE_2D, c->shadow_z, 0);
        snell__textures_publish(&v->textures, "u_recv_z", GL_TEXTURE_2D, c->recv_z, 0);
        snell__textures_publish(&v->textures, "u_caustic", GL_TEXTURE_2D, c->cm_tex, 0);
    }
    if (!c->made_plane) return;
    v->receiver_map = c->map_tex;
    snell__textures_publish(&v->textures, "u_plane_map", GL_TEXTURE_2D, c->map_tex, 0);
    v->receiver_plane[0] = rc->height, v->receiver_plane[1] = rc->center[0];
    v->receiver_plane[2] = rc->center[1], v->receiver_plane[3] = rc->extent;
    memcpy(v->receiver_albedo, rc->albedo, sizeof rc->albedo);
}

static const char *receiver_defines(unsigned bits)
{
    (void)bits;
    return "#define SNELL_RECEIVER 1\n";
}

static const char *const receiver_uniform_names[SNELL__RECEIVER_UNIFORMS] = {"u_plane", "u_plane_albedo",
                                                                              "u_lit_opaque"};

/* common/opaque_lit.glsl's uniforms of the program in use, its three maps on
 * units unit..unit + 2 (c NULL: the samplers' units alone): the opaque objects lit by the light the maps were
 * made with (caustics_opaque.frag; a kernel without the scene layers has
 * none of these uniforms: -1, ignored). */
void snell__lit_opaque_uniforms(unsigned prog, const snell__caustics *c, int unit)
{
    static const char *const samplers[3] = {"u_shadow", "u_recv_z", "u_caustic"};
    light_res L;
    int i;
    for (i = 0; i < 3 && unit >= 0; i++) glUniform1i(glGetUniformLocation(prog, samplers[i]), unit + i);
    if (!c) return;
    if (unit >= 0) {
        const unsigned tex[3] = {c->shadow_z, c->recv_z, c->cm_tex};
        for (i = 0; i < 3; i++) {
            glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
            glBindTexture(GL_TEXTURE_2D, tex[i]);
        }
    }
    resolve_light(&c->light, &L);
    frame_uniforms(prog, c);
    light_uniforms(prog, &L);
    glUniform3fv(glGetUniformLocation(prog, "u_light"), 1, L.col);
    glUniform1f(glGetUniformLocation(prog, "u_bias"), SHADOW_BIAS);
}

static void receiver_uniforms(const snell__glass_program *g, const int *locs, const snell__view *v,
                              const snell__object *o)
{
    (void)o;
    glUniform4fv(locs[0], 1, v->receiver_plane); /* extent 0 without a plane: none seen */
    glUniform3fv(locs[1], 1, v->receiver_albedo);
    glUniform1i(locs[2], v->lit_opaque != NULL);
    snell__lit_opaque_uniforms(g->prog, v->lit_opaque, -1);
}

const snell__kernel_hook snell__receiver_hook = {
    .variant_mask = SNELL__GLASS_RECEIVER,
    .defines = receiver_defines,
    .uniform_names = receiver_uniform_names,
    .uniform_count = SNELL__RECEIVER_UNIFORMS,
    .uniforms = receiver_uniforms,
};
