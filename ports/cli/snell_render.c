#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* snell-render — renders one frame of a glass object to PNG.
 * With no arguments: the built-in glass object in the procedural environment,
 * written to snell.png. Exit status 0 on success, 1 on a runtime failure,
 * 2 on bad usage. */
#include "snell/snell.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846
#define STR_(x) #x
#define STR(x) STR_(x) /* a default from snell.h, spelled out in --help */

typedef struct options {
    const char *mesh;       /* NULL: built-in shape */
    snell_shape shape;
    const char *env;        /* NULL or "procedural" */
    const char *out;
    float ior;
    float absorption[3];
    int width, height;
    float az_deg, el_deg, dist, fov_deg;
    snell_method method;
    snell_backend backend;
    int frames;             /* >1: time the frames and print the median */
    int normalize;
    int iterations, linear_steps, interfaces, face_size;  /* cubemap method; 0 = library default */
    snell_ndcube_encoding encoding;
    int stats;              /* print the frame statistics */
    int trace_xy[32];       /* --trace-pixel X,Y (repeatable, up to 16) */
    int trace_count;
    int opaque;             /* demo: this many opaque cubes orbiting the glass (move every frame) */
} options;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: snell-render [options]\n"
            "Renders refractive glass to a PNG (default: built-in object -> snell.png).\n\n"
            "  --mesh FILE            OBJ, glTF (.gltf/.glb) mesh, or shape:sphere|cube|torus|goblet (default sphere)\n"
            "  --env FILE|procedural  environment: procedural (default), an equirectangular image,\n"
            "                         or six faces given as a pattern with %%s (px nx py ny pz nz)\n"
            "  --ior N                index of refraction (default 1.5)\n"
            "  --absorption R,G,B     Beer-Lambert coefficient per unit length (default 0,0,0)\n"
            "  --size WxH             image size (default 512x512)\n"
            "  --camera AZ,EL,DIST    orbit camera: degrees, degrees, distance (default 30,20,3.5)\n"
            "  --fov DEG              vertical field of view (default 45)\n"
            "  --method NAME          refraction method: single, cubemap, auto (default auto)\n"
            "  --iterations N         cubemap: binary-search steps per interface, 1..32 (default "
            STR(SNELL_CUBEMAP_DEFAULT_ITERATIONS) ")\n"
            "  --linear-steps N       cubemap: linear pre-search steps, 0..32 (default 0)\n"
            "  --interfaces N         cubemap: surfaces per light path, 1..8 (default "
            STR(SNELL_CUBEMAP_DEFAULT_INTERFACES) ")\n"
            "  --face-size N          cubemap: normal+distance cubemap face, 16..2048 (default "
            STR(SNELL_CUBEMAP_DEFAULT_FACE_SIZE) ")\n"
            "  --encoding plain|oct   cubemap: texel packing (default plain)\n"
            "  --stats                print the last frame's statistics\n"
            "  --opaque N             demo scene: N opaque cubes (0..16) orbiting the glass, moving each frame;\n"
            "                         the glass sees them through a dynamic environment\n"
            "  --backend NAME         surfaceless (default), pbuffer\n"
            "  --no-normalize         keep the mesh's own scale (default: fit in the unit sphere)\n"
            "  --frames N             render N frames and print the median time per frame\n"
            "  -o FILE                output PNG (default snell.png)\n"
            "  --trace-pixel X,Y      reference light path of pixel X,Y (repeatable): drawn over a second\n"
            "                         view into FILE_trace.png, points in FILE_trace.json\n"
            "  --2d SCENE             2D lightmap mode (see the 2D options with --2d --help)\n"
            "  -h, --help             this text\n");
}

static int parse_floats(const char *s, float *out, int n)
{
    int i;
    char *end;
    for (i = 0; i < n; i++) {
        errno = 0;
        out[i] = strtof(s, &end);
        if (end == s || errno || !isfinite(out[i])) return 0;
        s = end;
        if (i < n - 1) {
            if (*s != ',') return 0;
            s++;
        }
    }
    return *s == '\0';
}

static int parse_int(const char *s, int *out)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < -1000000 || v > 1000000) return 0;
    *out = (int)v;
    return 1;
}

static int parse_args(int argc, char **argv, options *o)
{
    int i;
    memset(o, 0, sizeof *o);
    o->shape = SNELL_SHAPE_SPHERE;
    o->out = "snell.png";
    o->ior = 1.5f;
    o->width = o->height = 512;
    o->az_deg = 30.0f;
    o->el_deg = 20.0f;
    o->dist = 3.5f;
    o->fov_deg = 45.0f;
    o->method = SNELL_METHOD_AUTO;
    o->frames = 1;
    o->normalize = 1;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            exit(0);
        } else if (!strcmp(a, "--no-normalize")) {
            o->normalize = 0;
            takes = 0;
        } else if (!strcmp(a, "--stats")) {
            o->stats = 1;
            takes = 0;
        } else if (!v) {
            fprintf(stderr, "snell-render: %s needs a value (or is unknown); see --help\n", a);
            return 0;
        } else if (!strcmp(a, "--mesh")) {
            if (!strncmp(v, "shape:", 6)) {
                const char *names[] = {"sphere", "cube", "torus", "goblet"};
                int k, found = 0;
                for (k = 0; k < 4; k++)
                    if (!strcmp(v + 6, names[k])) { o->shape = (snell_shape)k; found = 1; }
                if (!found) { fprintf(stderr, "snell-render: unknown shape '%s'\n", v + 6); return 0; }
            } else {
                o->mesh = v;
            }
        } else if (!strcmp(a, "--env")) {
            o->env = strcmp(v, "procedural") ? v : NULL;
        } else if (!strcmp(a, "--ior")) {
            if (!parse_floats(v, &o->ior, 1) || o->ior < 0.05f || o->ior > 100.0f) {
                fprintf(stderr, "snell-render: --ior wants a number in 0.05..100, got '%s'\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--absorption")) {
            if (!parse_floats(v, o->absorption, 3)) { fprintf(stderr, "snell-render: --absorption wants R,G,B\n"); return 0; }
        } else if (!strcmp(a, "--size")) {
            if (sscanf(v, "%dx%d", &o->width, &o->height) != 2 || o->width < 1 || o->height < 1 ||
                o->width > 16384 || o->height > 16384) {
                fprintf(stderr, "snell-render: --size wants WxH within 1..16384, got '%s'\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--camera")) {
            float c[3];
            if (!parse_floats(v, c, 3) || !(c[2] > 0.0f)) {
                fprintf(stderr, "snell-render: --camera wants AZ,EL,DIST with DIST > 0, got '%s'\n", v);
                return 0;
            }
            o->az_deg = c[0]; o->el_deg = c[1]; o->dist = c[2];
        } else if (!strcmp(a, "--fov")) {
            if (!parse_floats(v, &o->fov_deg, 1) || !(o->fov_deg > 1.0f && o->fov_deg < 179.0f)) {
                fprintf(stderr, "snell-render: --fov wants degrees in 1..179\n");
                return 0;
            }
        } else if (!strcmp(a, "--method")) {
            if (!strcmp(v, "single")) o->method = SNELL_METHOD_SINGLE;
            else if (!strcmp(v, "cubemap")) o->method = SNELL_METHOD_CUBEMAP;
            else if (!strcmp(v, "auto")) o->method = SNELL_METHOD_AUTO;
            else { fprintf(stderr, "snell-render: unknown method '%s' (single, cubemap, auto)\n", v); return 0; }
        } else if (!strcmp(a, "--iterations")) {
            if (!parse_int(v, &o->iterations) || o->iterations < 1 || o->iterations > SNELL_CUBEMAP_MAX_ITERATIONS) {
                fprintf(stderr, "snell-render: --iterations wants 1..%d, got '%s'\n", SNELL_CUBEMAP_MAX_ITERATIONS, v);
                return 0;
            }
        } else if (!strcmp(a, "--linear-steps")) {
            if (!parse_int(v, &o->linear_steps) || o->linear_steps < 0 ||
                o->linear_steps > SNELL_CUBEMAP_MAX_LINEAR_STEPS) {
                fprintf(stderr, "snell-render: --linear-steps wants 0..%d, got '%s'\n", SNELL_CUBEMAP_MAX_LINEAR_STEPS, v);
                return 0;
            }
        } else if (!strcmp(a, "--interfaces")) {
            if (!parse_int(v, &o->interfaces) || o->interfaces < 1 || o->interfaces > SNELL_CUBEMAP_MAX_INTERFACES) {
                fprintf(stderr, "snell-render: --interfaces wants 1..%d, got '%s'\n", SNELL_CUBEMAP_MAX_INTERFACES, v);
                return 0;
            }
        } else if (!strcmp(a, "--face-size")) {
            if (!parse_int(v, &o->face_size) || o->face_size < 16 || o->face_size > 2048) {
                fprintf(stderr, "snell-render: --face-size wants 16..2048, got '%s'\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--opaque")) {
            if (!parse_int(v, &o->opaque) || o->opaque < 0 || o->opaque > SNELL_MAX_OPAQUE) {
                fprintf(stderr, "snell-render: --opaque wants 0..%d, got '%s'\n", SNELL_MAX_OPAQUE, v);
                return 0;
            }
        } else if (!strcmp(a, "--encoding")) {
            if (!strcmp(v, "plain")) o->encoding = SNELL_NDCUBE_PLAIN;
            else if (!strcmp(v, "oct")) o->encoding = SNELL_NDCUBE_OCT;
            else { fprintf(stderr, "snell-render: unknown encoding '%s' (plain, oct)\n", v); return 0; }
        } else if (!strcmp(a, "--backend")) {
            if (!strcmp(v, "surfaceless")) o->backend = SNELL_BACKEND_SURFACELESS;
            else if (!strcmp(v, "pbuffer")) o->backend = SNELL_BACKEND_PBUFFER;
            else { fprintf(stderr, "snell-render: unknown backend '%s'\n", v); return 0; }
        } else if (!strcmp(a, "--frames")) {
            if (!parse_int(v, &o->frames) || o->frames < 1 || o->frames > 100000) {
                fprintf(stderr, "snell-render: --frames wants 1..100000\n");
                return 0;
            }
        } else if (!strcmp(a, "--trace-pixel")) {
            float xy[2];
            if (o->trace_count == 16 || !parse_floats(v, xy, 2) || xy[0] != floorf(xy[0]) || xy[1] != floorf(xy[1])) {
                fprintf(stderr, "snell-render: --trace-pixel wants X,Y (integers, at most 16 pixels)\n");
                return 0;
            }
            o->trace_xy[2 * o->trace_count] = (int)xy[0];
            o->trace_xy[2 * o->trace_count++ + 1] = (int)xy[1];
        } else if (!strcmp(a, "-o")) {
            o->out = v;
        } else {
            fprintf(stderr, "snell-render: unknown option '%s'; see --help\n", a);
            return 0;
        }
        i += takes;
    }
    return 1;
}

static void log_cb(snell_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level >= SNELL_LOG_WARN) fprintf(stderr, "snell: %s\n", msg);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static snell_status make_env(snell_ctx *ctx, const char *spec, snell_env **env)
{
    snell_env_desc d;
    char faces[6][1024];
    const char *names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    int k;
    memset(&d, 0, sizeof d);
    if (!spec) return snell_env_create(ctx, &d, env);
    if (strstr(spec, "%s")) {
        d.source = SNELL_ENV_FACES;
        for (k = 0; k < 6; k++) {
            snprintf(faces[k], sizeof faces[k], spec, names[k]);
            d.face_paths[k] = faces[k];
        }
    } else {
        d.source = SNELL_ENV_EQUIRECT;
        d.equirect_path = spec;
    }
    return snell_env_create(ctx, &d, env);
}

/* render2d.c */
int snell_render2d_main(int argc, char **argv);
/* trace_pixel.c */
int snell_render_trace_pixels(snell_ctx *ctx, const snell_frame_desc *frame, int width, int height, const int *xy,
                              int count, const char *out_png);

int main(int argc, char **argv)
{
    options o;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_mesh *mesh = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    snell_frame_desc fd;
    snell_frame_stats fs;
    snell_mesh *cube = NULL;
    snell_opaque ob[SNELL_MAX_OPAQUE];
    float obm[SNELL_MAX_OPAQUE][16];
    uint8_t *pixels = NULL;
    double *times = NULL;
    snell_status st;
    int i, rc = 1;

    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--2d")) {
            return snell_render2d_main(argc, argv);
        }
    if (!parse_args(argc, argv, &o)) return 2;

    memset(&cd, 0, sizeof cd);
    cd.backend = o.backend;
    cd.log = log_cb;
    if ((st = snell_ctx_create(&cd, &ctx)) != SNELL_OK) {
        fprintf(stderr, "snell-render: cannot create a GL context: %s\n", snell_last_error(NULL));
        return 1;
    }
    if (o.mesh) {
        st = snell_mesh_load(ctx, o.mesh, &mesh);
    } else {
        snell_shape_desc sd;
        memset(&sd, 0, sizeof sd);
        sd.shape = o.shape;
        st = snell_mesh_create_shape(ctx, &sd, &mesh);
    }
    if (st != SNELL_OK) {
        fprintf(stderr, "snell-render: mesh: %s\n", snell_last_error(ctx));
        goto done;
    }
    if (o.normalize && (st = snell_mesh_normalize(mesh, 1.0f)) != SNELL_OK) {
        fprintf(stderr, "snell-render: mesh: %s\n", snell_last_error(ctx));
        goto done;
    }
    if ((st = make_env(ctx, o.env, &env)) != SNELL_OK) {
        fprintf(stderr, "snell-render: environment: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&rd, 0, sizeof rd);
    rd.width = o.width;
    rd.height = o.height;
    if ((st = snell_renderer_create(ctx, &rd, &r)) != SNELL_OK) {
        fprintf(stderr, "snell-render: renderer: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&fd, 0, sizeof fd);
    fd.mesh = mesh;
    fd.env = env;
    fd.glass.method = o.method;
    fd.glass.ior = o.ior;
    memcpy(fd.glass.absorption, o.absorption, sizeof o.absorption);
    fd.glass.search_iterations = o.iterations;
    fd.glass.linear_steps = o.linear_steps;
    fd.glass.max_interfaces = o.interfaces;
    fd.glass.cube_face_size = o.face_size;
    fd.glass.encoding = o.encoding;
    fd.camera.azimuth = (float)(o.az_deg * PI / 180.0);
    fd.camera.elevation = (float)(o.el_deg * PI / 180.0);
    fd.camera.distance = o.dist;
    fd.camera.fov_y = (float)(o.fov_deg * PI / 180.0);

    times = (double *)calloc((size_t)o.frames, sizeof *times);
    pixels = (uint8_t *)malloc((size_t)o.width * (size_t)o.height * 4);
    if (!times || !pixels) {
        fprintf(stderr, "snell-render: out of memory for a %dx%d image\n", o.width, o.height);
        goto done;
    }
    if (o.opaque > 0) {
        snell_shape_desc cs;
        memset(&cs, 0, sizeof cs);
        cs.shape = SNELL_SHAPE_CUBE;
        if ((st = snell_mesh_create_shape(ctx, &cs, &cube)) != SNELL_OK) {
            fprintf(stderr, "snell-render: opaque cube: %s\n", snell_last_error(ctx));
            goto done;
        }
        memset(ob, 0, sizeof ob);
        for (i = 0; i < o.opaque; i++) {
            ob[i].mesh = cube;
            ob[i].model = obm[i];
            ob[i].color[0] = (float)(0.5 + 0.5 * cos(2.1 * i));
            ob[i].color[1] = (float)(0.5 + 0.5 * cos(2.1 * i + 2.1));
            ob[i].color[2] = (float)(0.5 + 0.5 * cos(2.1 * i + 4.2));
        }
        fd.opaque = ob;
        fd.opaque_count = o.opaque;
    }
    /* Frame 0 warms up (uploads, shader JIT); with --frames N the median of the
     * following frames is reported, each ended by glFinish. */
    for (i = 0; i <= (o.frames > 1 ? o.frames : 0); i++) {
        double t0 = now_ms();
        int k;
        for (k = 0; k < o.opaque; k++) {
            /* cubes of size 0.4 on a circle of radius 2.2 around the glass, turning */
            double ang = 2.0 * PI * k / o.opaque + 0.15 * i;
            memset(obm[k], 0, sizeof obm[k]);
            obm[k][0] = obm[k][5] = obm[k][10] = 0.2f;
            obm[k][12] = (float)(2.2 * cos(ang));
            obm[k][13] = (float)(0.3 * sin(3.0 * ang));
            obm[k][14] = (float)(2.2 * sin(ang));
            obm[k][15] = 1.0f;
        }
        if ((st = snell_render(r, &fd, &fs)) != SNELL_OK) {
            fprintf(stderr, "snell-render: render: %s\n", snell_last_error(ctx));
            goto done;
        }
        snell_renderer_finish(r);
        if (i > 0) times[i - 1] = now_ms() - t0;
    }
    if (o.frames > 1) {
        qsort(times, (size_t)o.frames, sizeof *times, cmp_double);
        printf("%dx%d: median %.3f ms/frame over %d frames (min %.3f, max %.3f) on %s\n", o.width, o.height,
               times[o.frames / 2], o.frames, times[0], times[o.frames - 1], snell_ctx_gl_renderer(ctx));
    }
    if (o.stats) {
        static const char *mnames[] = {"auto", "single", "cubemap"};
        printf("stats: method %s, passes %d, ndcube_baked %d, env_updated %d, env_skipped %d, hidden_fraction %.4f, "
               "cpu %.3f ms\n",
               (unsigned)fs.method_used < sizeof mnames / sizeof *mnames ? mnames[fs.method_used] : "?", fs.passes,
               fs.ndcube_baked, fs.env_updated, fs.env_skipped, fs.hidden_fraction, fs.cpu_ms);
    }
    if ((st = snell_renderer_read_rgba(r, pixels)) != SNELL_OK) {
        fprintf(stderr, "snell-render: readback: %s\n", snell_last_error(ctx));
        goto done;
    }
    if ((st = snell_write_png(o.out, o.width, o.height, pixels)) != SNELL_OK) {
        fprintf(stderr, "snell-render: %s\n", snell_last_error(NULL));
        goto done;
    }
    printf("wrote %s (%dx%d)\n", o.out, o.width, o.height);
    if (o.trace_count &&
        (rc = snell_render_trace_pixels(ctx, &fd, o.width, o.height, o.trace_xy, o.trace_count, o.out)) != 0)
        goto done;
    rc = 0;
done:
    free(times);
    free(pixels);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_mesh_destroy(mesh);
    snell_mesh_destroy(cube);
    snell_ctx_destroy(ctx);
    return rc;
}
