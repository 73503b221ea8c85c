/* SPDX-License-Identifier: MIT */
/* test_resolve_order — descriptors are resolved once, then the resolved copy
 * is validated (sokol_gfx's order; render/defaults.c): a refusal names the
 * value the frame or material would have used (a derived far plane, a
 * resolved scale), never re-encodes a default ("0 = ..."), and a zero that
 * means a default is never refused. */
#include "test_util.h"
#include "snell/snell.h"

#include <GLES3/gl3.h>
#include <string.h>

static snell_ctx *g_ctx;

/* The call failed with SNELL_E_INVALID_ARG, its message holding want and no " 0 =", "(0 =", " 0 (" or "(0:". */
static void refused(snell_status st, const char *want, const char *what)
{
    const char *msg = snell_last_error(g_ctx);
    CHECK(st == SNELL_E_INVALID_ARG, "%s: status %d, %s", what, (int)st, msg);
    CHECK(strstr(msg, want) != NULL, "%s: \"%s\" lacks \"%s\"", what, msg, want);
    CHECK(!strstr(msg, " 0 =") && !strstr(msg, "(0 =") && !strstr(msg, " 0 (") && !strstr(msg, "(0:"),
          "%s: \"%s\" re-encodes a default", what, msg);
}

int main(void)
{
    snell_env *env;
    snell_renderer *r;
    snell_mesh *mesh = NULL;
    snell_shape_desc sd;
    snell_frame_desc fd;
    snell_glass g;
    snell_backdrop b;
    snell_glass_material m;
    snell_glass_resolved gr;
    snell_ctx *ctx = test_ctx();
    GLuint tex = 0;
    if (!ctx) return 77;
    g_ctx = ctx;
    env = test_sky(g_ctx, 16);
    r = test_renderer(g_ctx, 16, 16);
    memset(&sd, 0, sizeof sd);
    sd.shape = SNELL_SHAPE_SPHERE;
    CHECK_OK(snell_mesh_create_shape(g_ctx, &sd, &mesh));
    if (!env || !r || !mesh) return test_finish();
    test_frame_one(&fd, &g, mesh, env);
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, NULL)); /* every zero a default: drawn */

    /* The far plane derived from the distance is named with its value. */
    fd.camera.distance = 2.0f, fd.camera.z_near = 1000.0f;
    refused(snell_render(r, &fd, NULL), "camera.z_far 200 (derived from the distance)", "z_near past the far plane");
    fd.camera.z_near = 0.0f, fd.camera.fov_y = -0.5f;
    refused(snell_render(r, &fd, NULL), "camera.fov_y -0.5", "fov_y < 0");
    fd.camera.fov_y = 0.0f;
    fd.scene_layers = 1;
    refused(snell_render(r, &fd, NULL), "scene_layers 1: -1 (off) or 2..", "scene_layers 1");
    fd.scene_layers = 0;
    memset(&b, 0, sizeof b);
    b.source = SNELL_BACKDROP_TEXTURES, b.width = b.height = 16, b.distance = -1.0f;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, 16, 16);
    b.color_texture = tex; /* a texture of this context: refused for its distance alone */
    fd.backdrop = &b;
    refused(snell_render(r, &fd, NULL), "backdrop.distance -1: a finite distance > 0", "backdrop.distance -1");
    fd.backdrop = NULL;
    CHECK_OK_CTX(g_ctx, snell_render(r, &fd, NULL));

    /* A material: its scale resolved (0 is 1) before the range is checked, and named. */
    memset(&m, 0, sizeof m);
    CHECK_OK(snell_glass_defaults(&m, &gr));
    CHECK(gr.material.scale == 1.0f && gr.material.ior == 1.5f, "resolved scale %g, ior %g", gr.material.scale,
          gr.material.ior);
    m.scale = 0.5f;
    g_ctx = NULL; /* snell_glass_defaults has no context: its message is the thread's */
    refused(snell_glass_defaults(&m, &gr), "scale 0.5 outside 1..", "scale 0.5");

    glDeleteTextures(1, &tex);
    snell_mesh_destroy(mesh);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    return test_finish();
}
