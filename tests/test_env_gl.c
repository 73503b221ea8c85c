/* SPDX-License-Identifier: MIT */
/* test_env_gl — an environment from the host's GL cube map
 * (SNELL_ENV_GL_TEXTURE): borrowing the texture of a procedural environment
 * gives the same bytes as that environment (cube and dual-paraboloid
 * look-ups); what the host then draws into it shows in the next frame (not
 * copied), in both look-ups; the reference refuses it with
 * SNELL_E_UNSUPPORTED naming why, snell_env_sample gives black, destroying
 * it leaves the host's texture alone; a 2D texture, no face size or no
 * context are refused. */
#include "test_util.h"
#include "frame/env.h"
#include "snell/snell_ref.h"

#include <GLES3/gl3.h>
#include <string.h>

#define N 48

static void render(snell_ctx *ctx, snell_renderer *r, const snell_env *env, const snell_mesh *m, uint8_t *px)
{
    snell_glass g;
    snell_frame_desc fd;
    test_frame_one(&fd, &g, m, env);
    g.material.ior = 1.5f;
    CHECK_OK_CTX(ctx, snell_render(r, &fd, NULL));
    CHECK_OK_CTX(ctx, snell_renderer_read_rgba(r, px));
}

int main(void)
{
    static uint8_t a[N * N * 4], b[N * N * 4], c[N * N * 4], red[16 * 16 * 4];
    snell_ctx *ctx = test_ctx();
    snell_renderer *r[2] = {NULL, NULL};
    snell_renderer_desc rd = {.width = N, .height = N};
    snell_env *own = NULL, *host = NULL, *bad = NULL;
    snell_env_desc ed;
    snell_mesh *sphere = NULL;
    snell_ref *ref = NULL;
    snell_ref_params p;
    snell_glass g;
    snell_frame_desc fd;
    float rgb[3] = {1, 1, 1}, up[3] = {0, 1, 0}, out[4 * 4 * 3];
    GLuint tex2d;
    int i, k;
    if (!ctx) SKIP("no GL context");
    CHECK_OK_CTX(ctx, snell_mesh_create_shape(ctx, &(snell_shape_desc){.shape = SNELL_SHAPE_SPHERE}, &sphere));
    own = test_sky(ctx, 16);
    for (k = 0; k < 2; k++) {
        rd.env_lookup = k ? SNELL_ENV_LOOKUP_DUAL_PARABOLOID : SNELL_ENV_LOOKUP_AUTO;
        CHECK_OK_CTX(ctx, snell_renderer_create(ctx, &rd, &r[k]));
    }
    if (!sphere || !own || !r[0] || !r[1]) return test_finish();
    memset(&ed, 0, sizeof ed);
    ed.source = SNELL_ENV_GL_TEXTURE;
    ed.gl_texture = own->texture;
    ed.face_size = 16;
    CHECK_OK_CTX(ctx, snell_env_create(ctx, &ed, &host));
    if (!host) return test_finish();
    for (k = 0; k < 2; k++) {
        render(ctx, r[k], own, sphere, a);
        render(ctx, r[k], host, sphere, b);
        CHECK(!memcmp(a, b, sizeof a), "look-up %d: the borrowed cube differs from its own environment", k);
    }
    /* the host draws into its cube: the next frames see it */
    for (i = 0; i < 16 * 16; i++) red[4 * i] = 255, red[4 * i + 3] = 255;
    glBindTexture(GL_TEXTURE_CUBE_MAP, own->texture);
    for (i = 0; i < 6; i++)
        glTexSubImage2D((GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + i), 0, 0, 0, 16, 16, GL_RGBA, GL_UNSIGNED_BYTE, red);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    for (k = 0; k < 2; k++) {
        int reds = 0;
        render(ctx, r[k], host, sphere, c);
        for (i = 0; i < N * N; i++) reds += c[4 * i] > 200 && c[4 * i + 1] < 40 && c[4 * i + 2] < 40;
        printf("look-up %d: %d of %d pixels red after the host's update\n", k, reds, N * N);
        CHECK(reds > N * N * 9 / 10, "look-up %d: the host's update shows on %d of %d pixels", k, reds, N * N);
    }
    /* no CPU copy: the reference refuses, sampling gives black */
    test_frame_one(&fd, &g, sphere, host);
    CHECK_OK(test_ref_create(ctx, &fd, &ref));
    if (ref) {
        test_ref_params(&fd, 4, 4, 0, &p);
        CHECK(test_ref_render(ref, &p, out, NULL, NULL) == SNELL_E_UNSUPPORTED &&
                  strstr(snell_last_error(ctx), "SNELL_ENV_GL_TEXTURE") != NULL,
              "the reference on a host's texture: %s", snell_last_error(ctx));
    }
    snell_ref_destroy(ref);
    snell_env_sample(host, up, rgb);
    CHECK(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f, "snell_env_sample on a host's texture: not black");
    snell_env_destroy(host);
    CHECK(glIsTexture(own->texture), "destroying the environment deleted the host's texture");
    /* refusals */
    glGenTextures(1, &tex2d);
    glBindTexture(GL_TEXTURE_2D, tex2d);
    glBindTexture(GL_TEXTURE_2D, 0);
    ed.gl_texture = tex2d;
    CHECK(snell_env_create(ctx, &ed, &bad) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "not a cube map"),
          "a 2D texture: %s", snell_last_error(ctx));
    ed.gl_texture = own->texture;
    ed.face_size = 0;
    CHECK(snell_env_create(ctx, &ed, &bad) == SNELL_E_INVALID_ARG && strstr(snell_last_error(ctx), "face_size"),
          "no face size: %s", snell_last_error(ctx));
    ed.face_size = 16;
    CHECK(snell_env_create(NULL, &ed, &bad) == SNELL_E_INVALID_ARG, "no context");
    glDeleteTextures(1, &tex2d);
    snell_renderer_destroy(r[0]);
    snell_renderer_destroy(r[1]);
    snell_env_destroy(own);
    snell_mesh_destroy(sphere);
    snell_ctx_destroy(ctx);
    return test_finish();
}
