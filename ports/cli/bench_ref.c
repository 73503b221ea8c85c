/* SPDX-License-Identifier: MIT */
/* bench_ref.c — reference images for snell-bench (snell_ref_render of the
 * configuration's scene), cached on disk per scene, material, camera, size
 * and model, so that reruns only time the GPU. A cache file holds a text key
 * (checked on load, so a hash collision cannot return the wrong image) and
 * the raw float/byte arrays of this machine's byte order; a file that does
 * not match is re-rendered. */
#define _POSIX_C_SOURCE 200809L
#include "bench_ref.h"
#include "cli_input.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* 4: FULL uses the exact Fresnel; the key holds the area samples. 5: the
 * first-hit object ids are stored (snell-bench's per-class errors). 6: FULL
 * takes the triangle's side and bends smooth normals that face away. */
#define CACHE_MAGIC "SNELLBENCHREF6\n"

static uint64_t fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* Hash of everything in the mesh the reference sees (positions, normals, indices). */
static uint64_t mesh_hash(const snell_mesh *m)
{
    uint64_t h = 1469598103934665603ull;
    uint32_t nv = snell_mesh_vertex_count(m), nt = snell_mesh_triangle_count(m);
    h = fnv1a(h, &nv, sizeof nv);
    h = fnv1a(h, &nt, sizeof nt);
    h = fnv1a(h, snell_mesh_positions(m), (size_t)nv * 3 * sizeof(float));
    h = fnv1a(h, snell_mesh_normals(m), (size_t)nv * 3 * sizeof(float));
    h = fnv1a(h, snell_mesh_indices(m), (size_t)nt * 3 * sizeof(uint32_t));
    return h;
}

void bench_ref_free(bench_ref_image *img)
{
    if (!img) return;
    free(img->rgb);
    free(img->exit_dir);
    free(img->hit);
    free(img->rgba);
    free(img->object);
    memset(img, 0, sizeof *img);
}

static int alloc_image(bench_ref_image *img, int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    memset(img, 0, sizeof *img);
    img->width = w;
    img->height = h;
    img->rgb = (float *)malloc(n * 3 * sizeof(float));
    img->exit_dir = (float *)malloc(n * 3 * sizeof(float));
    img->hit = (uint8_t *)malloc(n);
    img->rgba = (uint8_t *)malloc(n * 4);
    img->object = (int16_t *)malloc(n * sizeof(int16_t));
    if (img->rgb && img->exit_dir && img->hit && img->rgba && img->object) return 1;
    bench_ref_free(img);
    return 0;
}

static int read_exact(FILE *f, void *p, size_t n) { return fread(p, 1, n, f) == n; }

/* 1 if the cache file exists and holds this key's image. */
static int cache_load(const char *path, const char *full_key, bench_ref_image *img)
{
    char why[64], magic[sizeof CACHE_MAGIC];
    int fd = cli_open_input(path, why, sizeof why); /* a FIFO planted in the cache must not block */
    FILE *f = fd < 0 ? NULL : fdopen(fd, "rb");
    uint32_t key_len, w, h;
    char *key = NULL;
    size_t n;
    int ok = 0;
    if (!f) {
        if (fd >= 0) close(fd);
        return 0;
    }
    if (!read_exact(f, magic, sizeof CACHE_MAGIC - 1) || memcmp(magic, CACHE_MAGIC, sizeof CACHE_MAGIC - 1)) goto done;
    if (!read_exact(f, &key_len, 4) || key_len != strlen(full_key)) goto done;
    key = (char *)malloc(key_len);
    if (!key || !read_exact(f, key, key_len) || memcmp(key, full_key, key_len)) goto done;
    if (!read_exact(f, &w, 4) || !read_exact(f, &h, 4) || (int)w != img->width || (int)h != img->height) goto done;
    n = (size_t)w * h;
    ok = read_exact(f, img->rgb, n * 3 * sizeof(float)) && read_exact(f, img->exit_dir, n * 3 * sizeof(float)) &&
         read_exact(f, img->hit, n) && read_exact(f, img->object, n * sizeof(int16_t));
done:
    free(key);
    fclose(f);
    return ok;
}

/* Writes to a temporary name and renames, so a killed run leaves no torn file. */
static void cache_store(const char *dir, const char *path, const char *full_key, const bench_ref_image *img)
{
    char tmp[1200];
    FILE *f;
    uint32_t key_len = (uint32_t)strlen(full_key), w = (uint32_t)img->width, h = (uint32_t)img->height;
    size_t n = (size_t)w * h;
    int ok;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) return;
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    if (!(f = fopen(tmp, "wb"))) return;
    ok = fwrite(CACHE_MAGIC, 1, sizeof CACHE_MAGIC - 1, f) == sizeof CACHE_MAGIC - 1 && fwrite(&key_len, 4, 1, f) == 1 &&
         fwrite(full_key, 1, key_len, f) == key_len && fwrite(&w, 4, 1, f) == 1 && fwrite(&h, 4, 1, f) == 1 &&
         fwrite(img->rgb, sizeof(float), n * 3, f) == n * 3 && fwrite(img->exit_dir, sizeof(float), n * 3, f) == n * 3 &&
         fwrite(img->hit, 1, n, f) == n && fwrite(img->object, sizeof(int16_t), n, f) == n;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) remove(tmp);
}

/* Appends printf-style text to the key (bounded; *len past the end marks overflow). */
static void key_add(char *key, size_t size, size_t *len, const char *fmt, ...)
{
    va_list ap;
    if (*len >= size) return;
    va_start(ap, fmt);
    *len += (size_t)vsnprintf(key + *len, size - *len, fmt, ap);
    va_end(ap);
}

static void key_model(char *key, size_t size, size_t *len, const float *model)
{
    int k;
    if (!model) {
        key_add(key, size, len, " model=identity");
        return;
    }
    key_add(key, size, len, " model=");
    for (k = 0; k < 16; k++) key_add(key, size, len, "%s%.9g", k ? "/" : "", model[k]);
}

/* Everything the reference image depends on, as text. 0 if it does not fit. */
static int scene_key(const snell_ref_desc *scene, const snell_ref_params *p, const char *env_key, char *key,
                     size_t size)
{
    const snell_camera *cam = &p->camera;
    size_t len = 0;
    int i;
    key_add(key, size, &len, "env=%s size=%dx%d cam=%.9g/%.9g/%.9g/%.9g/%.9g/%.9g/%.9g/%.9g/%.9g mode=%d "
            "interfaces=%d absorb=%d isolate=%d samples=%d",
            env_key, p->width, p->height, cam->azimuth, cam->elevation, cam->distance, cam->fov_y, cam->target[0],
            cam->target[1], cam->target[2], cam->z_near, cam->z_far, (int)p->mode, p->max_interfaces,
            (int)p->absorption_model, p->isolate_glass != 0, p->samples > 1 ? p->samples : 1);
    if (p->terms) /* only when some, so that the keys already cached stay */
        key_add(key, size, &len, " terms=%u", p->terms);
    if (cam->kind == SNELL_CAMERA_MATRICES) /* only then, so that the orbit cameras' cached keys stay */
        for (i = 0; i < 32; i++)
            key_add(key, size, &len, "%s%.9g", i == 0 ? " matrices=" : "/", i < 16 ? cam->view[i] : cam->projection[i - 16]);
    for (i = 0; i < scene->glass_count; i++) {
        const snell_glass *g = &scene->glass[i];
        snell_glass_resolved r;
        if (snell_glass_defaults(&g->material, &r) != SNELL_OK) return 0;
        key_add(key, size, &len, " | glass mesh=%016llx", (unsigned long long)mesh_hash(g->mesh));
        key_model(key, size, &len, g->model);
        key_add(key, size, &len, " ior=%.9g abs=%.9g/%.9g/%.9g tint=%.9g/%.9g/%.9g thickness=%.9g", r.material.ior,
                r.absorption[0], r.absorption[1], r.absorption[2], r.material.tint[0], r.material.tint[1],
                r.material.tint[2], r.material.thickness);
        /* only when on, so that the keys of non-dispersive scenes stay those already cached */
        if (r.disperses) key_add(key, size, &len, " dispersion=%.9g", r.material.dispersion);
    }
    for (i = 0; i < scene->opaque_count; i++) {
        const snell_opaque *q = &scene->opaque[i];
        key_add(key, size, &len, " | opaque mesh=%016llx", (unsigned long long)mesh_hash(q->mesh));
        key_model(key, size, &len, q->model);
        key_add(key, size, &len, " color=%.9g/%.9g/%.9g", q->color[0], q->color[1], q->color[2]);
    }
    return len < size;
}

static snell_status render_ref(const snell_ref_desc *scene, const snell_ref_params *p, bench_ref_image *out)
{
    snell_ref *ref = NULL;
    snell_ref_output o;
    snell_status st = snell_ref_create(NULL, scene, &ref);
    if (st != SNELL_OK) return st;
    memset(&o, 0, sizeof o);
    o.rgb = out->rgb;
    o.exit_dir = out->exit_dir;
    o.hit = out->hit;
    o.object = out->object;
    st = snell_ref_render(ref, p, &o);
    snell_ref_destroy(ref);
    return st;
}

snell_status bench_ref_get(const snell_ref_desc *scene, const snell_ref_params *p, const char *env_key,
                           const char *cache_dir, bench_ref_image *out, int *cached)
{
    size_t key_size = 1024 + (size_t)(scene->glass_count + scene->opaque_count) * 512;
    char *key = (char *)malloc(key_size), path[1100];
    snell_status st = SNELL_OK;
    *cached = 0;
    if (!key || !alloc_image(out, p->width, p->height)) {
        free(key);
        return SNELL_E_NOMEM;
    }
    if (!scene_key(scene, p, env_key, key, key_size)) cache_dir = NULL; /* a material the reference rejects */
    snprintf(path, sizeof path, "%s/%016llx.ref", cache_dir ? cache_dir : ".",
             (unsigned long long)fnv1a(1469598103934665603ull, key, strlen(key)));
    if (cache_dir && cache_load(path, key, out)) {
        *cached = 1;
    } else if ((st = render_ref(scene, p, out)) == SNELL_OK && cache_dir) {
        cache_store(cache_dir, path, key, out);
    }
    free(key);
    if (st != SNELL_OK) {
        bench_ref_free(out);
        return st;
    }
    snell_ref_rgb_to_rgba8(out->rgb, out->width, out->height, out->rgba);
    return SNELL_OK;
}
