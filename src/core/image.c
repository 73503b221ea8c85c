/* image.c — PNG/HDR input and PNG output through stb (libstb-dev headers).
 * The stb implementations are compiled here with static linkage so they never
 * clash with a host application's own copy of stb. */
#include "core/core.h"

#include <stdlib.h>

/* No single stb allocation may exceed what the largest accepted image needs
 * (2^25 pixels as 16-bit RGBA plus PNG filter bytes, or as float RGBA while
 * an HDR decodes: 512 MiB). Without this a corrupt zlib stream in a 100-byte
 * PNG makes stb double its output buffer up to 2 GiB (found by fuzzing);
 * with it stb fails with "outofmem", reported as SNELL_E_PARSE. */
#define IMAGE_MAX_ALLOC ((size_t)640 << 20)
static void *image_malloc(size_t n) { return n > IMAGE_MAX_ALLOC ? NULL : malloc(n); }
static void *image_realloc(void *p, size_t n) { return n > IMAGE_MAX_ALLOC ? NULL : realloc(p, n); }
#define STBI_MALLOC(sz) image_malloc(sz)
#define STBI_REALLOC(p, newsz) image_realloc(p, newsz)
#define STBI_FREE(p) free(p)

#define STBI_MAX_DIMENSIONS 16384
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
/* No JPEG: Debian's stb_image 2.27 writes past a Huffman table on malformed
 * DHT segments (libFuzzer, tests/data/images/bad_jpeg_huffman_overflow.jpg).
 * PNG and Radiance HDR cover environment maps. */
#define STBI_ONLY_PNG
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

/* Largest encoded image accepted (bytes); stb also caps each side at 16384. */
#define IMAGE_MAX_FILE (256u << 20)
/* Largest decoded image: 2^25 pixels (8192 x 4096, an 8K lat-long map; 128 MiB
 * as RGBA8, 512 MiB while an HDR is decoded as floats). Checked from the
 * header before decoding: a 100-byte file may declare 16384^2 pixels, which
 * would allocate 4 GiB of floats (found by fuzzing). */
#define IMAGE_MAX_PIXELS (1u << 25)

snell_status snell_image_decode(const void *data, size_t size, int *width, int *height, uint8_t **rgba)
{
    const stbi_uc *bytes = (const stbi_uc *)data;
    int w = 0, h = 0, n = 0;
    if (!data || !width || !height || !rgba)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_image_decode: NULL argument");
    *rgba = NULL;
    if (size == 0 || size > IMAGE_MAX_FILE)
        return snell__fail(NULL, SNELL_E_LIMIT, "image of %zu bytes outside 1..%u", size, IMAGE_MAX_FILE);
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
        return snell__fail(NULL, SNELL_E_UNSUPPORTED, "JPEG images are not decoded (use PNG or Radiance HDR)");
    if (!stbi_info_from_memory(bytes, (int)size, &w, &h, &n))
        return snell__fail(NULL, SNELL_E_PARSE, "not a readable PNG or HDR image (%s)", stbi_failure_reason());
    /* stb accepts some malformed headers as 0-pixel images (found by fuzzing). */
    if (w < 1 || h < 1) return snell__fail(NULL, SNELL_E_PARSE, "image header declares %dx%d pixels", w, h);
    if ((unsigned long long)w * (unsigned long long)h > IMAGE_MAX_PIXELS)
        return snell__fail(NULL, SNELL_E_LIMIT, "image of %dx%d pixels exceeds the limit of %u pixels", w, h,
                           IMAGE_MAX_PIXELS);
    if (stbi_is_hdr_from_memory(bytes, (int)size)) {
        /* HDR: clamp to the displayable range; the library's env is RGBA8. */
        float *px = stbi_loadf_from_memory(bytes, (int)size, &w, &h, &n, 4);
        size_t i, count;
        if (!px) return snell__fail(NULL, SNELL_E_PARSE, "cannot decode HDR image: %s", stbi_failure_reason());
        count = (size_t)w * (size_t)h * 4;
        *rgba = (uint8_t *)malloc(count);
        if (!*rgba) {
            stbi_image_free(px);
            return snell__fail(NULL, SNELL_E_NOMEM, "out of memory decoding a %dx%d image", w, h);
        }
        for (i = 0; i < count; i++) {
            float v = px[i] < 0.0f ? 0.0f : px[i] > 1.0f ? 1.0f : px[i];
            (*rgba)[i] = (uint8_t)(v * 255.0f + 0.5f);
        }
        stbi_image_free(px);
    } else {
        *rgba = stbi_load_from_memory(bytes, (int)size, &w, &h, &n, 4);
        if (!*rgba) return snell__fail(NULL, SNELL_E_PARSE, "cannot decode image: %s", stbi_failure_reason());
    }
    if (w < 1 || h < 1) {
        free(*rgba);
        *rgba = NULL;
        return snell__fail(NULL, SNELL_E_PARSE, "image decodes to %dx%d pixels", w, h);
    }
    *width = w;
    *height = h;
    return SNELL_OK;
}

snell_status snell_image_read(const char *path, int *width, int *height, uint8_t **rgba)
{
    FILE *f;
    long len;
    uint8_t *buf;
    snell_status st;
    if (!path || !width || !height || !rgba)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_image_read: NULL argument");
    *rgba = NULL;
    f = fopen(path, "rb");
    if (!f) return snell__fail(NULL, SNELL_E_IO, "cannot open image \"%s\"", path);
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return snell__fail(NULL, SNELL_E_IO, "cannot read image \"%s\"", path);
    }
    if (len == 0 || (unsigned long)len > IMAGE_MAX_FILE) {
        fclose(f);
        return snell__fail(NULL, len ? SNELL_E_LIMIT : SNELL_E_PARSE, "image \"%s\" has %ld bytes (1..%u accepted)",
                           path, len, IMAGE_MAX_FILE);
    }
    buf = (uint8_t *)malloc((size_t)len);
    if (!buf) {
        fclose(f);
        return snell__fail(NULL, SNELL_E_NOMEM, "out of memory reading \"%s\"", path);
    }
    if (fread(buf, 1, (size_t)len, f) != (size_t)len) {
        fclose(f);
        free(buf);
        return snell__fail(NULL, SNELL_E_IO, "cannot read image \"%s\"", path);
    }
    fclose(f);
    st = snell_image_decode(buf, (size_t)len, width, height, rgba);
    free(buf);
    if (st != SNELL_OK) {
        /* Name the file in the message (the decoder does not know it). */
        char msg[768];
        snprintf(msg, sizeof msg, "%s", snell_last_error(NULL));
        return snell__fail(NULL, st, "\"%s\": %s", path, msg);
    }
    return SNELL_OK;
}

/* stb_image allocates with malloc (STBI_MALLOC default), as does the HDR path. */
void snell_image_free(uint8_t *rgba) { free(rgba); }
