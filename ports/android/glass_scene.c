/* SPDX-License-Identifier: MIT */
/* glass_scene — the Android port's scene: CPU data kept, GL objects per context (glass_scene.h). */
#include "glass_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static snell_status fail(glass_scene *s, snell_status st, const char *what)
{
    snprintf(s->error, sizeof s->error, "%s: %s (%s)", what, snell_last_error(s->ctx), snell_status_str(st));
    return st;
}

snell_status glass_scene_init(glass_scene *s, const void *mesh, size_t mesh_size, glass_mesh_format format,
                              const void *env_image, size_t env_size)
{
    snell_status st;
    memset(s, 0, sizeof *s);
    s->material.ior = 1.5f;
    s->camera.distance = 3.5f;
    s->camera.elevation = 0.3f;
    if (mesh) {
        s->mesh_bytes = (unsigned char *)malloc(mesh_size ? mesh_size : 1);
        if (!s->mesh_bytes) {
            snprintf(s->error, sizeof s->error, "out of memory for a %zu-byte mesh asset", mesh_size);
            return SNELL_E_NOMEM;
        }
        memcpy(s->mesh_bytes, mesh, mesh_size);
        s->mesh_size = mesh_size;
        s->mesh_format = format;
    }
    if (env_image) {
        st = snell_image_decode(env_image, env_size, &s->env_width, &s->env_height, &s->env_rgba);
        if (st != SNELL_OK) {
            fail(s, st, "environment image");
            glass_scene_free(s);
            return st;
        }
    }
    return SNELL_OK;
}

static snell_status create_mesh(glass_scene *s)
{
    if (!s->mesh_bytes) {
        snell_shape_desc sd;
        memset(&sd, 0, sizeof sd);
        return snell_mesh_create_shape(s->ctx, &sd, &s->mesh);
    }
    return s->mesh_format == GLASS_MESH_OBJ
               ? snell_mesh_load_obj_mem(s->ctx, (const char *)s->mesh_bytes, s->mesh_size, &s->mesh)
               : snell_mesh_load_gltf_mem(s->ctx, s->mesh_bytes, s->mesh_size, &s->mesh);
}

static snell_status create_renderer(glass_scene *s, int width, int height)
{
    snell_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.width = width;
    rd.height = height;
    rd.target = SNELL_TARGET_BOUND_FRAMEBUFFER;
    s->width = width;
    s->height = height;
    return snell_renderer_create(s->ctx, &rd, &s->renderer);
}

snell_status glass_scene_create_gl(glass_scene *s, int width, int height)
{
    snell_ctx_desc cd;
    snell_env_desc ed;
    snell_status st;
    const char *what;
    glass_scene_destroy_gl(s);
    memset(&cd, 0, sizeof cd);
    cd.backend = SNELL_BACKEND_EXTERNAL;
    if ((st = snell_ctx_create(&cd, &s->ctx)) != SNELL_OK) return fail(s, st, "snell context");
    what = "mesh";
    if ((st = create_mesh(s)) != SNELL_OK || (st = snell_mesh_normalize(s->mesh, 1.0f)) != SNELL_OK) goto failed;
    memset(&ed, 0, sizeof ed);
    ed.face_size = 256; /* 1.5 MB of faces: a phone's share of memory */
    if (s->env_rgba) {
        ed.source = SNELL_ENV_EQUIRECT;
        ed.equirect_rgba = s->env_rgba;
        ed.equirect_width = s->env_width;
        ed.equirect_height = s->env_height;
    }
    what = "environment";
    if ((st = snell_env_create(s->ctx, &ed, &s->env)) != SNELL_OK) goto failed;
    what = "renderer";
    if ((st = create_renderer(s, width, height)) != SNELL_OK) goto failed;
    s->gl_generation++;
    return SNELL_OK;
failed:
    fail(s, st, what);
    glass_scene_destroy_gl(s);
    return st;
}

snell_status glass_scene_resize(glass_scene *s, int width, int height)
{
    snell_status st;
    if (!s->ctx) {
        snprintf(s->error, sizeof s->error, "glass_scene_resize without GL objects");
        return SNELL_E_INVALID_ARG;
    }
    if (width == s->width && height == s->height) return SNELL_OK;
    snell_renderer_destroy(s->renderer);
    s->renderer = NULL;
    if ((st = create_renderer(s, width, height)) != SNELL_OK) return fail(s, st, "renderer");
    return SNELL_OK;
}

snell_status glass_scene_draw(glass_scene *s, double seconds)
{
    snell_frame_desc fd;
    snell_glass g;
    snell_status st;
    if (!s->renderer) {
        snprintf(s->error, sizeof s->error, "glass_scene_draw without GL objects");
        return SNELL_E_INVALID_ARG;
    }
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    g.mesh = s->mesh;
    g.material = s->material;
    fd.env = s->env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera = s->camera;
    fd.camera.azimuth += (float)(seconds * 0.5); /* half a radian a second */
    fd.depth = SNELL_DEPTH_CLEAR;                /* the surface shows snell's frame alone */
    if ((st = snell_render(s->renderer, &fd, NULL)) != SNELL_OK) return fail(s, st, "frame");
    return SNELL_OK;
}

snell_status glass_scene_draw_in(glass_scene *s, const float view[16], const float projection[16])
{
    snell_frame_desc fd;
    snell_glass g;
    snell_backdrop bd;
    snell_status st;
    if (!s->renderer || !view || !projection) {
        snprintf(s->error, sizeof s->error, "glass_scene_draw_in without GL objects or the app's matrices");
        return SNELL_E_INVALID_ARG;
    }
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    memset(&bd, 0, sizeof bd);
    g.mesh = s->mesh;
    g.material = s->material;
    bd.source = SNELL_BACKDROP_COPY_BOUND;
    fd.env = s->env;
    fd.glass = &g;
    fd.glass_count = 1;
    fd.camera.kind = SNELL_CAMERA_MATRICES;
    memcpy(fd.camera.view, view, sizeof fd.camera.view);
    memcpy(fd.camera.projection, projection, sizeof fd.camera.projection);
    fd.depth = SNELL_DEPTH_TEST;
    fd.draw_background = -1;
    fd.backdrop = &bd;
    if ((st = snell_render(s->renderer, &fd, NULL)) != SNELL_OK) return fail(s, st, "frame in the app's");
    return SNELL_OK;
}

snell_status glass_scene_draw_panels(glass_scene *s, double seconds, const snell_panels_under *under)
{
    snell_frame_desc fd;
    snell_glass g;
    snell_panel p[2];
    snell_status st;
    float w = (float)s->width, h = (float)s->height, shorter = w < h ? w : h, r = 0.12f * shorter;
    int k;
    if (!s->renderer) {
        snprintf(s->error, sizeof s->error, "glass_scene_draw_panels without GL objects");
        return SNELL_E_INVALID_ARG;
    }
    memset(p, 0, sizeof p);
    p[0].center[0] = 0.5f * w, p[0].center[1] = 0.12f * h + 0.5f * r; /* the bar: bottom, 80% wide */
    p[0].size[0] = 0.8f * w, p[0].size[1] = r;
    p[0].frost = 3.0f;               /* the group's material: a little frosted, as a control strip */
    p[1].size[0] = p[1].size[1] = 2.0f * r;
    for (k = 0; k < 4; k++) p[0].radius[k] = 0.5f * r, p[1].radius[k] = r; /* capsule and circle */
    /* the drop swings across the bar, dipping into it at the ends */
    p[1].center[0] = 0.5f * w + 0.3f * w * (float)sin(seconds * 0.8);
    p[1].center[1] = p[0].center[1] + r * (1.6f - 0.9f * (float)fabs(sin(seconds * 0.8)));
    p[0].group = p[1].group = 1;
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    fd.depth = SNELL_DEPTH_CLEAR;
    fd.panels = p;
    fd.panel_count = 2;
    if (under) { /* a frame of panels only: the video is all that lies beneath */
        fd.panels_under = under;
        fd.draw_background = SNELL_BACKGROUND_NONE;
    } else {
        g.mesh = s->mesh;
        g.material = s->material;
        fd.env = s->env;
        fd.glass = &g;
        fd.glass_count = 1;
        fd.camera = s->camera;
        fd.camera.azimuth += (float)(seconds * 0.5);
    }
    if ((st = snell_render(s->renderer, &fd, NULL)) != SNELL_OK) return fail(s, st, "frame with panels");
    return SNELL_OK;
}

void glass_scene_destroy_gl(glass_scene *s)
{
    snell_renderer_destroy(s->renderer);
    snell_env_destroy(s->env);
    snell_mesh_destroy(s->mesh);
    snell_ctx_destroy(s->ctx);
    s->renderer = NULL;
    s->env = NULL;
    s->mesh = NULL;
    s->ctx = NULL;
    s->width = s->height = 0;
}

void glass_scene_free(glass_scene *s)
{
    glass_scene_destroy_gl(s);
    free(s->mesh_bytes);
    snell_image_free(s->env_rgba);
    s->mesh_bytes = NULL;
    s->env_rgba = NULL;
}
