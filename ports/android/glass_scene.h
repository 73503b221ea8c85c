/* SPDX-License-Identifier: MIT */
/* glass_scene — what the Android port draws, split into the CPU data that
 * lives as long as the activity (asset bytes, the decoded environment image,
 * the scene's settings) and the GL objects that live as long as one EGL
 * context (snell's EXTERNAL context, mesh, environment, renderer). After a
 * context loss glass_scene_create_gl() makes the GL half again from the CPU
 * half; nothing is read from the APK twice. Plain C on snell's public API,
 * so the host's ctest runs it (test_android_scene) in a Mesa context. */
#ifndef SNELL_ANDROID_GLASS_SCENE_H
#define SNELL_ANDROID_GLASS_SCENE_H

#include <snell/snell.h>
#include <stddef.h>

typedef enum glass_mesh_format { GLASS_MESH_GLTF = 0, GLASS_MESH_OBJ } glass_mesh_format;

typedef struct glass_scene {
    /* CPU data, kept across contexts */
    unsigned char *mesh_bytes;  /* the mesh asset as read (.glb/.gltf or .obj); NULL = a sphere */
    size_t mesh_size;
    glass_mesh_format mesh_format;
    uint8_t *env_rgba;          /* the environment asset decoded once; NULL = procedural sky */
    int env_width, env_height;
    snell_glass_material material;
    snell_camera camera;
    /* GL objects of the current context (all NULL between contexts) */
    snell_ctx *ctx;
    snell_mesh *mesh;
    snell_env *env;
    snell_renderer *renderer;
    int width, height;          /* the renderer's size, that of the surface */
    unsigned gl_generation;     /* glass_scene_create_gl calls that succeeded */
    char error[256];            /* why the last failing call failed */
} glass_scene;

/* Copies the mesh asset (may be NULL: a sphere) and decodes the environment
 * image (PNG or HDR bytes, may be NULL: procedural) with snell_image_decode.
 * No GL; the assets' memory may be released after it. */
snell_status glass_scene_init(glass_scene *s, const void *mesh, size_t mesh_size, glass_mesh_format format,
                              const void *env_image, size_t env_size);
/* Makes the GL objects in the current GLES 3.0 context (SNELL_BACKEND_EXTERNAL)
 * for a width x height target. Any GL objects already held are destroyed first. */
snell_status glass_scene_create_gl(glass_scene *s, int width, int height);
/* Follows a surface size change (a new renderer; mesh and environment stay). */
snell_status glass_scene_resize(glass_scene *s, int width, int height);
/* Draws one frame into the bound framebuffer, the camera turned by seconds. */
snell_status glass_scene_draw(glass_scene *s, double seconds);
/* Draws the glass into the app's own frame, bound with its opaque scene
 * drawn: through the app's camera (view and projection, column-major, GL
 * clip conventions), depth-tested against what the app drew, refracting it
 * (snell copies the bound framebuffer's colour and depth: a backdrop of
 * SNELL_BACKDROP_COPY_BOUND), nothing drawn where the glass is not. */
snell_status glass_scene_draw_in(glass_scene *s, const float view[16], const float projection[16]);
/* Glass panels (snell_panels.h) in the surface's pixels: a bar along the
 * bottom and a drop that slides over it, merging with it and leaving it
 * (one group), moved by seconds. under NULL: over the glass scene, drawn in
 * the same frame (what the frame drew lies beneath). Else a frame of panels
 * only over what under names: the video's GL_TEXTURE_EXTERNAL_OES with its
 * SurfaceTexture's transform (snell_activity.c), drawn first when under->draw. */
snell_status glass_scene_draw_panels(glass_scene *s, double seconds, const snell_panels_under *under);
/* Destroys the GL objects (in their context if it is current; after a loss
 * the dead context ignores the deletes) and keeps the CPU data. */
void glass_scene_destroy_gl(glass_scene *s);
/* Everything, GL objects first. */
void glass_scene_free(glass_scene *s);

#endif
