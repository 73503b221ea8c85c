/* SPDX-License-Identifier: MIT */
/* image.c — PNG/HDR input and PNG output through stb (libstb-dev headers).
 * The stb implementations are compiled here with static linkage so they never
 * clash with a host application's own copy of stb. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "core/core.h"

#include <sys/stat.h>

#include <stdlib.h>

#if SNELL_WITH_PNG
/* No single stb allocation may exceed what the largest accepted image needs
 * (2^25 pixels as 16-bit RGBA plus PNG filter bytes, or as float RGBA while
 * an HDR decodes: 512 MiB). Without this a corrupt zlib stream in a 100-byte
 * PNG makes stb double its output buffer up to 2 GiB (found by fuzzing);
 * with it stb fails with "outofmem", reported as SNELL_E_PARSE. */
#define IMAGE_MAX_ALLOC ((size_t)640 << 20)
/* While a PNG decodes, the largest allocation its own size justifies
 * (png_alloc_cap); a larger request is refused and remembered, so that a zlib
 * stream inflating far past the image (a decompression bomb) stops there. */
static SNELL__THREAD_LOCAL size_t g_alloc_cap;
static SNELL__THREAD_LOCAL int g_cap_hit;
static int alloc_ok(size_t n)
{
    if (g_alloc_cap && n > g_alloc_cap) {
        g_cap_hit = 1;
        return 0;
    }
    return n <= IMAGE_MAX_ALLOC;
}
static void *image_malloc(size_t n) { return alloc_ok(n) ? malloc(n) : NULL; }
static void *image_realloc(void *p, size_t n) { return alloc_ok(n) ? realloc(p, n) : NULL; }
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

#include <errno.h>
#include <stdlib.h>
#include <string.h>

snell_status snell_write_png(const char *path, int width, int height, const uint8_t *rgba)
{
    if (!path || !rgba || width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_write_png: bad arguments (%dx%d)", width, height);
    {
        /* encoded in memory and written here: stbi_write_png ignores fwrite's
         * and fclose's errors (a full disk would leave a truncated file) */
        int len = 0, ok, e;
        unsigned char *png = stbi_write_png_to_mem(rgba, width * 4, width, height, 4, &len);
        FILE *f;
        if (!png) return snell__fail(NULL, SNELL_E_NOMEM, "cannot encode PNG \"%s\" (%dx%d)", path, width, height);
        errno = 0;
        f = fopen(path, "wb");
        if (!f) {
            e = errno;
            free(png);
            return snell__fail(NULL, SNELL_E_IO, "cannot write PNG \"%s\": %s", path, strerror(e));
        }
        ok = fwrite(png, 1, (size_t)len, f) == (size_t)len;
        e = errno;
        if (fclose(f) != 0 && ok) {
            ok = 0;
            e = errno;
        }
        free(png);
        if (!ok) return snell__fail(NULL, SNELL_E_IO, "cannot write PNG \"%s\": %s", path, e ? strerror(e) : "write error");
    }
    return SNELL_OK;
}

/* Largest encoded image accepted (bytes); stb also caps each side at 16384. */
#define IMAGE_MAX_FILE (256u << 20)
/* Largest decoded image: 2^25 pixels (8192 x 4096, an 8K lat-long map; 128 MiB
 * as RGBA8, 512 MiB while an HDR is decoded as floats). Checked from the
 * header before decoding: a 100-byte file may declare 16384^2 pixels, which
 * would allocate 4 GiB of floats (found by fuzzing). */
#define IMAGE_MAX_PIXELS (1u << 25)

/* ---- headers, read before stb sees the file -------------------------------
 * stb refuses a side beyond STBI_MAX_DIMENSIONS as "not of any known type, or
 * corrupt", which hides the reason; its HDR decoder reads past the end as
 * zero bytes, so a truncated file decoded with black rows (flat scanlines) or
 * never finished (a run-length scanline: a zero count does not advance). */
typedef struct image_header {
    unsigned long w, h;
    int hdr;            /* Radiance HDR (else PNG) */
    size_t data;        /* HDR: offset of the pixel data */
    size_t peak_per_px; /* bytes per pixel the decode holds at its peak */
} image_header;

static int starts_with(const uint8_t *b, size_t n, const char *s)
{
    size_t k = strlen(s);
    return n >= k && memcmp(b, s, k) == 0;
}

/* Decimal number as strtol reads it (spaces, sign, digits), capped; advances *p. */
static long hdr_number(const uint8_t *b, size_t end, size_t *p)
{
    long v = 0;
    int neg = 0;
    while (*p < end && b[*p] == ' ') (*p)++;
    if (*p < end && (b[*p] == '+' || b[*p] == '-')) neg = b[(*p)++] == '-';
    while (*p < end && b[*p] >= '0' && b[*p] <= '9') {
        if (v < 100000000L) v = v * 10 + (b[*p] - '0');
        (*p)++;
    }
    return neg ? -v : v;
}

/* 1 and *hd if the data starts like a PNG (IHDR) or an HDR with a resolution
 * line stb accepts ("-Y h +X w"); 0 otherwise (stb then says what is wrong). */
static int read_header(const uint8_t *b, size_t n, image_header *hd)
{
    memset(hd, 0, sizeof *hd);
    if (n >= 26 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0 && memcmp(b + 12, "IHDR", 4) == 0) {
        unsigned bd = b[24], ct = b[25], ch = ct == 0 ? 1 : ct == 2 ? 3 : ct == 4 ? 2 : 4;
        size_t bpp = ch * (bd == 16 ? 2u : 1u), convert = bpp == 4 && bd == 8 ? 0 : 4;
        hd->w = (unsigned long)b[16] << 24 | (unsigned long)b[17] << 16 | (unsigned long)b[18] << 8 | b[19];
        hd->h = (unsigned long)b[20] << 24 | (unsigned long)b[21] << 16 | (unsigned long)b[22] << 8 | b[23];
        /* stb inflates the scanlines (about bpp a pixel), unfilters them into
         * an image of bpp a pixel, then converts that to RGBA8 if it is not */
        hd->peak_per_px = ct == 3 ? 8 : (2 * bpp > bpp + convert ? 2 * bpp : bpp + convert);
        return 1;
    }
    if (starts_with(b, n, "#?RADIANCE\n") || starts_with(b, n, "#?RGBE\n")) {
        size_t p = 0, e;
        long w, h;
        /* the header's lines end at an empty one; then the resolution line */
        for (;;) {
            const uint8_t *nl = (const uint8_t *)memchr(b + p, '\n', n - p);
            if (!nl) return 0;
            e = (size_t)(nl - b);
            if (p > 0 && e == p) break;
            p = e + 1;
        }
        p = e + 1;
        {
            const uint8_t *nl = (const uint8_t *)memchr(b + p, '\n', n - p);
            e = nl ? (size_t)(nl - b) : n;
        }
        if (e - p < 3 || memcmp(b + p, "-Y ", 3) != 0) return 0;
        p += 3;
        h = hdr_number(b, e, &p);
        while (p < e && b[p] == ' ') p++;
        if (e - p < 3 || memcmp(b + p, "+X ", 3) != 0) return 0;
        p += 3;
        w = hdr_number(b, e, &p);
        if (w < 1 || h < 1) return 0;
        hd->w = (unsigned long)w;
        hd->h = (unsigned long)h;
        hd->hdr = 1;
        hd->data = e < n ? e + 1 : n;
        hd->peak_per_px = 16 + 4; /* float RGBA, then our RGBA8 copy */
        return 1;
    }
    return 0;
}

/* 1 if the pixel data of an HDR of w x h holds every scanline, walking it as
 * stbi__hdr_load reads it (stb 2.27): flat RGBE when w < 8 or w >= 32768 or
 * the first scanline is not run-length encoded (then the rest is read flat),
 * else per scanline 2 2 w_hi w_lo and four run-length coded channels. Data
 * stb rejects itself (bad counts) counts as complete: stb says why. */
static int hdr_complete(const uint8_t *b, size_t n, size_t pos, size_t w, size_t h)
{
    size_t j;
    if (w < 8 || w >= 32768) return n - pos >= w * h * 4;
    for (j = 0; j < h; j++) {
        int k;
        if (n - pos < 4) return 0;
        if (b[pos] != 2 || b[pos + 1] != 2 || (b[pos + 2] & 0x80)) return n - pos >= w * h * 4;
        if (((size_t)b[pos + 2] << 8 | b[pos + 3]) != w) return 1;
        pos += 4;
        for (k = 0; k < 4; k++) {
            size_t i = 0;
            while (i < w) {
                size_t c;
                if (pos >= n) return 0;
                c = b[pos++];
                if (c > 128) {
                    c -= 128;
                    if (c > w - i) return 1;
                    if (pos >= n) return 0;
                    pos++;
                } else {
                    if (c > w - i) return 1;
                    if (n - pos < c) return 0;
                    pos += c;
                }
                i += c;
            }
        }
    }
    return 1;
}

/* The largest single allocation stb makes for a PNG of w x h pixels in n
 * bytes: its IDAT chunks joined (less than 2n as the buffer doubles), the
 * inflated scanlines (at most 8 bytes a pixel and a filter byte a row, twice
 * that when an interlaced image's passes outgrow stb's first guess) and the
 * unfiltered image. Inflating past it means data the image has no room for. */
static size_t png_alloc_cap(size_t w, size_t h, size_t n)
{
    return 2 * (w * h * 8 + h) + 2 * n + 65536;
}

snell_status snell__image_decode_budget(const void *data, size_t size, size_t budget, int *width, int *height,
                                        uint8_t **rgba)
{
    const stbi_uc *bytes = (const stbi_uc *)data;
    int w = 0, h = 0, n = 0;
    image_header hd;
    int have_header;
    if (!data || !width || !height || !rgba)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_image_decode: NULL argument");
    *rgba = NULL;
    if (size == 0 || size > IMAGE_MAX_FILE)
        return snell__fail(NULL, SNELL_E_LIMIT, "image of %zu bytes outside 1..%u", size, IMAGE_MAX_FILE);
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
        return snell__fail(NULL, SNELL_E_UNSUPPORTED, "JPEG images are not decoded (use PNG or Radiance HDR)");
    have_header = read_header(bytes, size, &hd);
    if (have_header && (hd.w > STBI_MAX_DIMENSIONS || hd.h > STBI_MAX_DIMENSIONS))
        return snell__fail(NULL, SNELL_E_LIMIT, "%s image of %lux%lu pixels exceeds the limit of %d pixels per side",
                           hd.hdr ? "HDR" : "PNG", hd.w, hd.h, STBI_MAX_DIMENSIONS);
    if (!stbi_info_from_memory(bytes, (int)size, &w, &h, &n))
        return snell__fail(NULL, SNELL_E_PARSE, "not a readable PNG or HDR image (%s)", stbi_failure_reason());
    /* stb accepts some malformed headers as 0-pixel images (found by fuzzing). */
    if (w < 1 || h < 1) return snell__fail(NULL, SNELL_E_PARSE, "image header declares %dx%d pixels", w, h);
    if ((unsigned long long)w * (unsigned long long)h > IMAGE_MAX_PIXELS)
        return snell__fail(NULL, SNELL_E_LIMIT, "image of %dx%d pixels exceeds the limit of %u pixels", w, h,
                           IMAGE_MAX_PIXELS);
    {
        /* the decode's peak (stb's buffers and the RGBA8 result): one request */
        size_t need = (size_t)w * (size_t)h * (have_header ? hd.peak_per_px : 20);
        if (need > budget)
            return snell__fail(NULL, SNELL_E_LIMIT,
                               "decoding a %dx%d image needs %.1f MiB, more than the memory budget of %.1f MiB "
                               "(snell_ctx_desc.memory_budget)",
                               w, h, (double)need / 1048576.0, (double)budget / 1048576.0);
    }
    if (stbi_is_hdr_from_memory(bytes, (int)size)) {
        /* HDR: clamp to the displayable range; the library's env is RGBA8. */
        float *px;
        size_t i, count;
        if (have_header && hd.hdr && !hdr_complete(bytes, size, hd.data, hd.w, hd.h))
            return snell__fail(NULL, SNELL_E_PARSE, "HDR image of %dx%d pixels is truncated (%zu bytes)", w, h, size);
        px = stbi_loadf_from_memory(bytes, (int)size, &w, &h, &n, 4);
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
        int bomb;
        g_alloc_cap = png_alloc_cap((size_t)w, (size_t)h, size);
        g_cap_hit = 0;
        *rgba = stbi_load_from_memory(bytes, (int)size, &w, &h, &n, 4);
        bomb = g_cap_hit;
        g_alloc_cap = 0;
        if (!*rgba && bomb)
            return snell__fail(NULL, SNELL_E_PARSE,
                               "PNG image of %dx%d pixels: its compressed data inflates past the image's size "
                               "(a decompression bomb?)", w, h);
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

snell_status snell__image_read_budget(const char *path, size_t budget, int *width, int *height, uint8_t **rgba)
{
    FILE *f;
    long len;
    uint8_t *buf;
    snell_status st;
    const char *why;
    int opened;
    if (!path || !width || !height || !rgba)
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_image_read: NULL argument");
    *rgba = NULL;
    f = snell__fopen_regular(path, &opened, &why);
    if (!f && !opened) return snell__fail(NULL, SNELL_E_IO, "cannot open image \"%s\": %s", path, why);
    if (!f) return snell__fail(NULL, SNELL_E_IO, "image \"%s\" is %s", path, why);
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return snell__fail(NULL, SNELL_E_IO, "cannot read image \"%s\"", path);
    }
    if (len == 0 || (unsigned long)len > IMAGE_MAX_FILE) {
        fclose(f);
        return snell__fail(NULL, len ? SNELL_E_LIMIT : SNELL_E_PARSE, "image \"%s\" has %ld bytes (1..%u accepted)",
                           path, len, IMAGE_MAX_FILE);
    }
    if ((size_t)len > budget) {
        fclose(f);
        return snell__fail(NULL, SNELL_E_LIMIT,
                           "reading image \"%s\" needs %.1f MiB, more than the memory budget of %.1f MiB "
                           "(snell_ctx_desc.memory_budget)", path, (double)len / 1048576.0, (double)budget / 1048576.0);
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
    st = snell__image_decode_budget(buf, (size_t)len, budget, width, height, rgba);
    free(buf);
    if (st != SNELL_OK) {
        /* Name the file in the message (the decoder does not know it). */
        char msg[768];
        snprintf(msg, sizeof msg, "%s", snell_last_error(NULL));
        return snell__fail(NULL, st, "\"%s\": %s", path, msg);
    }
    return SNELL_OK;
}

#else /* !SNELL_WITH_PNG: no stb; image files are refused (environments from memory still work) */

#define NO_PNG " built without SNELL_WITH_PNG (configure with -DSNELL_WITH_PNG=ON)"

snell_status snell_write_png(const char *path, int width, int height, const uint8_t *rgba)
{
    (void)width, (void)height, (void)rgba;
    return snell__fail(NULL, SNELL_E_UNSUPPORTED, "snell_write_png \"%s\":" NO_PNG, path ? path : "(null)");
}

snell_status snell__image_decode_budget(const void *data, size_t size, size_t budget, int *width, int *height,
                                        uint8_t **rgba)
{
    (void)data, (void)size, (void)budget, (void)width, (void)height, (void)rgba;
    return snell__fail(NULL, SNELL_E_UNSUPPORTED, "image decoding:" NO_PNG);
}

snell_status snell__image_read_budget(const char *path, size_t budget, int *width, int *height, uint8_t **rgba)
{
    (void)budget, (void)width, (void)height, (void)rgba;
    return snell__fail(NULL, SNELL_E_UNSUPPORTED, "image file \"%s\":" NO_PNG, path ? path : "(null)");
}
#endif

snell_status snell_image_decode(const void *data, size_t size, int *width, int *height, uint8_t **rgba)
{
    return snell__image_decode_budget(data, size, SNELL_DEFAULT_MEMORY_BUDGET, width, height, rgba);
}

snell_status snell_image_read(const char *path, int *width, int *height, uint8_t **rgba)
{
    return snell__image_read_budget(path, SNELL_DEFAULT_MEMORY_BUDGET, width, height, rgba);
}

/* stb_image allocates with malloc (STBI_MALLOC default), as does the HDR path. */
void snell_image_free(uint8_t *rgba) { free(rgba); }
