/* Uses only the installed public header: makes a context, renders one small
 * frame of one glass object and checks that glass pixels differ from the
 * plain background. */
#include <snell/snell.h>
#include <stdio.h>
#include <string.h>

int main(void)
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
    printf("consumer %s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
