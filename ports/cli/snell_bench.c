#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* snell-bench — time vs error of the refraction methods (issue 3).
 *
 * Runs scenes x methods x parameters; for each configuration it times the
 * median of N frames after warm-up (each frame ended by glFinish, plus
 * GL_EXT_disjoint_timer_query when the context has it; the configurations of
 * one scene and size take turns frame by frame, so a shared machine's drift
 * hits all of them alike and ratios to single-surface are per round), renders the exit
 * directions (SNELL_OUTPUT_EXIT_DIRECTION) and compares them and the colour
 * image with the CPU reference (snell_ref, MATCHED with the method's
 * max_interfaces and FULL), cached on disk per scene/camera/size/glass.
 * Writes PREFIX.json, PREFIX.csv and PREFIX.png (time vs error, Pareto front).
 * Configurations are written glmark2 style: -b method:key=value:key=v1,v2
 * (a comma list sweeps). With no arguments: a quick default sweep.
 * Exit status 0 on success, 1 if a configuration or an output failed,
 * 2 on bad usage. */
#include "bench_common.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846
#define MAX_CONFIGS 4096
#define MAX_KEYS 16
#define MAX_VALUES 32
#define MAX_SCENES 32
#define MAX_INTERLEAVED 48 /* renderers alive at once while timing (memory) */

/* ------------------------------------------------------------ parameters */
typedef struct bench_param {
    const char *key;
    const char *help;
    int (*apply)(bench_config *c, const char *value); /* 0: bad value (message printed) */
} bench_param;

typedef struct bench_method {
    const char *name;
    snell_method id;
    const char *description;
    const char *default_sweep;       /* parameters of the method in the default run */
    const bench_param *params;       /* method-specific keys, {NULL} terminated */
    void (*finalize)(bench_config *c); /* sets the MATCHED reference model from the glass */
} bench_method;

static int bad(const char *key, const char *v, const char *want)
{
    fprintf(stderr, "snell-bench: %s=%s: want %s\n", key, v, want);
    return 0;
}

static int parse_int_in(const char *key, const char *v, int lo, int hi, int *out)
{
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    if (end == v || *end || errno || x < lo || x > hi) {
        char want[64];
        snprintf(want, sizeof want, "an integer in %d..%d", lo, hi);
        return bad(key, v, want);
    }
    *out = (int)x;
    return 1;
}

/* n floats separated by '/' (',' separates sweep values); a single value fills all n. */
static int parse_vec(const char *key, const char *v, float *out, int n, float lo, float hi)
{
    const char *s = v;
    char *end;
    int i;
    for (i = 0; i < n; i++) {
        float x;
        errno = 0;
        x = strtof(s, &end);
        if (end == s || errno || !isfinite(x) || x < lo || x > hi) return bad(key, v, "number(s) in range, a/b/c");
        out[i] = x;
        s = end;
        if (*s == '\0' && i == 0) {
            for (; i < n; i++) out[i] = x;
            return 1;
        }
        if (i < n - 1) {
            if (*s != '/') return bad(key, v, "a/b/c");
            s++;
        }
    }
    return *s == '\0' ? 1 : bad(key, v, "a/b/c");
}

static int p_scene(bench_config *c, const char *v)
{
    if (!*v || strlen(v) >= sizeof c->scene) return bad("scene", v, "a shape name or a mesh path");
    strcpy(c->scene, v);
    return 1;
}

static int p_size(bench_config *c, const char *v)
{
    char tail;
    if (sscanf(v, "%dx%d%c", &c->width, &c->height, &tail) != 2 || c->width < 1 || c->height < 1 ||
        c->width > 8192 || c->height > 8192)
        return bad("size", v, "WxH within 1..8192");
    return 1;
}

static int p_ior(bench_config *c, const char *v) { return parse_vec("ior", v, &c->glass.ior, 1, 0.05f, 100.0f); }
static int p_absorption(bench_config *c, const char *v)
{
    return parse_vec("absorption", v, c->glass.absorption, 3, 0.0f, 1e6f);
}
static int p_tint(bench_config *c, const char *v) { return parse_vec("tint", v, c->glass.tint, 3, 0.0f, 1.0f); }
static int p_camera(bench_config *c, const char *v)
{
    if (!parse_vec("camera", v, c->cam, 3, -1e4f, 1e4f)) return 0;
    return c->cam[2] > 0.0f ? 1 : bad("camera", v, "az/el/dist (degrees, degrees, distance > 0)");
}

#define STR_(x) #x
#define STR(x) STR_(x)

/* Keys every method takes. */
static const bench_param g_common_params[] = {
    {"scene", "sphere|cube|torus|goblet|bunny or a mesh file (normalised to the unit sphere)", p_scene},
    {"size", "WxH image size", p_size},
    {"ior", "index of refraction (default 1.5)", p_ior},
    {"absorption", "Beer-Lambert coefficient per unit length, a or r/g/b (default 0)", p_absorption},
    {"tint", "transmission tint r/g/b (default white)", p_tint},
    {"camera", "orbit camera az/el/dist, degrees (default 30/20/3.5)", p_camera},
    {NULL, NULL, NULL}};

static const bench_param g_no_params[] = {{NULL, NULL, NULL}};

static void single_finalize(bench_config *c)
{
    /* Unger 3.3: one interface; absorption over the bounding-sphere chord. */
    c->ref_interfaces = 1;
    c->ref_absorb = SNELL_REF_ABSORB_BOUNDING_SPHERE;
}

static int p_iterations(bench_config *c, const char *v)
{
    return parse_int_in("iterations", v, 1, SNELL_CUBEMAP_MAX_ITERATIONS, &c->glass.search_iterations);
}
static int p_linear(bench_config *c, const char *v)
{
    return parse_int_in("linear", v, 0, SNELL_CUBEMAP_MAX_LINEAR_STEPS, &c->glass.linear_steps);
}
static int p_interfaces(bench_config *c, const char *v)
{
    return parse_int_in("interfaces", v, 1, SNELL_CUBEMAP_MAX_INTERFACES, &c->glass.max_interfaces);
}
static int p_face(bench_config *c, const char *v) { return parse_int_in("face", v, 16, 2048, &c->glass.cube_face_size); }
static int p_encoding(bench_config *c, const char *v)
{
    if (!strcmp(v, "oct")) c->glass.encoding = SNELL_NDCUBE_OCT;
    else if (!strcmp(v, "plain")) c->glass.encoding = SNELL_NDCUBE_PLAIN;
    else return bad("encoding", v, "oct or plain");
    return 1;
}

static const bench_param g_cubemap_params[] = {
    {"iterations", "binary-search steps per interface (default " STR(SNELL_CUBEMAP_DEFAULT_ITERATIONS) ")",
     p_iterations},
    {"linear", "linear pre-search steps (default 0)", p_linear},
    {"interfaces", "surfaces per path (default " STR(SNELL_CUBEMAP_DEFAULT_INTERFACES) ")", p_interfaces},
    {"face", "normal+distance cubemap face size (default " STR(SNELL_CUBEMAP_DEFAULT_FACE_SIZE) ")", p_face},
    {"encoding", "plain|oct normal+distance packing (default plain)", p_encoding},
    {NULL, NULL, NULL}};

static void cubemap_finalize(bench_config *c)
{
    c->ref_interfaces = c->glass.max_interfaces ? c->glass.max_interfaces : SNELL_CUBEMAP_DEFAULT_INTERFACES;
    c->ref_absorb = SNELL_REF_ABSORB_PATH;
}

/* Every method snell-bench knows. A new method: one row here, its keys in a
 * bench_param table (one apply function each) and a finalize that states
 * which reference model it approximates. */
static const bench_method g_methods[] = {
    {"single", SNELL_METHOD_SINGLE, "front surface only (Unger 3.3)", "", g_no_params, single_finalize},
    {"cubemap", SNELL_METHOD_CUBEMAP, "normal+distance cubemap search (Unger 4.1)", "iterations=4,6,12", g_cubemap_params,
     cubemap_finalize},
};
#define METHOD_COUNT ((int)(sizeof g_methods / sizeof *g_methods))

/* --------------------------------------------------------------- options */
typedef struct options {
    const char *specs[256];
    int spec_count;
    char scenes[1024], sizes[256];
    int frames, warmup;
    const char *out_prefix;
    const char *cache_dir;
    const char *env;
    const char *images_dir;
    int full_interfaces;
    int threads;
    const char *plot_y;
    int quiet;
} options;

static void usage(FILE *f)
{
    int m, k;
    fprintf(f,
            "usage: snell-bench [options] [-b SPEC]...\n"
            "Times refraction methods and measures their error against the CPU reference.\n"
            "With no SPEC: a quick default sweep of every method that renders here.\n\n"
            "  -b, --benchmark SPEC   method[:key=value[,value...]]... (a comma list sweeps);\n"
            "                         bare SPEC arguments are accepted too\n"
            "  --scenes LIST          scenes for specs without scene= (default sphere,torus,goblet,bunny)\n"
            "  --sizes LIST           sizes for specs without size= (default 256x256)\n"
            "  --frames N             timed frames per configuration, median reported (default 15)\n"
            "  --warmup N             untimed frames first (default 3)\n"
            "  --full-interfaces N    interface cap of the FULL reference (default 10)\n"
            "  --threads N            reference tracer threads (default: all CPUs)\n"
            "  --env FILE|procedural  environment (default procedural)\n"
            "  -o PREFIX              outputs PREFIX.json, .csv, .png (default snell-bench)\n"
            "  --cache DIR            reference cache (default snell-bench-cache); --no-cache\n"
            "  --images DIR           also write each configuration's colour image and error map\n"
            "  --plot-y WHAT          full-mean (default), full-p99, full-rmse, matched-mean\n"
            "  --list                 methods and their keys\n"
            "  --2d ...               the 2D lightmap benchmarks (see --2d --help)\n"
            "  -q                     no progress lines\n"
            "  -h, --help             this text\n\n"
            "example: snell-bench -b single:scene=bunny:size=256x256,512x512 -b single:ior=1.33,2.42\n");
    if (f != stdout) return;
    printf("\nkeys of every method:\n");
    for (k = 0; g_common_params[k].key; k++) printf("  %-12s %s\n", g_common_params[k].key, g_common_params[k].help);
    for (m = 0; m < METHOD_COUNT; m++) {
        printf("method %s: %s\n", g_methods[m].name, g_methods[m].description);
        for (k = 0; g_methods[m].params[k].key; k++)
            printf("  %-12s %s\n", g_methods[m].params[k].key, g_methods[m].params[k].help);
    }
}

static int parse_options(int argc, char **argv, options *o)
{
    int i;
    memset(o, 0, sizeof *o);
    snprintf(o->scenes, sizeof o->scenes, "sphere,torus,goblet,bunny");
    snprintf(o->sizes, sizeof o->sizes, "256x256");
    o->frames = 15;
    o->warmup = 3;
    o->out_prefix = "snell-bench";
    o->cache_dir = "snell-bench-cache";
    o->full_interfaces = 10;
    o->plot_y = "full-mean";
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help") || !strcmp(a, "--list")) {
            usage(stdout);
            exit(0);
        } else if (!strcmp(a, "--no-cache")) {
            o->cache_dir = NULL;
        } else if (!strcmp(a, "-q")) {
            o->quiet = 1;
        } else if (a[0] != '-') {
            if (o->spec_count == 256) return fprintf(stderr, "snell-bench: too many specs\n"), 0;
            o->specs[o->spec_count++] = a;
        } else if (!v) {
            fprintf(stderr, "snell-bench: %s needs a value (or is unknown); see --help\n", a);
            return 0;
        } else {
            i++;
            if (!strcmp(a, "-b") || !strcmp(a, "--benchmark")) {
                if (o->spec_count == 256) return fprintf(stderr, "snell-bench: too many specs\n"), 0;
                o->specs[o->spec_count++] = v;
            } else if (!strcmp(a, "--scenes")) {
                if (strlen(v) >= sizeof o->scenes || !*v) return fprintf(stderr, "snell-bench: bad --scenes\n"), 0;
                strcpy(o->scenes, v);
            } else if (!strcmp(a, "--sizes")) {
                if (strlen(v) >= sizeof o->sizes || !*v) return fprintf(stderr, "snell-bench: bad --sizes\n"), 0;
                strcpy(o->sizes, v);
            } else if (!strcmp(a, "--frames")) {
                if (!parse_int_in("--frames", v, 1, 100000, &o->frames)) return 0;
            } else if (!strcmp(a, "--warmup")) {
                if (!parse_int_in("--warmup", v, 0, 100000, &o->warmup)) return 0;
            } else if (!strcmp(a, "--full-interfaces")) {
                if (!parse_int_in("--full-interfaces", v, 1, SNELL_REF_MAX_INTERFACES, &o->full_interfaces)) return 0;
            } else if (!strcmp(a, "--threads")) {
                if (!parse_int_in("--threads", v, 0, SNELL_REF_MAX_THREADS, &o->threads)) return 0;
            } else if (!strcmp(a, "--env")) {
                o->env = strcmp(v, "procedural") ? v : NULL;
            } else if (!strcmp(a, "-o")) {
                o->out_prefix = v;
            } else if (!strcmp(a, "--cache")) {
                o->cache_dir = v;
            } else if (!strcmp(a, "--images")) {
                o->images_dir = v;
            } else if (!strcmp(a, "--plot-y")) {
                if (strcmp(v, "full-mean") && strcmp(v, "full-p99") && strcmp(v, "full-rmse") && strcmp(v, "matched-mean"))
                    return fprintf(stderr, "snell-bench: --plot-y wants full-mean|full-p99|full-rmse|matched-mean\n"), 0;
                o->plot_y = v;
            } else {
                fprintf(stderr, "snell-bench: unknown option '%s'; see --help\n", a);
                return 0;
            }
        }
    }
    return 1;
}

/* ------------------------------------------------------- spec expansion */
typedef struct spec_key {
    const bench_param *param;
    char key[32];
    char values[MAX_VALUES][256];
    int count;
} spec_key;

typedef struct expansion {
    const bench_method *method;
    spec_key keys[MAX_KEYS + 2];
    int key_count;
    bench_config *out;
    int *n;
} expansion;

static const bench_param *find_param(const bench_method *m, const char *key)
{
    int k;
    for (k = 0; g_common_params[k].key; k++)
        if (!strcmp(g_common_params[k].key, key)) return &g_common_params[k];
    for (k = 0; m->params[k].key; k++)
        if (!strcmp(m->params[k].key, key)) return &m->params[k];
    return NULL;
}

/* Splits "a,b,c" into k->values. */
static int split_values(spec_key *k, const char *list)
{
    const char *s = list;
    k->count = 0;
    for (;;) {
        const char *e = strchr(s, ',');
        size_t n = e ? (size_t)(e - s) : strlen(s);
        if (n == 0 || n >= sizeof k->values[0] || k->count == MAX_VALUES) {
            fprintf(stderr, "snell-bench: %s: empty, too long or too many values in '%s'\n", k->key, list);
            return 0;
        }
        memcpy(k->values[k->count], s, n);
        k->values[k->count++][n] = '\0';
        if (!e) return 1;
        s = e + 1;
    }
}

static void config_defaults(bench_config *c, const bench_method *m)
{
    memset(c, 0, sizeof *c);
    c->method = m;
    c->glass.method = m->id;
    c->cam[0] = 30.0f;
    c->cam[1] = 20.0f;
    c->cam[2] = 3.5f;
    c->width = c->height = 256;
    c->gpu_median = -1.0;
}

/* Cartesian product of the keys' values, depth-first in key order. */
static int expand(expansion *e, int depth, const char **chosen)
{
    int v;
    if (depth == e->key_count) {
        bench_config *c;
        int k;
        size_t len;
        if (*e->n >= MAX_CONFIGS) {
            fprintf(stderr, "snell-bench: more than %d configurations\n", MAX_CONFIGS);
            return 0;
        }
        c = &e->out[(*e->n)++];
        config_defaults(c, e->method);
        len = (size_t)snprintf(c->spec, sizeof c->spec, "%s", e->method->name);
        for (k = 0; k < e->key_count; k++) {
            if (!e->keys[k].param->apply(c, chosen[k])) return 0;
            if (len < sizeof c->spec)
                len += (size_t)snprintf(c->spec + len, sizeof c->spec - len, ":%s=%s", e->keys[k].key, chosen[k]);
        }
        e->method->finalize(c);
        return 1;
    }
    for (v = 0; v < e->keys[depth].count; v++) {
        chosen[depth] = e->keys[depth].values[v];
        if (!expand(e, depth + 1, chosen)) return 0;
    }
    return 1;
}

/* "method:k=v:k=v1,v2" plus the global scene and size lists -> configurations. */
static int expand_spec(const char *spec, const options *o, bench_config *out, int *n)
{
    expansion e;
    char buf[2048], *tok, *save = NULL;
    const char *chosen[MAX_KEYS + 2];
    int m, k, have_scene = 0, have_size = 0;
    memset(&e, 0, sizeof e);
    if (strlen(spec) >= sizeof buf) return fprintf(stderr, "snell-bench: spec too long\n"), 0;
    strcpy(buf, spec);
    tok = strtok_r(buf, ":", &save);
    for (m = 0; tok && m < METHOD_COUNT; m++)
        if (!strcmp(g_methods[m].name, tok)) e.method = &g_methods[m];
    if (!e.method) {
        fprintf(stderr, "snell-bench: unknown method '%s' in '%s'; methods:", tok ? tok : "", spec);
        for (m = 0; m < METHOD_COUNT; m++) fprintf(stderr, " %s", g_methods[m].name);
        fprintf(stderr, "\n");
        return 0;
    }
    /* scene and size first, so that they lead the canonical spec */
    e.key_count = 2;
    while ((tok = strtok_r(NULL, ":", &save)) != NULL) {
        char *eq = strchr(tok, '=');
        spec_key *sk;
        const bench_param *p;
        if (!eq) return fprintf(stderr, "snell-bench: '%s' in '%s' is not key=value\n", tok, spec), 0;
        *eq = '\0';
        if (!(p = find_param(e.method, tok))) {
            fprintf(stderr, "snell-bench: method %s has no key '%s' (see --list)\n", e.method->name, tok);
            return 0;
        }
        if (!strcmp(tok, "scene")) sk = &e.keys[0], have_scene = 1;
        else if (!strcmp(tok, "size")) sk = &e.keys[1], have_size = 1;
        else if (e.key_count == MAX_KEYS + 2) return fprintf(stderr, "snell-bench: too many keys\n"), 0;
        else sk = &e.keys[e.key_count++];
        sk->param = p;
        snprintf(sk->key, sizeof sk->key, "%s", tok);
        if (!split_values(sk, eq + 1)) return 0;
    }
    if (!have_scene) {
        e.keys[0].param = find_param(e.method, "scene");
        strcpy(e.keys[0].key, "scene");
        if (!split_values(&e.keys[0], o->scenes)) return 0;
    }
    if (!have_size) {
        e.keys[1].param = find_param(e.method, "size");
        strcpy(e.keys[1].key, "size");
        if (!split_values(&e.keys[1], o->sizes)) return 0;
    }
    for (k = 0; k < e.key_count; k++) chosen[k] = NULL;
    e.out = out;
    e.n = n;
    return expand(&e, 0, chosen);
}

/* ---------------------------------------------------------------- scenes */
typedef struct scene_entry {
    char name[256];
    snell_mesh *mesh;
} scene_entry;

static scene_entry g_scenes[MAX_SCENES];
static int g_scene_count;

static snell_status get_scene(snell_ctx *ctx, const char *name, snell_mesh **out)
{
    static const char *shapes[] = {"sphere", "cube", "torus", "goblet"};
    snell_status st = SNELL_OK;
    snell_mesh *m = NULL;
    int i;
    for (i = 0; i < g_scene_count; i++)
        if (!strcmp(g_scenes[i].name, name)) {
            *out = g_scenes[i].mesh;
            return SNELL_OK;
        }
    if (g_scene_count == MAX_SCENES) {
        fprintf(stderr, "snell-bench: more than %d scenes\n", MAX_SCENES);
        return SNELL_E_LIMIT;
    }
    for (i = 0; i < 4; i++)
        if (!strcmp(name, shapes[i])) {
            snell_shape_desc sd;
            memset(&sd, 0, sizeof sd);
            sd.shape = (snell_shape)i;
            st = snell_mesh_create_shape(ctx, &sd, &m);
            break;
        }
    if (i == 4) st = snell_mesh_load(ctx, !strcmp(name, "bunny") ? "/usr/share/glmark2/models/bunny.obj" : name, &m);
    if (st == SNELL_OK) st = snell_mesh_normalize(m, 1.0f);
    if (st != SNELL_OK) {
        snell_mesh_destroy(m);
        return st;
    }
    snprintf(g_scenes[g_scene_count].name, sizeof g_scenes[0].name, "%s", name);
    g_scenes[g_scene_count++].mesh = m;
    *out = m;
    return SNELL_OK;
}

/* ------------------------------------------------------------- running */

static void frame_of(const bench_config *c, const snell_mesh *mesh, const snell_env *env, snell_frame_desc *fd)
{
    memset(fd, 0, sizeof *fd);
    fd->mesh = mesh;
    fd->env = env;
    fd->glass = c->glass;
    fd->camera.azimuth = (float)(c->cam[0] * PI / 180.0);
    fd->camera.elevation = (float)(c->cam[1] * PI / 180.0);
    fd->camera.distance = c->cam[2];
}

static void fail_config(bench_config *c, const char *what, snell_ctx *ctx)
{
    const char *msg = snell_last_error(ctx);
    if (!msg || !*msg) msg = snell_last_error(NULL);
    snprintf(c->error, sizeof c->error, "%s: %s", what, msg && *msg ? msg : "failed");
    c->ok = 0;
}

/* Error map for --images: grey background, glass pixels coloured by the
 * log of the angle, 0.01 degrees (black) .. 10 degrees (white), red = NaN. */
static void write_error_map(const char *path, const float *err, const uint8_t *mask, const float *dirs, int w,
                            int h)
{
    uint8_t *px = (uint8_t *)malloc((size_t)w * h * 4);
    long i;
    if (!px) return;
    for (i = 0; i < (long)w * h; i++) {
        uint8_t *p = px + 4 * i;
        p[3] = 255;
        if (!isfinite(dirs[3 * i]) || !isfinite(dirs[3 * i + 1]) || !isfinite(dirs[3 * i + 2])) {
            p[0] = 255, p[1] = p[2] = 0;
        } else if (!mask[i] || isnan(err[i])) {
            p[0] = p[1] = p[2] = 64;
        } else {
            double t = (log10(err[i] > 1e-4f ? err[i] : 1e-4f) + 2.0) / 3.0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            p[0] = (uint8_t)(255 * t);
            p[1] = (uint8_t)(255 * t * t);
            p[2] = (uint8_t)(255 * 2 * t * (1 - t));
        }
    }
    snell_write_png(path, w, h, px);
    free(px);
}

static void sanitize(char *s)
{
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '.' ||
              *s == '-' || *s == '='))
            *s = '_';
}

/* One configuration while it is being timed. */
typedef struct timing_slot {
    bench_config *c;
    snell_renderer *r;
    snell_frame_desc fd;
    double *times, *gpu, *ratio;
    int gpu_n;
} timing_slot;

/* One frame of t; recorded as round `round` if record, else warm-up. A
 * failure marks the configuration failed (c->ok = 0). */
static void time_frame(snell_ctx *ctx, timing_slot *t, int record, int round)
{
    double t0 = bench_now_ms(), g;
    snell_status st;
    bench_timer_begin();
    st = snell_render(t->r, &t->fd, NULL);
    bench_timer_end();
    snell_renderer_finish(t->r);
    if (st != SNELL_OK) {
        fail_config(t->c, "render", ctx);
        return;
    }
    if (!record) {
        bench_timer_read();
        return;
    }
    t->times[round] = bench_now_ms() - t0;
    g = bench_timer_read();
    if (g >= 0.0) t->gpu[t->gpu_n++] = g;
}

/* Times the m configurations cs[idx[0..m)] (one scene and size; base = the
 * position in idx of its single-surface configuration, or -1): each gets its
 * warm-up frames, then o->frames rounds in which every configuration renders
 * one frame, the order rotating from round to round. */
static void time_group(snell_ctx *ctx, const snell_env *env, const options *o, bench_config *cs, const int *idx, int m,
                       int base)
{
    timing_slot *ts = (timing_slot *)calloc((size_t)m, sizeof *ts);
    int i, r, k;
    if (!ts) {
        for (i = 0; i < m; i++) {
            cs[idx[i]].ok = 0;
            snprintf(cs[idx[i]].error, sizeof cs[idx[i]].error, "out of memory");
        }
        return;
    }
    for (i = 0; i < m; i++) {
        timing_slot *t = &ts[i];
        snell_renderer_desc desc;
        snell_mesh *mesh = NULL;
        t->c = &cs[idx[i]];
        t->c->ok = 1;
        t->c->frames = o->frames;
        t->c->vs_single = -1.0;
        t->times = (double *)malloc(sizeof(double) * (size_t)o->frames);
        t->gpu = (double *)malloc(sizeof(double) * (size_t)o->frames);
        t->ratio = (double *)malloc(sizeof(double) * (size_t)o->frames);
        if (!t->times || !t->gpu || !t->ratio) {
            snprintf(t->c->error, sizeof t->c->error, "out of memory");
            t->c->ok = 0;
            continue;
        }
        if (get_scene(ctx, t->c->scene, &mesh) != SNELL_OK) {
            fail_config(t->c, "scene", ctx);
            continue;
        }
        memset(&desc, 0, sizeof desc);
        desc.width = t->c->width;
        desc.height = t->c->height;
        if (snell_renderer_create(ctx, &desc, &t->r) != SNELL_OK) {
            fail_config(t->c, "renderer", ctx);
            continue;
        }
        frame_of(t->c, mesh, env, &t->fd);
        for (k = 0; k < o->warmup && t->c->ok; k++) time_frame(ctx, t, 0, 0);
    }
    for (r = 0; r < o->frames; r++)
        for (k = 0; k < m; k++) {
            timing_slot *t = &ts[(k + r) % m];
            if (t->c->ok) time_frame(ctx, t, 1, r);
        }
    for (i = 0; i < m; i++) {
        timing_slot *t = &ts[i];
        if (t->c->ok && base >= 0 && ts[base].c->ok) {
            for (r = 0; r < o->frames; r++) t->ratio[r] = t->times[r] / ts[base].times[r];
            t->c->vs_single = bench_median(t->ratio, o->frames);
        }
    }
    for (i = 0; i < m; i++) {
        timing_slot *t = &ts[i];
        if (t->c->ok) {
            t->c->t_median = bench_median(t->times, o->frames); /* sorts */
            t->c->t_min = t->times[0];
            t->c->t_max = t->times[o->frames - 1];
            t->c->gpu_median = t->gpu_n == o->frames ? bench_median(t->gpu, t->gpu_n) : -1.0;
        }
        snell_renderer_destroy(t->r);
        free(t->times);
        free(t->gpu);
        free(t->ratio);
    }
    free(ts);
}

static int same_group(const bench_config *a, const bench_config *b)
{
    return !strcmp(a->scene, b->scene) && a->width == b->width && a->height == b->height;
}

/* Times every configuration: those of one scene and size interleaved (at
 * most MAX_INTERLEAVED at once; a larger group is timed in parts, each with
 * the group's single-surface configuration, if any, so every ratio is taken
 * within one part). */
static void time_all(snell_ctx *ctx, const snell_env *env, const options *o, bench_config *cs, int n)
{
    int *done = (int *)calloc((size_t)(n > 0 ? n : 1), sizeof(int));
    int idx[MAX_INTERLEAVED], i, j, k, m, single, part;
    if (!done) {
        for (i = 0; i < n; i++) {
            cs[i].ok = 0;
            snprintf(cs[i].error, sizeof cs[i].error, "out of memory");
        }
        return;
    }
    for (i = 0; i < n; i++) {
        if (done[i]) continue;
        single = -1;
        for (j = i; j < n && single < 0; j++)
            if (!done[j] && cs[j].method->id == SNELL_METHOD_SINGLE && same_group(&cs[j], &cs[i])) single = j;
        j = i;
        for (part = 0;; part++) {
            m = 0;
            if (single >= 0) idx[m++] = single;
            for (; j < n && m < MAX_INTERLEAVED; j++)
                if (!done[j] && j != single && same_group(&cs[j], &cs[i])) idx[m++] = j;
            if (part > 0 && m == (single >= 0)) break; /* nothing left but the baseline */
            if (!o->quiet)
                fprintf(stderr, "timing %d configuration(s) of %s at %dx%d, taking turns frame by frame\n", m,
                        cs[i].scene, cs[i].width, cs[i].height);
            time_group(ctx, env, o, cs, idx, m, single >= 0 ? 0 : -1);
            for (k = 0; k < m; k++) done[idx[k]] = 1;
            if (j >= n) break;
        }
    }
    free(done);
}

static void run_config(snell_ctx *ctx, const snell_env *env, const char *env_name, const options *o,
                       bench_config *c)
{
    snell_mesh *mesh = NULL;
    snell_renderer *rc = NULL, *rd = NULL;
    snell_renderer_desc desc;
    snell_frame_desc fd, bg;
    size_t n = (size_t)c->width * (size_t)c->height;
    uint8_t *rgba = (uint8_t *)malloc(n * 4), *mask = (uint8_t *)malloc(n), *either = (uint8_t *)malloc(n);
    float *dirs = (float *)malloc(n * 3 * sizeof(float)), *bgdirs = (float *)malloc(n * 3 * sizeof(float));
    float *err = (float *)malloc(n * sizeof(float));
    int i, mode;
    if (!c->ok) return; /* timing failed */
    if (!rgba || !mask || !either || !dirs || !bgdirs || !err) {
        snprintf(c->error, sizeof c->error, "out of memory");
        c->ok = 0;
        goto done;
    }
    if (get_scene(ctx, c->scene, &mesh) != SNELL_OK) {
        fail_config(c, "scene", ctx);
        goto done;
    }
    memset(&desc, 0, sizeof desc);
    desc.width = c->width;
    desc.height = c->height;
    if (snell_renderer_create(ctx, &desc, &rc) != SNELL_OK) {
        fail_config(c, "renderer", ctx);
        goto done;
    }
    frame_of(c, mesh, env, &fd);

    /* The colour image (timing is done before, in time_group). */
    if (snell_render(rc, &fd, NULL) != SNELL_OK) {
        fail_config(c, "render", ctx);
        goto done;
    }
    if (snell_renderer_read_rgba(rc, rgba) != SNELL_OK) {
        fail_config(c, "readback", ctx);
        goto done;
    }

    /* Exit directions, and a background-only frame for the coverage mask. */
    desc.output = SNELL_OUTPUT_EXIT_DIRECTION;
    if (snell_renderer_create(ctx, &desc, &rd) != SNELL_OK) {
        fail_config(c, "exit-direction renderer", ctx);
        goto done;
    }
    c->encoding = snell_renderer_exit_dir_encoding(rd);
    bg = fd;
    bg.mesh = NULL;
    if (snell_render(rd, &bg, NULL) != SNELL_OK || snell_renderer_read_exit_dirs(rd, bgdirs) != SNELL_OK ||
        snell_render(rd, &fd, NULL) != SNELL_OK || snell_renderer_read_exit_dirs(rd, dirs) != SNELL_OK) {
        fail_config(c, "exit-direction frame", ctx);
        goto done;
    }
    snell_metrics_coverage_mask(dirs, bgdirs, (long)n, mask);
    c->nan_inf = 0;
    for (i = 0; i < (int)n; i++)
        c->nan_inf += !isfinite(dirs[3 * i]) || !isfinite(dirs[3 * i + 1]) || !isfinite(dirs[3 * i + 2]);

    for (mode = 0; mode < 2; mode++) {
        snell_ref_params p;
        bench_ref_image ref;
        snell_dir_error_desc dd;
        char key[1024];
        snell_status st;
        size_t j;
        memset(&p, 0, sizeof p);
        p.mode = mode ? SNELL_REF_FULL : SNELL_REF_MATCHED;
        p.max_interfaces = mode ? o->full_interfaces : c->ref_interfaces;
        p.absorption_model = mode ? SNELL_REF_ABSORB_PATH : c->ref_absorb;
        p.glass = c->glass;
        p.env = env;
        p.camera = fd.camera;
        p.width = c->width;
        p.height = c->height;
        p.threads = o->threads;
        snprintf(key, sizeof key,
                 "scene=%s env=%s size=%dx%d cam=%.9g/%.9g/%.9g ior=%.9g abs=%.9g/%.9g/%.9g tint=%.9g/%.9g/%.9g "
                 "mode=%d interfaces=%d absorb=%d",
                 c->scene, env_name, c->width, c->height, c->cam[0], c->cam[1], c->cam[2], c->glass.ior,
                 c->glass.absorption[0], c->glass.absorption[1], c->glass.absorption[2], c->glass.tint[0],
                 c->glass.tint[1], c->glass.tint[2], (int)p.mode, p.max_interfaces, (int)p.absorption_model);
        if (!o->quiet)
            fprintf(stderr, "    reference %s (%d interfaces)...\n", mode ? "FULL" : "MATCHED", p.max_interfaces);
        st = bench_ref_get(mesh, &p, o->cache_dir, key, &ref, &c->ref_cached[mode]);
        if (st != SNELL_OK) {
            fail_config(c, mode ? "FULL reference" : "MATCHED reference", NULL);
            goto done;
        }
        memset(&dd, 0, sizeof dd);
        dd.test = dirs;
        dd.ref = ref.exit_dir;
        dd.ref_mask = ref.hit;
        dd.test_mask = mask;
        dd.width = c->width;
        dd.height = c->height;
        dd.error_deg = err;
        snell_metrics_dir_error(&dd, &c->dir[mode]);
        snell_metrics_image_error(rgba, ref.rgba, c->width, c->height, NULL, &c->img[mode]);
        for (j = 0; j < n; j++) either[j] = (uint8_t)(mask[j] || ref.hit[j]);
        snell_metrics_image_error(rgba, ref.rgba, c->width, c->height, either, &c->img_glass[mode]);
        if (o->images_dir) {
            char path[1400], name[600];
            snprintf(name, sizeof name, "%s", c->spec);
            sanitize(name);
            if (mode == 0) {
                snprintf(path, sizeof path, "%s/%s.png", o->images_dir, name);
                snell_write_png(path, c->width, c->height, rgba);
            }
            snprintf(path, sizeof path, "%s/%s.ref-%s.png", o->images_dir, name, mode ? "full" : "matched");
            snell_write_png(path, c->width, c->height, ref.rgba);
            snprintf(path, sizeof path, "%s/%s.err-%s.png", o->images_dir, name, mode ? "full" : "matched");
            write_error_map(path, err, mask, dirs, c->width, c->height);
        }
        bench_ref_free(&ref);
    }
done:
    snell_renderer_destroy(rc);
    snell_renderer_destroy(rd);
    free(rgba);
    free(mask);
    free(either);
    free(dirs);
    free(bgdirs);
    free(err);
}

/* --------------------------------------------------------------- output */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\') fprintf(f, "\\%c", ch);
        else if (ch < 0x20) fprintf(f, "\\u%04x", ch);
        else fputc(ch, f);
    }
    fputc('"', f);
}

static void json_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "%.6g", v);
    else fprintf(f, "null");
}

static void json_errors(FILE *f, const bench_config *c, int m)
{
    const snell_dir_error *d = &c->dir[m];
    fprintf(f, "{\"mean_deg\": ");
    json_num(f, d->mean_deg);
    fprintf(f, ", \"rms_deg\": ");
    json_num(f, d->rms_deg);
    fprintf(f, ", \"median_deg\": ");
    json_num(f, d->median_deg);
    fprintf(f, ", \"p99_deg\": ");
    json_num(f, d->p99_deg);
    fprintf(f, ", \"max_deg\": ");
    json_num(f, d->max_deg);
    fprintf(f, ", \"frac_above_1deg\": ");
    json_num(f, d->frac_above_1deg);
    fprintf(f, ", \"frac_above_5deg\": ");
    json_num(f, d->frac_above_5deg);
    fprintf(f, ", \"compared\": %ld, \"mask_mismatch\": %ld, \"glass_ref\": %ld, \"glass_test\": %ld", d->compared,
            d->mask_mismatch, d->glass_ref, d->glass_test);
    fprintf(f, ", \"rmse\": ");
    json_num(f, c->img[m].rmse);
    fprintf(f, ", \"psnr_db\": ");
    json_num(f, c->img[m].psnr_db);
    fprintf(f, ", \"rmse_glass\": ");
    json_num(f, c->img_glass[m].rmse);
    fprintf(f, ", \"psnr_glass_db\": ");
    json_num(f, c->img_glass[m].psnr_db);
    fprintf(f, ", \"reference_cached\": %s}", c->ref_cached[m] ? "true" : "false");
}

static int write_json(const char *path, const bench_config *cs, int n, const options *o, const char *renderer,
                      int timer, const char *load_before, const char *load_after, const char *date)
{
    FILE *f = fopen(path, "w");
    int i;
    if (!f) return 0;
    fprintf(f, "{\n  \"tool\": \"snell-bench\",\n  \"date\": ");
    json_str(f, date);
    fprintf(f, ",\n  \"gl_renderer\": ");
    json_str(f, renderer);
    fprintf(f, ",\n  \"timer_query\": %s,\n  \"timing\": ", timer ? "true" : "false");
    json_str(f, "median of frames after warm-up; each frame = snell_render + glFinish (CPU wall clock); the "
                "configurations of one scene and size take turns frame by frame; vs_single = median over rounds of "
                "the ratio to the single-surface configuration's frame of the same round");
    fprintf(f, ",\n  \"frames\": %d,\n  \"warmup\": %d,\n  \"full_interfaces\": %d,\n  \"loadavg_before\": ", o->frames,
            o->warmup, o->full_interfaces);
    json_str(f, load_before);
    fprintf(f, ",\n  \"loadavg_after\": ");
    json_str(f, load_after);
    fprintf(f, ",\n  \"mask_policy\": ");
    json_str(f, "angles over pixels that are glass in both the reference hit mask and the method's coverage; "
                "mismatches counted, not compared");
    fprintf(f, ",\n  \"results\": [\n");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        fprintf(f, "    {\"spec\": ");
        json_str(f, c->spec);
        fprintf(f, ", \"method\": ");
        json_str(f, c->method->name);
        fprintf(f, ", \"scene\": ");
        json_str(f, c->scene);
        fprintf(f, ", \"width\": %d, \"height\": %d, \"ior\": ", c->width, c->height);
        json_num(f, c->glass.ior > 0 ? c->glass.ior : 1.5);
        fprintf(f, ", \"ok\": %s", c->ok ? "true" : "false");
        if (!c->ok) {
            fprintf(f, ", \"error\": ");
            json_str(f, c->error);
            fprintf(f, "}%s\n", i + 1 < n ? "," : "");
            continue;
        }
        fprintf(f, ", \"time_ms\": {\"median\": ");
        json_num(f, c->t_median);
        fprintf(f, ", \"min\": ");
        json_num(f, c->t_min);
        fprintf(f, ", \"max\": ");
        json_num(f, c->t_max);
        fprintf(f, ", \"gpu_median\": ");
        json_num(f, c->gpu_median >= 0 ? c->gpu_median : NAN);
        fprintf(f, "}, \"vs_single\": ");
        json_num(f, c->vs_single >= 0 ? c->vs_single : NAN);
        fprintf(f, ", \"pareto\": %s, \"exit_dir_encoding\": ", c->pareto ? "true" : "false");
        json_str(f, c->encoding);
        fprintf(f, ", \"nan_inf\": %ld, \"matched_interfaces\": %d,\n     \"vs_matched\": ", c->nan_inf,
                c->ref_interfaces);
        json_errors(f, c, 0);
        fprintf(f, ",\n     \"vs_full\": ");
        json_errors(f, c, 1);
        fprintf(f, "}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    return fclose(f) == 0;
}

static void csv_num(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, ",%.6g", v);
    else fprintf(f, ",");
}

static int write_csv(const char *path, const bench_config *cs, int n)
{
    FILE *f = fopen(path, "w");
    int i, m;
    if (!f) return 0;
    fprintf(f, "spec,method,scene,width,height,ior,ok,time_median_ms,time_min_ms,time_max_ms,gpu_median_ms,"
               "vs_single,pareto,exit_dir_encoding,nan_inf");
    for (m = 0; m < 2; m++) {
        const char *p = m ? "full" : "matched";
        fprintf(f, ",%s_mean_deg,%s_rms_deg,%s_median_deg,%s_p99_deg,%s_max_deg,%s_frac_above_1deg,"
                   "%s_frac_above_5deg,%s_compared,%s_mask_mismatch,%s_rmse,%s_psnr_db,%s_rmse_glass",
                p, p, p, p, p, p, p, p, p, p, p, p);
    }
    fprintf(f, ",error\n");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        fprintf(f, "\"%s\",%s,\"%s\",%d,%d,%g,%d", c->spec, c->method->name, c->scene, c->width, c->height,
                c->glass.ior > 0 ? c->glass.ior : 1.5, c->ok);
        if (c->ok) {
            csv_num(f, c->t_median);
            csv_num(f, c->t_min);
            csv_num(f, c->t_max);
            csv_num(f, c->gpu_median >= 0 ? c->gpu_median : NAN);
            csv_num(f, c->vs_single >= 0 ? c->vs_single : NAN);
            fprintf(f, ",%d,%s,%ld", c->pareto, c->encoding, c->nan_inf);
            for (m = 0; m < 2; m++) {
                const snell_dir_error *d = &c->dir[m];
                csv_num(f, d->mean_deg);
                csv_num(f, d->rms_deg);
                csv_num(f, d->median_deg);
                csv_num(f, d->p99_deg);
                csv_num(f, d->max_deg);
                csv_num(f, d->frac_above_1deg);
                csv_num(f, d->frac_above_5deg);
                fprintf(f, ",%ld,%ld", d->compared, d->mask_mismatch);
                csv_num(f, c->img[m].rmse);
                csv_num(f, c->img[m].psnr_db);
                csv_num(f, c->img_glass[m].rmse);
            }
            fprintf(f, ",\n");
        } else {
            fprintf(f, ",,,,,,,,%s", "");
            for (m = 0; m < 25; m++) fputc(',', f);
            fprintf(f, "\"%s\"\n", c->error);
        }
    }
    return fclose(f) == 0;
}

static double plot_value(const bench_config *c, const char *what)
{
    if (!strcmp(what, "full-p99")) return c->dir[1].p99_deg;
    if (!strcmp(what, "full-rmse")) return c->img_glass[1].rmse;
    if (!strcmp(what, "matched-mean")) return c->dir[0].mean_deg;
    return c->dir[1].mean_deg;
}

/* cs[i].pareto: not dominated in (median time, plot's error) by another
 * configuration of the same scene and size. */
static void mark_pareto(bench_config *cs, int n, const options *o)
{
    bench_plot_point *pts = (bench_plot_point *)calloc((size_t)(n > 0 ? n : 1), sizeof *pts);
    int *front = (int *)calloc((size_t)(n > 0 ? n : 1), sizeof(int)), *at = (int *)calloc((size_t)(n > 0 ? n : 1), sizeof(int));
    int i, j, count = 0;
    for (i = 0; i < n; i++) cs[i].pareto = 0;
    if (pts && front && at) {
        for (i = 0; i < n; i++) {
            if (!cs[i].ok) continue;
            for (j = 0; j < i && !(cs[j].ok && same_group(&cs[j], &cs[i])); j++) {}
            pts[count].group = j; /* first configuration of the group */
            pts[count].x = cs[i].t_median;
            pts[count].y = plot_value(&cs[i], o->plot_y);
            at[count++] = i;
        }
        bench_pareto(pts, count, front);
        for (i = 0; i < count; i++) cs[at[i]].pareto = front[i];
    }
    free(pts);
    free(front);
    free(at);
}

static int write_plot(const char *path, const bench_config *cs, int n, const options *o, const char *renderer,
                      int timer, const char *date, const char *load)
{
    bench_plot_point *pts = (bench_plot_point *)calloc((size_t)(n > 0 ? n : 1), sizeof *pts);
    char (*labels)[64] = (char (*)[64])calloc((size_t)(n > 0 ? n : 1), 64);
    char groups[MAX_SCENES * 8][300];
    const char *scene_names[MAX_SCENES], *method_names[8];
    char subtitle[512], ylabel[160];
    int i, k, ngroups = 0, nscenes = 0, count = 0, ok, several_sizes = 0;
    bench_plot_desc d;
    if (!pts || !labels) {
        free(pts);
        free(labels);
        return 0;
    }
    for (k = 0; k < METHOD_COUNT && k < 8; k++) method_names[k] = g_methods[k].name;
    for (i = 1; i < n; i++)
        if (cs[i].width != cs[0].width || cs[i].height != cs[0].height) several_sizes = 1;
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        char g[300];
        const char *params;
        if (!c->ok) continue;
        for (k = 0; k < nscenes; k++)
            if (!strcmp(scene_names[k], c->scene)) break;
        if (k == nscenes && nscenes < MAX_SCENES) scene_names[nscenes++] = c->scene;
        pts[count].color = k;
        snprintf(g, sizeof g, "%s %dx%d", c->scene, c->width, c->height);
        for (k = 0; k < ngroups; k++)
            if (!strcmp(groups[k], g)) break;
        if (k == ngroups && ngroups < (int)(sizeof groups / sizeof *groups)) strcpy(groups[ngroups++], g);
        pts[count].group = k;
        pts[count].marker = (int)(c->method - g_methods);
        pts[count].x = c->t_median;
        pts[count].y = plot_value(c, o->plot_y);
        /* label: the width when sizes differ, then the method's own keys
         * (scene and size lead the canonical spec) */
        params = strchr(c->spec, ':');
        for (k = 0; params && k < 2; k++) params = strchr(params + 1, ':');
        if (several_sizes) snprintf(labels[count], 64, "%d%s%s", c->width, params ? " " : "", params ? params + 1 : "");
        else snprintf(labels[count], 64, "%s", params ? params + 1 : "");
        pts[count].label = labels[count];
        count++;
    }
    snprintf(subtitle, sizeof subtitle, "%s; median of %d frames after %d warm-up, glFinish%s; %s; load %s",
             renderer, o->frames, o->warmup, timer ? " (GL timer query in JSON)" : " (no GL timer query)", date, load);
    snprintf(ylabel, sizeof ylabel, "%s",
             !strcmp(o->plot_y, "full-p99")       ? "99th percentile exit-direction error vs FULL reference [deg]"
             : !strcmp(o->plot_y, "full-rmse")    ? "RMSE of glass pixels vs FULL reference [8-bit units]"
             : !strcmp(o->plot_y, "matched-mean") ? "mean exit-direction error vs MATCHED reference [deg]"
                                                  : "mean exit-direction error vs FULL reference [deg]");
    memset(&d, 0, sizeof d);
    d.title = "snell-bench: frame time vs error";
    d.subtitle = subtitle;
    d.x_label = several_sizes ? "median frame time [ms]  (labels: image width, method parameters)"
                              : "median frame time [ms]";
    d.y_label = ylabel;
    d.points = pts;
    d.count = count;
    d.color_names = scene_names;
    d.color_count = nscenes;
    d.marker_names = method_names;
    d.marker_count = METHOD_COUNT < 8 ? METHOD_COUNT : 8;
    ok = bench_plot_write(path, &d) == SNELL_OK;
    free(pts);
    free(labels);
    return ok;
}

static void read_loadavg(char *buf, size_t n)
{
    FILE *f = fopen("/proc/loadavg", "r");
    float a = 0, b = 0, c = 0;
    if (f && fscanf(f, "%f %f %f", &a, &b, &c) == 3) snprintf(buf, n, "%.2f %.2f %.2f", a, b, c);
    else snprintf(buf, n, "unknown");
    if (f) fclose(f);
}

/* Does the method render here? The default sweep skips those that do not. */
static int method_works(snell_ctx *ctx, const snell_env *env, const bench_method *m)
{
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_mesh *mesh = NULL;
    int ok;
    memset(&rd, 0, sizeof rd);
    rd.width = rd.height = 16;
    if (get_scene(ctx, "sphere", &mesh) != SNELL_OK || snell_renderer_create(ctx, &rd, &r) != SNELL_OK) return 0;
    memset(&fd, 0, sizeof fd);
    fd.mesh = mesh;
    fd.env = env;
    fd.glass.method = m->id;
    ok = snell_render(r, &fd, NULL) == SNELL_OK;
    if (!ok) fprintf(stderr, "snell-bench: method %s skipped: %s\n", m->name, snell_last_error(ctx));
    snell_renderer_destroy(r);
    return ok;
}


int main(int argc, char **argv)
{
    options o;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_env_desc ed;
    bench_config *cs = NULL;
    int i, n = 0, rc = 0, timer, failed = 0;
    char path[1200], load_before[64], load_after[64], date[64];
    const char *renderer;
    double t_start = bench_now_ms();
    time_t now = time(NULL);

    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--2d")) {
            return snell_bench2d_main(argc, argv);
        }
    if (!parse_options(argc, argv, &o)) return 2;
    cs = (bench_config *)calloc(MAX_CONFIGS, sizeof *cs);
    if (!cs) return fprintf(stderr, "snell-bench: out of memory\n"), 1;
    for (i = 0; i < o.spec_count; i++)
        if (!expand_spec(o.specs[i], &o, cs, &n)) {
            free(cs);
            return 2;
        }

    memset(&cd, 0, sizeof cd);
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-bench: cannot create a GL context: %s\n", snell_last_error(NULL));
        free(cs);
        return 1;
    }
    memset(&ed, 0, sizeof ed);
    if (o.env) {
        ed.source = SNELL_ENV_EQUIRECT;
        ed.equirect_path = o.env;
    }
    if (snell_env_create(ctx, &ed, &env) != SNELL_OK) {
        fprintf(stderr, "snell-bench: environment: %s\n", snell_last_error(ctx));
        rc = 1;
        goto done;
    }
    if (o.spec_count == 0) {
        /* Default sweep: every method that renders here, with its default parameters. */
        for (i = 0; i < METHOD_COUNT; i++) {
            char spec[512];
            if (!method_works(ctx, env, &g_methods[i])) continue;
            snprintf(spec, sizeof spec, "%s%s%s", g_methods[i].name, *g_methods[i].default_sweep ? ":" : "",
                     g_methods[i].default_sweep);
            if (!expand_spec(spec, &o, cs, &n)) {
                rc = 2;
                goto done;
            }
        }
    }
    renderer = snell_ctx_gl_renderer(ctx);
    timer = bench_timer_init(ctx);
    read_loadavg(load_before, sizeof load_before);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M", localtime(&now));
    if (!o.quiet) {
        fprintf(stderr, "snell-bench: %d configuration(s) on %s; load %s\n", n, renderer, load_before);
        fprintf(stderr, "snell-bench: GL_EXT_disjoint_timer_query %s\n",
                timer ? "present: GPU times reported too"
                      : "not available: times are CPU wall clock of render + glFinish only");
    }
    time_all(ctx, env, &o, cs, n);
    for (i = 0; i < n; i++) {
        bench_config *c = &cs[i];
        if (!o.quiet) fprintf(stderr, "[%d/%d] %s\n", i + 1, n, c->spec);
        run_config(ctx, env, o.env ? o.env : "procedural", &o, c);
        if (!c->ok) {
            failed++;
            fprintf(stderr, "[%d/%d] %s FAILED: %s\n", i + 1, n, c->spec, c->error);
        } else if (!o.quiet) {
            fprintf(stderr,
                    "[%d/%d] %.2f ms/frame (GL timer %.2f); vs MATCHED(%d) mean %.3g deg; vs FULL mean %.3g deg, >1deg %.1f%%, "
                    ">5deg %.1f%%, PSNR %.1f dB; NaN/Inf %ld; %.0f s elapsed\n",
                    i + 1, n, c->t_median, c->gpu_median, c->ref_interfaces, c->dir[0].mean_deg, c->dir[1].mean_deg,
                    100.0 * c->dir[1].frac_above_1deg, 100.0 * c->dir[1].frac_above_5deg, c->img[1].psnr_db,
                    c->nan_inf, (bench_now_ms() - t_start) / 1000.0);
        }
    }
    read_loadavg(load_after, sizeof load_after);
    mark_pareto(cs, n, &o);

    snprintf(path, sizeof path, "%s.json", o.out_prefix);
    if (!write_json(path, cs, n, &o, renderer, timer, load_before, load_after, date)) {
        fprintf(stderr, "snell-bench: cannot write %s\n", path);
        rc = 1;
    }
    snprintf(path, sizeof path, "%s.csv", o.out_prefix);
    if (!write_csv(path, cs, n)) {
        fprintf(stderr, "snell-bench: cannot write %s\n", path);
        rc = 1;
    }
    snprintf(path, sizeof path, "%s.png", o.out_prefix);
    if (!write_plot(path, cs, n, &o, renderer, timer, date, load_before)) {
        fprintf(stderr, "snell-bench: cannot write %s\n", path);
        rc = 1;
    }
    printf("%-58s %9s %7s %9s %9s %7s %7s %6s %6s\n", "configuration", "ms/frame", "xsingle", "deg/MATCH", "deg/FULL",
           ">1deg", ">5deg", "NaN", "pareto");
    for (i = 0; i < n; i++) {
        const bench_config *c = &cs[i];
        if (!c->ok) {
            printf("%-58s FAILED: %s\n", c->spec, c->error);
            continue;
        }
        printf("%-58s %9.2f %7.3f %9.3g %9.3g %6.1f%% %6.1f%% %6ld %6s\n", c->spec, c->t_median, c->vs_single,
               c->dir[0].mean_deg, c->dir[1].mean_deg, 100.0 * c->dir[1].frac_above_1deg,
               100.0 * c->dir[1].frac_above_5deg, c->nan_inf, c->pareto ? "*" : "");
    }
    printf("wrote %s.json, %s.csv, %s.png (%.1f s)\n", o.out_prefix, o.out_prefix, o.out_prefix,
           (bench_now_ms() - t_start) / 1000.0);
    if (failed) rc = 1;
done:
    for (i = 0; i < g_scene_count; i++) snell_mesh_destroy(g_scenes[i].mesh);
    snell_env_destroy(env);
    snell_ctx_destroy(ctx);
    free(cs);
    return rc;
}
