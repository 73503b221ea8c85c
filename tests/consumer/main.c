/* SPDX-License-Identifier: MIT */
/* Uses only the installed public header: makes a context, renders one small
 * frame of one glass object and checks that glass pixels differ from the
 * plain background; then loads the .glb named by argv[1], if any (tests/data/nodes.glb),
 * which pulls the glTF loader, a C++ object, into a C program: a static link
 * without the C++ runtime fails here. */
#include <snell/snell.h>
#include <stdio.h>
#include <string.h>

/* nodes.glb's default scene, as tests/data/make_gltf.py defines it: mesh 0
 * and mesh 1 (one triangle each) under node 0, mesh 2 (a quad strip: two)
 * and mesh 3 (one). */
#define NODES_GLB_TRIANGLES 5u

static int load_glb(const char *path)
{
    snell_mesh *mesh = NULL;
    int ok;
    if (snell_mesh_load_gltf(NULL, path, &mesh) != SNELL_OK) {
        fprintf(stderr, "consumer: %s\n", snell_last_error(NULL));
        return 0;
    }
    ok = snell_mesh_triangle_count(mesh) == NODES_GLB_TRIANGLES;
    if (!ok)
        fprintf(stderr, "consumer: %s has %u triangles, expected %u\n", path, snell_mesh_triangle_count(mesh),
                NODES_GLB_TRIANGLES);
    snell_mesh_destroy(mesh);
    return ok;
}

int main(int argc, char **argv)
{
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_shape_desc sd;
    snell_env_desc ed;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_glass g;
    snell_glass_resolved res;
    static uint8_t a[32 * 32 * 4], b[32 * 32 * 4];
    int ok;
    memset(&sd, 0, sizeof sd);
    memset(&ed, 0, sizeof ed);
    memset(&rd, 0, sizeof rd);
    memset(&fd, 0, sizeof fd);
    memset(&g, 0, sizeof g);
    ed.face_size = 32;
    rd.width = rd.height = 32;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK || snell_mesh_create_shape(ctx, &sd, &mesh) != SNELL_OK ||
        snell_env_create(ctx, &ed, &env) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        fprintf(stderr, "consumer: %s %s\n", snell_last_error(NULL), snell_last_error(ctx));
        return 1;
    }
    fd.env = env;
    ok = snell_render(r, &fd, NULL) == SNELL_OK && snell_renderer_read_rgba(r, a) == SNELL_OK;
    g.mesh = mesh;
    fd.glass = &g;
    fd.glass_count = 1;
    ok = ok && snell_render(r, &fd, NULL) == SNELL_OK && snell_renderer_read_rgba(r, b) == SNELL_OK;
    ok = ok && memcmp(a, b, sizeof a) != 0;
    /* the material defaults and the method registry are exported too */
    ok = ok && snell_glass_defaults(NULL, &res) == SNELL_OK && res.material.ior == 1.5f &&
         strcmp(snell_method_str(SNELL_METHOD_CUBEMAP), "cubemap") == 0;
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_ctx_destroy(ctx);
    if (argc > 1) /* given when the library has the glTF loader (tests/core.cmake) */
        ok = ok && load_glb(argv[1]);
    printf("consumer %s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
