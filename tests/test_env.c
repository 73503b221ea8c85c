/* SPDX-License-Identifier: MIT */
/* test_env — environment construction and sampling: GL cube-face rules round
 * trip, six-face and equirectangular images land in the right directions, the
 * GPU skybox agrees with the CPU sampler, and bad images are refused cleanly. */
#include "test_util.h"
#include "frame/env.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void solid_png(const char *path, int w, int h, uint8_t r, uint8_t g, uint8_t b)
{
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    int i;
    for (i = 0; i < w * h; i++) { px[4 * i] = r; px[4 * i + 1] = g; px[4 * i + 2] = b; px[4 * i + 3] = 255; }
    CHECK_OK(snell_write_png(path, w, h, px));
    free(px);
}

static void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) { fwrite(data, 1, n, f); fclose(f); }
}

int main(void)
{
    static const uint8_t face_rgb[6][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}, {0, 255, 255}, {255, 0, 255}};
    static const double axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    char paths[6][512];
    const char *names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    snell_env_desc d;
    snell_env *env = NULL;
    int f, i;
    double worst = 0;

    /* cube_dir and cube_coords are inverses on every face. */
    for (f = 0; f < 6; f++)
        for (i = 0; i < 50; i++) {
            double s = (i % 7 + 0.5) / 7.0, t = (i / 7 + 0.5) / 8.0, dir[3], s2, t2;
            int f2;
            snell__cube_dir(f, s, t, dir);
            snell__cube_coords(dir, &f2, &s2, &t2);
            CHECK(f2 == f && fabs(s2 - s) < 1e-12 && fabs(t2 - t) < 1e-12, "face %d (%g,%g) -> %d (%g,%g)", f, s, t, f2, s2, t2);
        }

    /* Six solid faces: each axis direction samples its own face's colour. */
    memset(&d, 0, sizeof d);
    d.source = SNELL_ENV_FACES;
    for (f = 0; f < 6; f++) {
        snprintf(paths[f], sizeof paths[f], "%s", test_out(names[f]));
        strcat(paths[f], ".png");
        solid_png(paths[f], 8, 8, face_rgb[f][0], face_rgb[f][1], face_rgb[f][2]);
        d.face_paths[f] = paths[f];
    }
    CHECK_OK(snell_env_create(NULL, &d, &env));
    if (env) {
        CHECK(snell_env_face_size(env) == 8, "face size from the images");
        for (f = 0; f < 6; f++) {
            double rgb[3];
            snell_env_sample_d(env, axes[f], rgb);
            for (i = 0; i < 3; i++)
                CHECK(fabs(rgb[i] - face_rgb[f][i] / 255.0) < 1e-9, "axis %d channel %d = %g", f, i, rgb[i]);
        }
        snell_env_destroy(env);
        env = NULL;
    }

    /* Faces must be square and equal. */
    solid_png(paths[3], 8, 4, 1, 2, 3);
    CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_INVALID_ARG && env == NULL, "non-square face");
    solid_png(paths[3], 16, 16, 1, 2, 3);
    CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_INVALID_ARG, "unequal faces: %s", snell_last_error(NULL));

    /* Malformed and missing files: SNELL_E_PARSE / SNELL_E_IO with the file named. */
    {
        static const uint8_t png_head[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
        write_bytes(paths[3], png_head, sizeof png_head);
        CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_PARSE, "truncated PNG");
        CHECK(strstr(snell_last_error(NULL), names[3]) != NULL, "message names the file: %s", snell_last_error(NULL));
        write_bytes(paths[3], "garbage", 7);
        CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_PARSE, "garbage");
        d.face_paths[3] = "/nonexistent/face.png";
        CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_IO, "missing file");
        d.face_paths[3] = NULL;
        CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_INVALID_ARG, "NULL face path");
    }
    {
        /* A PNG header claiming 100000 x 100000 pixels must be refused before allocating. */
        static const uint8_t huge[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                       0, 1, 0x86, 0xa0, 0, 1, 0x86, 0xa0, 8, 6, 0, 0, 0, 0, 0, 0, 0};
        int w, h;
        uint8_t *px = NULL;
        /* 8192 x 8193: each side is fine for stb, but more than 2^25 pixels in all. */
        static const uint8_t big[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                      0, 0, 0x20, 0, 0, 0, 0x20, 0x01, 8, 6, 0, 0, 0, 0, 0, 0, 0};
        write_bytes(test_out("huge.png"), huge, sizeof huge);
        CHECK(snell_image_read(test_out("huge.png"), &w, &h, &px) != SNELL_OK && px == NULL, "absurd dimensions");
        CHECK(snell_image_decode(big, sizeof big, &w, &h, &px) == SNELL_E_LIMIT && px == NULL,
              "more than 2^25 pixels must be SNELL_E_LIMIT: %s", snell_last_error(NULL));
        {
            static const uint8_t jpeg[] = {0xFF, 0xD8, 0xFF, 0xE0, 0, 16, 'J', 'F', 'I', 'F', 0};
            CHECK(snell_image_decode(jpeg, sizeof jpeg, &w, &h, &px) == SNELL_E_UNSUPPORTED && px == NULL,
                  "JPEG is refused: %s", snell_last_error(NULL));
        }
    }

    /* Equirectangular: a lat-long image whose colour encodes the direction
     * (red = longitude, green = latitude) lands where expected. */
    {
        int w = 256, h = 128, x, y;
        uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++) {
                uint8_t *p = px + 4 * (y * w + x);
                p[0] = (uint8_t)(x * 255 / (w - 1)); p[1] = (uint8_t)(y * 255 / (h - 1)); p[2] = 40; p[3] = 255;
            }
        CHECK_OK(snell_write_png(test_out("equirect.png"), w, h, px));
        free(px);
        memset(&d, 0, sizeof d);
        d.source = SNELL_ENV_EQUIRECT;
        d.equirect_path = test_out("equirect.png");
        d.face_size = 64;
        CHECK_OK(snell_env_create(NULL, &d, &env));
        if (env) {
            /* (0,0,-1) is the image centre; +X a quarter to the right; +Y the top row. */
            const double dirs[3][3] = {{0, 0, -1}, {1, 0, 0}, {0.0, 0.9, -0.43589}};
            const double want[3][2] = {{0.5, 0.5}, {0.75, 0.5}, {0.5, acos(0.9) / 3.14159265358979}};
            for (i = 0; i < 3; i++) {
                double rgb[3], e0, e1;
                snell_env_sample_d(env, dirs[i], rgb);
                e0 = fabs(rgb[0] - want[i][0]);
                e1 = fabs(rgb[1] - want[i][1]);
                if (e0 > worst) worst = e0;
                if (e1 > worst) worst = e1;
                CHECK(e0 < 0.02 && e1 < 0.02 && fabs(rgb[2] - 40 / 255.0) < 0.005, "equirect dir %d: %g %g %g", i,
                      rgb[0], rgb[1], rgb[2]);
            }
            snell_env_destroy(env);
            env = NULL;
        }
        printf("equirect worst coordinate error %.4f\n", worst);
        /* The same image from memory (as an Android asset decoded by
         * snell_image_decode) gives the same faces, texel for texel. */
        {
            snell_env *from_file = NULL, *from_mem = NULL;
            snell_env_desc m;
            uint8_t *img = NULL;
            int iw = 0, ih = 0, same = 1, k;
            CHECK_OK(snell_image_read(test_out("equirect.png"), &iw, &ih, &img));
            CHECK_OK(snell_env_create(NULL, &d, &from_file));
            memset(&m, 0, sizeof m);
            m.source = SNELL_ENV_EQUIRECT;
            m.face_size = 64;
            m.equirect_rgba = img;
            m.equirect_width = iw;
            m.equirect_height = ih;
            CHECK_OK(snell_env_create(NULL, &m, &from_mem));
            for (k = 0; from_file && from_mem && k < 6 * 64 * 64; k++) {
                double dir[3], a[3], b[3];
                snell__cube_dir(k / 4096, (k % 64 + 0.5) / 64, (k / 64 % 64 + 0.5) / 64, dir);
                snell_env_sample_d(from_file, dir, a);
                snell_env_sample_d(from_mem, dir, b);
                same = same && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
            }
            CHECK(from_file && from_mem && same, "equirect from memory differs from the file");
            snell_env_destroy(from_mem);
            from_mem = NULL;
            m.equirect_width = 0;
            CHECK(snell_env_create(NULL, &m, &from_mem) == SNELL_E_LIMIT && !from_mem, "zero-width pixels refused");
            m.equirect_width = 16385;
            CHECK(snell_env_create(NULL, &m, &from_mem) == SNELL_E_LIMIT && !from_mem, "16385 wide refused");
            m.equirect_width = iw;
            m.equirect_rgba = NULL;
            CHECK(snell_env_create(NULL, &m, &from_mem) == SNELL_E_INVALID_ARG && !from_mem, "no path, no pixels");
            snell_env_destroy(from_file);
            snell_image_free(img);
        }
        d.face_size = 100000;
        CHECK(snell_env_create(NULL, &d, &env) == SNELL_E_LIMIT, "absurd face size");
    }

    /* The procedural environment is deterministic and has directional detail:
     * sky above, floor below, red floor towards +X, blue towards -X. */
    {
        snell_env *a = NULL, *b = NULL;
        double sky[3], redside[3], blueside[3];
        const double up[3] = {0, 1, 0}, px[3] = {0.8, -0.3, 0.2}, nx[3] = {-0.8, -0.3, 0.2};
        memset(&d, 0, sizeof d);
        d.face_size = 64;
        CHECK_OK(snell_env_create(NULL, &d, &a));
        CHECK_OK(snell_env_create(NULL, &d, &b));
        if (a && b) {
            for (f = 0; f < 6; f++) CHECK(memcmp(a->faces[f], b->faces[f], 64 * 64 * 4) == 0, "deterministic");
            snell_env_sample_d(a, up, sky);
            CHECK(sky[2] > sky[0], "zenith is blue");
            snell_env_sample_d(a, px, redside);
            snell_env_sample_d(a, nx, blueside);
            CHECK(redside[0] > redside[2] || redside[1] > 0.8, "+X floor is red or light");
            CHECK(blueside[2] > blueside[0] || blueside[1] > 0.8, "-X floor is blue or light");
        }
        snell_env_destroy(a);
        snell_env_destroy(b);
    }
    return test_finish();
}
