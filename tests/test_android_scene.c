/* SPDX-License-Identifier: MIT */
/* test_android_scene — ports/android/glass_scene.c, the Android port's scene,
 * in a host-made GLES 3 context (EXTERNAL backend) as the port runs it in its
 * EGL window context: assets given as bytes (an OBJ or .glb mesh, a PNG
 * environment decoded with snell_image_decode) and released at once; a frame
 * shows the glass and the asset's environment; after a context loss (the EGL
 * context destroyed under the GL objects, then glass_scene_destroy_gl with no
 * context current) a new context gets the same frame, pixel for pixel, from
 * the kept CPU data; a resize makes a new renderer; glass panels lie over
 * the glass scene and over a texture drawn beneath them; bad assets fail
 * with a message and leave nothing behind. */
#include "test_util.h"
#include "glass_scene.h"

#include <GLES3/gl3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A closed cube, 8 vertices, 12 triangles (outward winding). */
static const char cube_obj[] = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                               "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                               "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                               "f 4 8 7\nf 4 7 3\nf 2 3 7\nf 2 7 6\nf 1 5 8\nf 1 8 4\n";

/* The window surface's stand-in: an RGBA8 + depth framebuffer, bound. */
typedef struct target {
    GLuint fbo, rb[2];
} target;

static void target_make(target *t, int w, int h)
{
    glGenRenderbuffers(2, t->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, t->rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, t->rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->rb[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->rb[1]);
    glViewport(0, 0, w, h);
}

static int draw_read(glass_scene *s, int w, int h, uint8_t *px)
{
    snell_status st;
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    st = glass_scene_draw(s, 1.0);
    CHECK(st == SNELL_OK, "draw: %s", s->error);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return st == SNELL_OK;
}

static int differ(const uint8_t *a, const uint8_t *b, int n)
{
    int i, d = 0;
    for (i = 0; i < n * 4; i++) d += a[i] != b[i];
    return d;
}

#define W 64
#define H 48

int main(void)
{
    EGLDisplay dpy;
    EGLContext first, second;
    glass_scene s, plain;
    target t;
    size_t png_size = 0, glb_size = 0, bad_size = 0;
    unsigned char *png, *glb, *bad;
    static uint8_t a[W * H * 4], b[W * H * 4], c[W * H * 4];
    const unsigned char *kept_mesh;
    const uint8_t *kept_env;
    int x, y;

    /* the environment asset: a PNG, left half red, right half blue */
    {
        static uint8_t img[32 * 16 * 4];
        for (y = 0; y < 16; y++)
            for (x = 0; x < 32; x++) {
                uint8_t *p = img + 4 * (y * 32 + x);
                p[0] = x < 16 ? 230 : 20; p[1] = (uint8_t)(y * 8); p[2] = x < 16 ? 20 : 230; p[3] = 255;
            }
        CHECK_OK(snell_write_png(test_out("android_env.png"), 32, 16, img));
    }
    png = test_read_file(test_out("android_env.png"), &png_size);
    glb = test_read_file(test_data("nodes.glb"), &glb_size);
    bad = test_read_file(test_data("images/bad_truncated.png"), &bad_size);
    CHECK(png && glb && bad, "test assets");
    if (!png || !glb || !bad) return test_finish();
    if (!test_host_context(&dpy, &first)) SKIP("cannot make a host GLES 3 context");

    /* assets as bytes, released (and overwritten) right after init */
    {
        char *obj = (char *)malloc(sizeof cube_obj);
        unsigned char *env = (unsigned char *)malloc(png_size);
        memcpy(obj, cube_obj, sizeof cube_obj);
        memcpy(env, png, png_size);
        CHECK_OK(glass_scene_init(&s, obj, sizeof cube_obj - 1, GLASS_MESH_OBJ, env, png_size));
        memset(obj, 'x', sizeof cube_obj);
        memset(env, 0xAA, png_size);
        free(obj);
        free(env);
    }
    CHECK(s.env_width == 32 && s.env_height == 16, "decoded environment %dx%d", s.env_width, s.env_height);
    CHECK(glass_scene_draw(&s, 0) == SNELL_E_INVALID_ARG, "a draw before the GL objects fails");
    kept_mesh = s.mesh_bytes;
    kept_env = s.env_rgba;

    target_make(&t, W, H);
    CHECK(glass_scene_create_gl(&s, W, H) == SNELL_OK, "create_gl: %s", s.error);
    CHECK(s.mesh && snell_mesh_triangle_count(s.mesh) == 12, "the OBJ asset's cube");
    draw_read(&s, W, H, a);
    /* what it shows: the glass (against IOR 1, which draws nothing) and the
     * asset's environment (against the procedural sky) */
    s.material.ior = 1.0f;
    draw_read(&s, W, H, b);
    s.material.ior = 1.5f;
    CHECK(differ(a, b, W * H) > W * H / 20, "the glass changes %d of %d pixels", differ(a, b, W * H) / 4, W * H);
    CHECK_OK(glass_scene_init(&plain, cube_obj, sizeof cube_obj - 1, GLASS_MESH_OBJ, NULL, 0));
    CHECK(glass_scene_create_gl(&plain, W, H) == SNELL_OK, "create_gl: %s", plain.error);
    draw_read(&plain, W, H, c);
    CHECK(differ(a, c, W * H) > W * H / 4, "the environment asset is what the frame shows");
    glass_scene_free(&plain);

    /* context loss: the context goes under the GL objects */
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, first);
    glass_scene_destroy_gl(&s); /* LIFECYCLE_DESTROY_GL_OBJECTS: no context current, memory only */
    CHECK(!s.ctx && !s.renderer && !s.env && !s.mesh, "GL objects dropped");
    CHECK(s.mesh_bytes == kept_mesh && s.env_rgba == kept_env, "CPU data kept");
    if (!test_host_context(&dpy, &second)) {
        CHECK(0, "a second host context");
        return test_finish();
    }
    target_make(&t, W, H);
    CHECK(glass_scene_create_gl(&s, W, H) == SNELL_OK, "create_gl after the loss: %s", s.error);
    draw_read(&s, W, H, c);
    CHECK(differ(a, c, W * H) == 0, "after the loss %d bytes differ from the first context's frame",
          differ(a, c, W * H));
    CHECK(s.gl_generation == 2, "GL objects made %u times", s.gl_generation);

    /* a surface size change: a new renderer for the new size */
    target_make(&t, 40, 30);
    CHECK_OK(glass_scene_resize(&s, 40, 30));
    CHECK(s.width == 40 && s.height == 30 && s.renderer, "resized to %dx%d", s.width, s.height);
    {
        static uint8_t small[40 * 30 * 4];
        draw_read(&s, 40, 30, small);
    }
    { /* into the app's frame (a red wall at depth 0.99), through the app's camera:
       * the corners stay the app's, the glass shows the wall through it */
        static uint8_t app[40 * 30 * 4];
        float eye[3], view[16], proj[16];
        const uint8_t *centre = app + 4 * (15 * 40 + 20), *corner = app;
        snell_camera_matrices(&s.camera, 40.0f / 30.0f, eye, view, proj);
        glClearColor(0.9f, 0.1f, 0.1f, 1.0f);
        glClearDepthf(0.99f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glClearDepthf(1.0f);
        CHECK(glass_scene_draw_in(&s, view, proj) == SNELL_OK, "draw_in: %s", s.error);
        glReadPixels(0, 0, 40, 30, GL_RGBA, GL_UNSIGNED_BYTE, app);
        printf("in the app's frame: corner %d %d %d, centre %d %d %d\n", corner[0], corner[1], corner[2], centre[0],
               centre[1], centre[2]);
        CHECK(corner[0] == 230 && corner[1] == 26 && corner[2] == 26, "the app's corner pixel changed");
        CHECK(centre[0] != 230 && centre[0] > 2 * centre[1] && centre[0] > 2 * centre[2],
              "the glass shows the app's red frame: %d %d %d", centre[0], centre[1], centre[2]);
        CHECK(glass_scene_draw_in(&s, NULL, proj) == SNELL_E_INVALID_ARG, "draw_in without a view");
    }
    { /* glass panels (the sample's bar and drop): over the glass scene, then
       * over an app's texture drawn first, as the video's external texture is */
        static uint8_t scene_px[40 * 30 * 4], panels_px[40 * 30 * 4], tex_px[40 * 30 * 4], green[4 * 4 * 4];
        const uint8_t *corner = tex_px + 4 * (29 * 40);
        snell_panels_under under;
        GLuint tex = 0;
        int k, glass = 0;
        draw_read(&s, 40, 30, scene_px);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        CHECK(glass_scene_draw_panels(&s, 1.0, NULL) == SNELL_OK, "draw_panels: %s", s.error);
        glReadPixels(0, 0, 40, 30, GL_RGBA, GL_UNSIGNED_BYTE, panels_px);
        CHECK(differ(scene_px, panels_px, 40 * 30) > 40 * 30 / 10, "the panels change %d bytes of the glass scene",
              differ(scene_px, panels_px, 40 * 30));
        for (k = 0; k < 16; k++) green[4 * k] = 20, green[4 * k + 1] = 200, green[4 * k + 2] = 40, green[4 * k + 3] = 255;
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, green);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glBindTexture(GL_TEXTURE_2D, 0);
        memset(&under, 0, sizeof under);
        under.source = SNELL_PANELS_UNDER_TEXTURE;
        under.texture = tex;
        under.draw = 1;
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        CHECK(glass_scene_draw_panels(&s, 1.0, &under) == SNELL_OK, "draw_panels over a texture: %s", s.error);
        glReadPixels(0, 0, 40, 30, GL_RGBA, GL_UNSIGNED_BYTE, tex_px);
        for (k = 0; k < 40 * 30; k++) glass += memcmp(tex_px + 4 * k, green, 3) != 0;
        CHECK(corner[0] == 20 && corner[1] == 200 && corner[2] == 40, "the texture drawn beneath: corner %d %d %d",
              corner[0], corner[1], corner[2]);
        CHECK(glass > 40 * 30 / 20, "the panels over the texture: %d pixels not its green", glass);
        glDeleteTextures(1, &tex);
    }
    glass_scene_free(&s);
    CHECK(!s.mesh_bytes && !s.env_rgba && !s.ctx, "freed");

    /* a .glb asset through snell_mesh_load_gltf_mem: nodes.glb's 5 triangles */
    target_make(&t, W, H);
    CHECK_OK(glass_scene_init(&s, glb, glb_size, GLASS_MESH_GLTF, NULL, 0));
    CHECK(glass_scene_create_gl(&s, W, H) == SNELL_OK, "create_gl (glb): %s", s.error);
#ifdef SNELL_WITH_GLTF
    CHECK(s.mesh && snell_mesh_triangle_count(s.mesh) == 5, "nodes.glb: 5 triangles");
#endif
    glass_scene_free(&s);

    /* bad assets: a clear failure, nothing left behind */
    CHECK(glass_scene_init(&s, cube_obj, sizeof cube_obj - 1, GLASS_MESH_OBJ, bad, bad_size) != SNELL_OK &&
              s.error[0] && !s.mesh_bytes && !s.env_rgba,
          "a truncated PNG asset fails cleanly: %s", s.error);
    printf("bad environment asset: %s\n", s.error);
    CHECK_OK(glass_scene_init(&s, glb, glb_size / 2, GLASS_MESH_GLTF, NULL, 0));
    CHECK(glass_scene_create_gl(&s, W, H) != SNELL_OK && !s.ctx && !s.mesh && strstr(s.error, "mesh"),
          "a truncated .glb asset fails cleanly: %s", s.error);
    printf("bad mesh asset: %s\n", s.error);
    glass_scene_free(&s);

    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, second);
    free(png);
    free(glb);
    free(bad);
    return test_finish();
}
