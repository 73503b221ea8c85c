/* cubemap_bench — time vs error of SNELL_METHOD_CUBEMAP (issue table for
 * bench/BENCHMARKS_CUBEMAP.md). For a mesh and a list of settings: the median
 * frame time (glFinish, after one warm-up frame) and the per-pixel angular
 * error of the exit direction against the reference tracer in MATCHED mode
 * with the same max_interfaces (SNELL_OUTPUT_EXIT_DIRECTION vs
 * snell_ref_render exit_dir, over the pixels where the reference hits the
 * mesh). Single-surface rows: the same with SNELL_METHOD_SINGLE against the
 * same reference (what the two-sided model says the light really does).
 *
 * usage: cubemap_bench MESH [frames] [size] [sweep]
 *   MESH: shape:sphere|cube|torus|goblet or an OBJ path (normalised to radius 1)
 *   sweep: all (default) | defaults | quick | ratio
 *   ratio: single and the cubemap defaults frame by frame alternating (the
 *   cost target of issue 4 is a ratio; alternating cancels the drift of a
 *   shared machine), prints the medians of each and of the per-pair ratios.
 * ms = median wall time per frame; cpu_ms = process CPU time per frame
 * (llvmpipe's threads included), steadier than wall time on a shared machine.
 * Output: one CSV line per setting:
 *   mesh,method,encoding,face,iterations,linear,interfaces,ms,cpu_ms,mean_deg,median_deg,p95_deg,hit_px */
#define _POSIX_C_SOURCE 200809L
#include "test_util.h"
#include "snell/snell_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct setting {
    snell_method method;
    snell_ndcube_encoding enc;
    int face, iterations, linear, interfaces;
} setting;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

typedef struct bench {
    snell_ctx *ctx;
    snell_mesh *mesh;
    snell_env *env;
    snell_renderer *color, *dirs;
    int size, frames;
    snell_frame_desc fd;
    float *gpu;
    float *ref_dir[SNELL_CUBEMAP_MAX_INTERFACES + 1];
    uint8_t *hit;
    snell_ref *ref;
    double *err, *times;
} bench;

static float *reference(bench *b, int interfaces)
{
    if (!b->ref_dir[interfaces]) {
        snell_ref_params p;
        float *rgb = (float *)malloc(sizeof(float) * 3 * b->size * b->size);
        b->ref_dir[interfaces] = (float *)malloc(sizeof(float) * 3 * b->size * b->size);
        test_ref_params(&b->fd, b->size, b->size, interfaces, &p);
        p.env = b->env;
        if (test_ref_render(b->ref, &p, rgb, b->ref_dir[interfaces], b->hit) != SNELL_OK)
            fprintf(stderr, "ref: %s\n", snell_last_error(NULL));
        free(rgb);
    }
    return b->ref_dir[interfaces];
}

static void apply(snell_frame_desc *fd, const setting *s)
{
    fd->glass.method = s->method;
    fd->glass.encoding = s->enc;
    fd->glass.cube_face_size = s->face;
    fd->glass.search_iterations = s->iterations;
    fd->glass.linear_steps = s->linear;
    fd->glass.max_interfaces = s->interfaces;
}

static double timed_frame(bench *b, const snell_frame_desc *fd)
{
    double t0 = now_ms();
    if (snell_render(b->color, fd, NULL) != SNELL_OK) fprintf(stderr, "render: %s\n", snell_last_error(b->ctx));
    snell_renderer_finish(b->color);
    return now_ms() - t0;
}

/* Frames of a and b alternating (a b b a a b ...: each gets the first slot
 * of a pair half the time); medians of each and of the per-pair ratio b/a. */
static void ratio(bench *b, const setting *sa, const setting *sb)
{
    snell_frame_desc fa = b->fd, fb = b->fd;
    double *ta = (double *)malloc(sizeof(double) * b->frames), *tb = (double *)malloc(sizeof(double) * b->frames);
    double *r = (double *)malloc(sizeof(double) * b->frames);
    int f;
    apply(&fa, sa);
    apply(&fb, sb);
    timed_frame(b, &fa);
    timed_frame(b, &fb);
    for (f = 0; f < b->frames; f++) {
        if (f & 1) {
            tb[f] = timed_frame(b, &fb);
            ta[f] = timed_frame(b, &fa);
        } else {
            ta[f] = timed_frame(b, &fa);
            tb[f] = timed_frame(b, &fb);
        }
        r[f] = tb[f] / ta[f];
    }
    qsort(ta, (size_t)b->frames, sizeof *ta, cmp_d);
    qsort(tb, (size_t)b->frames, sizeof *tb, cmp_d);
    qsort(r, (size_t)b->frames, sizeof *r, cmp_d);
    printf("ratio,frames=%d,a_ms=%.3f,b_ms=%.3f,ratio_of_medians=%.3f,median_ratio=%.3f,p25=%.3f,p75=%.3f\n", b->frames,
           ta[b->frames / 2], tb[b->frames / 2], tb[b->frames / 2] / ta[b->frames / 2], r[b->frames / 2],
           r[b->frames / 4], r[3 * b->frames / 4]);
    free(ta);
    free(tb);
    free(r);
}

static void run(bench *b, const char *mesh_name, const setting *s)
{
    snell_frame_desc fd = b->fd;
    int i, n = b->size * b->size, hits = 0, f;
    double mean = 0.0, cpu0 = 0.0, cpu = 0.0;
    float *ref;
    apply(&fd, s);
    for (f = 0; f <= b->frames; f++) {
        double t0 = now_ms();
        if (f == 1) cpu0 = cpu_ms();
        if (snell_render(b->color, &fd, NULL) != SNELL_OK) {
            fprintf(stderr, "render: %s\n", snell_last_error(b->ctx));
            return;
        }
        snell_renderer_finish(b->color);
        if (f > 0) b->times[f - 1] = now_ms() - t0;
    }
    cpu = (cpu_ms() - cpu0) / b->frames;
    qsort(b->times, (size_t)b->frames, sizeof *b->times, cmp_d);
    snell_render(b->dirs, &fd, NULL);
    snell_renderer_read_exit_dirs(b->dirs, b->gpu);
    ref = reference(b, s->interfaces);
    for (i = 0; i < n; i++) {
        double d;
        if (!b->hit[i]) continue;
        {
            const float *a = b->gpu + 3 * i, *c = ref + 3 * i;
            double x = (double)a[1] * c[2] - (double)a[2] * c[1], y = (double)a[2] * c[0] - (double)a[0] * c[2],
                   z = (double)a[0] * c[1] - (double)a[1] * c[0];
            d = (double)a[0] * c[0] + (double)a[1] * c[1] + (double)a[2] * c[2];
            d = atan2(sqrt(x * x + y * y + z * z), d) * 180.0 / 3.14159265358979;
        }
        b->err[hits++] = d;
        mean += d;
    }
    qsort(b->err, (size_t)hits, sizeof *b->err, cmp_d);
    printf("%s,%s,%s,%d,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%d\n", mesh_name, s->method == SNELL_METHOD_SINGLE ? "single" : "cubemap",
           s->enc == SNELL_NDCUBE_PLAIN ? "plain" : "oct", s->face, s->iterations, s->linear, s->interfaces,
           b->times[b->frames / 2], cpu, hits ? mean / hits : 0.0, hits ? b->err[hits / 2] : 0.0,
           hits ? b->err[(int)(0.95 * hits)] : 0.0, hits);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    bench b;
    snell_renderer_desc rd;
    snell_env_desc ed;
    snell_ref_desc refd;
    const char *mesh_name = argc > 1 ? argv[1] : "shape:sphere";
    const char *sweep = argc > 4 ? argv[4] : "all";
    setting s;
    int i, k;
    static const int iters[] = {4, 6, 8, 12, 16, 20}, faces[] = {64, 128, 256, 512}, ifs[] = {1, 2, 3, 4};
    memset(&b, 0, sizeof b);
    b.frames = argc > 2 ? atoi(argv[2]) : 7;
    b.size = argc > 3 ? atoi(argv[3]) : 512;
    if (b.frames < 1 || b.size < 8) return 2;
    b.ctx = test_ctx();
    if (!b.ctx) SKIP("no GL context");
    if (!strncmp(mesh_name, "shape:", 6)) {
        snell_shape_desc sd;
        const char *names[] = {"sphere", "cube", "torus", "goblet"};
        memset(&sd, 0, sizeof sd);
        for (k = 0; k < 4; k++)
            if (!strcmp(mesh_name + 6, names[k])) sd.shape = (snell_shape)k;
        CHECK_OK(snell_mesh_create_shape(b.ctx, &sd, &b.mesh));
    } else {
        CHECK_OK(snell_mesh_load(b.ctx, mesh_name, &b.mesh));
    }
    if (!b.mesh) return 1;
    CHECK_OK(snell_mesh_normalize(b.mesh, 1.0f));
    memset(&ed, 0, sizeof ed);
    CHECK_OK(snell_env_create(b.ctx, &ed, &b.env));
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = b.size;
    CHECK_OK(snell_renderer_create(b.ctx, &rd, &b.color));
    rd.output = SNELL_OUTPUT_EXIT_DIRECTION;
    CHECK_OK(snell_renderer_create(b.ctx, &rd, &b.dirs));
    memset(&refd, 0, sizeof refd);
    refd.mesh = b.mesh;
    CHECK_OK(snell_ref_create(b.ctx, &refd, &b.ref));
    if (!b.env || !b.color || !b.dirs || !b.ref) return 1;
    memset(&b.fd, 0, sizeof b.fd);
    b.fd.mesh = b.mesh;
    b.fd.env = b.env;
    b.fd.glass.ior = argc > 5 ? (float)atof(argv[5]) : 1.5f;
    b.fd.camera.azimuth = 0.5236f;   /* the CLI's default view: 30, 20 degrees, distance 3.5 */
    b.fd.camera.elevation = 0.3491f;
    b.fd.camera.distance = 3.5f;
    b.gpu = (float *)malloc(sizeof(float) * 3 * b.size * b.size);
    b.hit = (uint8_t *)malloc((size_t)b.size * b.size);
    b.err = (double *)malloc(sizeof(double) * b.size * b.size);
    b.times = (double *)malloc(sizeof(double) * b.frames);
    printf("mesh,method,encoding,face,iterations,linear,interfaces,ms,cpu_ms,mean_deg,median_deg,p95_deg,hit_px\n");

    /* Baseline first, then the defaults, then the sweeps (one parameter varied
     * around the defaults at a time). */
    memset(&s, 0, sizeof s);
    s.method = SNELL_METHOD_SINGLE;
    s.interfaces = 2;
    run(&b, mesh_name, &s);
    s.method = SNELL_METHOD_CUBEMAP;
    s.enc = SNELL_NDCUBE_PLAIN;
    s.face = 256;
    s.iterations = 8;
    s.interfaces = 2;
    if (!strcmp(sweep, "ratio")) {
        setting a = s;
        /* CUBEMAP_BENCH_ITERATIONS / _FACE: settings other than the defaults. */
        if (getenv("CUBEMAP_BENCH_ITERATIONS")) s.iterations = atoi(getenv("CUBEMAP_BENCH_ITERATIONS"));
        if (getenv("CUBEMAP_BENCH_FACE")) s.face = atoi(getenv("CUBEMAP_BENCH_FACE"));
        a.method = SNELL_METHOD_SINGLE;
        ratio(&b, &a, &s);
        run(&b, mesh_name, &s);
    }
    if (!strcmp(sweep, "quick")) {
        setting d = s;
        run(&b, mesh_name, &s);
        d.interfaces = 1;
        run(&b, mesh_name, &d);
    }
    if (!strcmp(sweep, "defaults") || !strcmp(sweep, "all")) {
        setting d = s;
        run(&b, mesh_name, &s);
        d.enc = SNELL_NDCUBE_OCT;
        run(&b, mesh_name, &d);
        d = s;
        d.method = SNELL_METHOD_SINGLE;
        d.interfaces = 3;
        run(&b, mesh_name, &d);
        d.method = SNELL_METHOD_CUBEMAP;
        d.enc = SNELL_NDCUBE_PLAIN;
        run(&b, mesh_name, &d);
    }
    if (!strcmp(sweep, "all")) {
        for (k = 0; k < 2; k++) {
            setting d = s;
            d.enc = k ? SNELL_NDCUBE_OCT : SNELL_NDCUBE_PLAIN;
            for (i = 0; i < 6; i++) {
                d.iterations = iters[i];
                run(&b, mesh_name, &d);
            }
            d.iterations = s.iterations;
            for (i = 0; i < 4; i++) {
                d.face = faces[i];
                run(&b, mesh_name, &d);
            }
            d.face = s.face;
            for (i = 0; i < 4; i++) {
                d.interfaces = ifs[i];
                run(&b, mesh_name, &d);
            }
            d.interfaces = s.interfaces;
            d.linear = 8;
            run(&b, mesh_name, &d);
        }
    }
    snell_ref_destroy(b.ref);
    for (i = 0; i <= SNELL_CUBEMAP_MAX_INTERFACES; i++) free(b.ref_dir[i]);
    free(b.gpu);
    free(b.hit);
    free(b.err);
    free(b.times);
    snell_renderer_destroy(b.color);
    snell_renderer_destroy(b.dirs);
    snell_env_destroy(b.env);
    snell_mesh_destroy(b.mesh);
    snell_ctx_destroy(b.ctx);
    return 0;
}
