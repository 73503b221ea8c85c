/* image.c — PNG/JPEG/HDR input and PNG output through stb (libstb-dev headers).
 * The stb implementations are compiled here with static linkage so they never
 * clash with a host application's own copy of stb. */
#include "core.h"

#define STBI_MAX_DIMENSIONS 16384
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_HDR
#define STBI_FAILURE_USERMSG
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
/* stb is third-party code: its warnings (some reported at the end of the
 * translation unit) are silenced for this file only. */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb_image.h>
#include <stb_image_write.h>

#include <stdlib.h>
#include <string.h>

snell_status snell_write_png(const char *path, int width, int height, const uint8_t *rgba)
{
    if (!path || !rgba || width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_write_png: bad arguments (%dx%d)", width, height);
    if (!stbi_write_png(path, width, height, 4, rgba, width * 4))
        return snell__fail(NULL, SNELL_E_IO, "cannot write PNG \"%s\"", path);
    return SNELL_OK;
}

static int has_suffix_ci(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix), i;
    if (m > n) return 0;
    for (i = 0; i < m; i++) {
        char a = s[n - m + i], b = suffix[i];
        if (a >= 'A' && a <= 'Z') a = (char)(a - 'A' + 'a');
        if (a != b) return 0;
    }
    return 1;
}

snell_status snell_image_read(const char *path, int *width, int *height, uint8_t **rgba)
{
    int w = 0, h = 0, n = 0;
    FILE *f;
    if (!path || !width || !height || !rgba)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_image_read: NULL argument");
    *rgba = NULL;
    f = fopen(path, "rb");
    if (!f) return snell__fail(NULL, SNELL_E_IO, "cannot open image \"%s\"", path);
    if (!stbi_info_from_file(f, &w, &h, &n)) {
        fclose(f);
        return snell__fail(NULL, SNELL_E_PARSE, "\"%s\" is not a readable PNG/JPEG/HDR image (%s)", path,
                           stbi_failure_reason());
    }
    fseek(f, 0, SEEK_SET);
    if (stbi_is_hdr_from_file(f) || has_suffix_ci(path, ".hdr")) {
        /* HDR: clamp to the displayable range; the library's env is RGBA8. */
        float *px = stbi_loadf_from_file(f, &w, &h, &n, 4);
        size_t i, count;
        fclose(f);
        if (!px) return snell__fail(NULL, SNELL_E_PARSE, "cannot decode \"%s\": %s", path, stbi_failure_reason());
        count = (size_t)w * (size_t)h * 4;
        *rgba = (uint8_t *)malloc(count);
        if (!*rgba) {
            stbi_image_free(px);
            return snell__fail(NULL, SNELL_E_NOMEM, "out of memory decoding \"%s\"", path);
        }
        for (i = 0; i < count; i++) {
            float v = px[i] < 0.0f ? 0.0f : px[i] > 1.0f ? 1.0f : px[i];
            (*rgba)[i] = (uint8_t)(v * 255.0f + 0.5f);
        }
        stbi_image_free(px);
    } else {
        *rgba = stbi_load_from_file(f, &w, &h, &n, 4);
        fclose(f);
        if (!*rgba) return snell__fail(NULL, SNELL_E_PARSE, "cannot decode \"%s\": %s", path, stbi_failure_reason());
    }
    *width = w;
    *height = h;
    return SNELL_OK;
}

/* stb_image allocates with malloc (STBI_MALLOC default), as does the HDR path. */
void snell_image_free(uint8_t *rgba) { free(rgba); }
