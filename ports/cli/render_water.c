/* SPDX-License-Identifier: MIT */
/* render_water.c — snell-render --water: the container scene of issue 17
 * (Dachsbacher 2002): a water surface in a tiled box, drops at the points
 * the flags give, simulated and rendered frame by frame; with --save-every K
 * every K-th frame goes to <out>_NNNN.png so the animation can be seen.
 * main reads as the pipeline: options -> context -> water -> environment ->
 * renderer -> frames (step, render, save) -> statistics. Exit 0, 1 on a
 * runtime failure, 2 on bad usage. */
#include "render.h"
#include "cli_opts.h"
#include "cli_scene.h"
#include "snell/snell_water.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define MAX_DROPS 32

typedef struct water_drop_opt {
    float x, z, radius, amplitude;
    int frame;                     /* dropped before this frame's step */
} water_drop_opt;

#define MAX_OBJECTS 8

typedef struct water_object_opt {
    char mesh[256];                /* shape name or OBJ/glTF file */
    float place[4];                /* x, y, z, scale of the unit-sphere-normalised mesh */
    int glass;                     /* --glass: a glass object, else opaque */
} water_object_opt;

typedef struct water_options {
    snell_water_desc desc;
    water_object_opt objects[MAX_OBJECTS];
    int object_count;
    water_drop_opt drops[MAX_DROPS];
    int drop_count;
    int frames, save_every, steps;
    float dt;
    int width, height, ssaa;
    float az_deg, el_deg, dist;
    const char *out, *env;
    int stats;
    snell_light light;             /* --light: the floor's caustics (zero = none) */
} water_options;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: snell-render --water [options]\n"
            "  a water surface in a tiled box container (snell_water.h), seen by an orbit camera\n"
            "  --grid N               simulation nodes per side, 64..512 (default 128)\n"
            "  --sim cpu|gpu          where the simulation runs (default: the library's AUTO, cpu on software GL)\n"
            "  --drop X,Z[,R[,A[,F]]] a drop at world (X, Z), radius R (default 0.08), amplitude A\n"
            "                         (default -0.03; > 0 lifts), before frame F (default 0); repeatable\n"
            "  --object MESH:X,Y,Z,S  an opaque object (shape or file, fitted in the unit sphere) at (X, Y, Z)\n"
            "                         scaled by S, standing in the water; repeatable (up to 8 objects)\n"
            "  --glass MESH:X,Y,Z,S   a glass object (IOR 1.5, method AUTO), placed as --object; repeatable\n"
            "  --frames N             frames to simulate and render (default 1)\n"
            "  --steps S              simulation steps per frame (default 2)\n"
            "  --dt SECONDS           step (default 1/120; clamped to the stability limit)\n"
            "  --save-every K         write every K-th frame to OUT_NNNN.png (default: the last frame to OUT)\n"
            "  --damping D            velocity decay per second (default 0.4; < 0 none)\n"
            "  --wave-speed C         world units per second (default 0.6)\n"
            "  --size WxH             image size (default 512x512)\n"
            "  --ssaa S               supersample S x S per pixel (2..8; default off)\n"
            "  --camera AZ,EL,DIST    degrees, degrees, distance (default 30,35,3.6)\n"
            "  --env procedural|FILE  environment (default procedural)\n"
            "  --light dir:X,Y,Z[,I]  a directional light travelling along X,Y,Z of irradiance I (default 1): the\n"
            "                         floor lit by it through the moving surface (its caustics; tiles times irradiance)\n"
            "  --light spot:PX,PY,PZ,X,Y,Z,A[,I]  a spot light at P shining along X,Y,Z within A radians, intensity I\n"
            "  --light-map N          the floor's light map, N x N texels (16..2048, default 256)\n"
            "  -o FILE                output PNG (default water.png)\n"
            "  --stats                per-frame simulation statistics on stdout\n");
}

/* --light dir:X,Y,Z[,I] or spot:PX,PY,PZ,X,Y,Z,ANGLE[,I], as snell-render's. */
static int parse_light(const char *v, snell_light *l)
{
    float f[8] = {0, 0, 0, 1, 0, 0, 0, 1};
    char extra;
    int spot = !strncmp(v, "spot:", 5), n;
    memset(l, 0, sizeof *l);
    if (spot) {
        n = sscanf(v + 5, "%f,%f,%f,%f,%f,%f,%f,%f%c", &f[0], &f[1], &f[2], &f[3], &f[4], &f[5], &f[6], &f[7], &extra);
        if ((n != 7 && n != 8) || !(f[6] > 0.0f && f[6] <= 1.5f) || f[3] * f[3] + f[4] * f[4] + f[5] * f[5] == 0.0f ||
            !(f[7] >= 0.0f))
            return 0;
        l->type = SNELL_LIGHT_SPOT;
        memcpy(l->position, f, sizeof l->position);
        memcpy(l->direction, f + 3, sizeof l->direction);
        l->spot_angle = f[6];
        l->color[0] = l->color[1] = l->color[2] = f[7];
        return 1;
    }
    if (strncmp(v, "dir:", 4)) return 0;
    n = sscanf(v + 4, "%f,%f,%f,%f%c", &f[0], &f[1], &f[2], &f[3], &extra);
    if ((n != 3 && n != 4) || f[0] * f[0] + f[1] * f[1] + f[2] * f[2] == 0.0f || !(f[3] >= 0.0f)) return 0;
    l->type = SNELL_LIGHT_DIRECTIONAL;
    memcpy(l->direction, f, sizeof l->direction);
    l->color[0] = l->color[1] = l->color[2] = f[3];
    return 1;
}

static int parse(int argc, char **argv, water_options *o)
{
    static const struct option longopts[] = {
        {"grid", required_argument, NULL, 256},      {"sim", required_argument, NULL, 257},
        {"drop", required_argument, NULL, 258},      {"object", required_argument, NULL, 259},
        {"glass", required_argument, NULL, 260},     {"frames", required_argument, NULL, 261},
        {"steps", required_argument, NULL, 262},     {"dt", required_argument, NULL, 263},
        {"save-every", required_argument, NULL, 264}, {"damping", required_argument, NULL, 265},
        {"wave-speed", required_argument, NULL, 266}, {"size", required_argument, NULL, 267},
        {"ssaa", required_argument, NULL, 268},      {"camera", required_argument, NULL, 269},
        {"env", required_argument, NULL, 270},       {"light", required_argument, NULL, 271},
        {"light-map", required_argument, NULL, 272}, {"water", no_argument, NULL, 273},
        {"stats", no_argument, NULL, 274},           {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    int i, c;
    memset(o, 0, sizeof *o);
    o->frames = 1;
    o->steps = 2;
    o->dt = 1.0f / 120.0f;
    o->width = o->height = 512;
    o->az_deg = 30.0f;
    o->el_deg = 35.0f;
    o->dist = 3.6f;
    o->out = "water.png";
    if (cli_wants_help(argc, argv)) { /* --help wherever it is */
        usage(stdout);
        return -1;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-render --water", "--water --help", argc, argv, "o:h", longopts)) != -1) {
        char name[32];
        const char *a = name, *v = optarg;
        if (c == '?') return 0;
        if (c >= 256) snprintf(name, sizeof name, "--%s", longopts[c - 256].name);
        else snprintf(name, sizeof name, "-%c", c);
        if (!strcmp(a, "--water")) {
            continue;
        } else if (!strcmp(a, "--stats")) {
            o->stats = 1;
        } else if (!strcmp(a, "--grid")) {
            o->desc.grid = atoi(v);
        } else if (!strcmp(a, "--sim")) {
            if (!strcmp(v, "cpu")) o->desc.sim = SNELL_WATER_SIM_CPU;
            else if (!strcmp(v, "gpu")) o->desc.sim = SNELL_WATER_SIM_GPU;
            else {
                fprintf(stderr, "snell-render --water: --sim %s: cpu or gpu\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--drop")) {
            water_drop_opt *d = &o->drops[o->drop_count];
            float f = 0.0f;
            int n;
            if (o->drop_count == MAX_DROPS) {
                fprintf(stderr, "snell-render --water: at most %d drops\n", MAX_DROPS);
                return 0;
            }
            d->radius = 0.08f;
            d->amplitude = -0.03f;
            n = sscanf(v, "%f,%f,%f,%f,%f", &d->x, &d->z, &d->radius, &d->amplitude, &f);
            if (n < 2) {
                fprintf(stderr, "snell-render --water: --drop %s: X,Z[,R[,A[,F]]]\n", v);
                return 0;
            }
            /* F becomes an int: a value that is no whole frame number (1e30, NaN) has no defined conversion */
            if (!(f >= 0.0f && f < 100000.0f) || f != floorf(f)) {
                fprintf(stderr, "snell-render --water: --drop %s: frame F must be a whole number 0..99999\n", v);
                return 0;
            }
            d->frame = (int)f;
            o->drop_count++;
        } else if (!strcmp(a, "--object") || !strcmp(a, "--glass")) {
            water_object_opt *ob = &o->objects[o->object_count];
            const char *colon = strrchr(v, ':');
            if (o->object_count == MAX_OBJECTS || !colon || colon == v || (size_t)(colon - v) >= sizeof ob->mesh ||
                sscanf(colon + 1, "%f,%f,%f,%f", &ob->place[0], &ob->place[1], &ob->place[2], &ob->place[3]) != 4) {
                fprintf(stderr, "snell-render --water: %s %s: MESH:X,Y,Z,S (at most %d objects)\n", a, v, MAX_OBJECTS);
                return 0;
            }
            memcpy(ob->mesh, v, (size_t)(colon - v));
            ob->mesh[colon - v] = '\0';
            ob->glass = a[2] == 'g';
            o->object_count++;
        } else if (!strcmp(a, "--frames")) {
            o->frames = atoi(v);
        } else if (!strcmp(a, "--steps")) {
            o->steps = atoi(v);
        } else if (!strcmp(a, "--dt")) {
            o->dt = (float)atof(v);
        } else if (!strcmp(a, "--save-every")) {
            o->save_every = atoi(v);
        } else if (!strcmp(a, "--damping")) {
            o->desc.damping = (float)atof(v);
        } else if (!strcmp(a, "--wave-speed")) {
            o->desc.wave_speed = (float)atof(v);
        } else if (!strcmp(a, "--size")) {
            if (sscanf(v, "%dx%d", &o->width, &o->height) != 2) {
                fprintf(stderr, "snell-render --water: --size %s: WxH\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--ssaa")) {
            o->ssaa = atoi(v);
        } else if (!strcmp(a, "--camera")) {
            if (sscanf(v, "%f,%f,%f", &o->az_deg, &o->el_deg, &o->dist) != 3) {
                fprintf(stderr, "snell-render --water: --camera %s: AZ,EL,DIST\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--env")) {
            o->env = v;
        } else if (!strcmp(a, "--light")) {
            if (!parse_light(v, &o->light)) {
                fprintf(stderr, "snell-render --water: --light %s: dir:X,Y,Z[,I] or spot:PX,PY,PZ,X,Y,Z,ANGLE[,I] "
                        "(direction not zero, ANGLE 0..1.5 radians, I >= 0)\n", v);
                return 0;
            }
        } else if (!strcmp(a, "--light-map")) {
            o->desc.light_map = atoi(v);
        } else if (!strcmp(a, "-o")) {
            o->out = v;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "snell-render --water: unexpected argument '%s'; see --water --help\n", argv[optind]);
        return 0;
    }
    if (o->frames < 1 || o->frames > 100000 || o->steps < 0 || o->save_every < 0 || o->width < 1 || o->height < 1) {
        fprintf(stderr, "snell-render --water: --frames 1..100000, --steps >= 0, --save-every >= 0, --size > 0\n");
        return 0;
    }
    for (i = 0; i < o->drop_count; i++)
        if (o->drops[i].frame >= o->frames) {
            fprintf(stderr, "snell-render --water: --drop %d: before frame %d, but only %d frame(s) are made (--frames)\n",
                    i + 1, o->drops[i].frame, o->frames);
            return 0;
        }
    return 1;
}

static int save(snell_ctx *ctx, snell_renderer *r, const water_options *o, uint8_t *px, const char *path)
{
    if (snell_renderer_read_rgba(r, px) != SNELL_OK) {
        fprintf(stderr, "snell-render --water: %s: %s\n", path, snell_last_error(ctx));
        return 0;
    }
    if (snell_write_png(path, o->width, o->height, px) != SNELL_OK) { /* no context: the thread's message */
        fprintf(stderr, "snell-render --water: %s\n", snell_last_error(NULL));
        return 0;
    }
    return 1;
}

/* OUT without ".png" + _NNNN.png */
static void frame_path(const char *out, int frame, char *buf, size_t n)
{
    size_t len = strlen(out);
    if (len > 4 && !strcmp(out + len - 4, ".png")) len -= 4;
    snprintf(buf, n, "%.*s_%04d.png", (int)len, out, frame);
}

static int run(snell_ctx *ctx, const water_options *o)
{
    snell_water *w = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_frame_desc fd;
    snell_mesh *meshes[MAX_OBJECTS] = {0};
    snell_opaque opaque[MAX_OBJECTS];
    snell_glass glass[MAX_OBJECTS];
    int n_opaque = 0, n_glass = 0;
    float models[MAX_OBJECTS][16];
    uint8_t *px = NULL;
    int f, k, rc = 1;
    if (snell_water_create(ctx, &o->desc, &w) != SNELL_OK) {
        fprintf(stderr, "snell-render --water: %s\n", snell_last_error(ctx));
        return 2;
    }
    if (cli_env_open(ctx, o->env, &env) != SNELL_OK) {
        fprintf(stderr, "snell-render --water: environment: %s\n", snell_last_error(ctx));
        goto done;
    }
    if (snell_renderer_create(ctx, &(snell_renderer_desc){.width = o->width, .height = o->height, .ssaa = o->ssaa}, &r) !=
        SNELL_OK) {
        fprintf(stderr, "snell-render --water: renderer: %s\n", snell_last_error(ctx));
        goto done;
    }
    px = (uint8_t *)malloc((size_t)o->width * (size_t)o->height * 4);
    if (!px) goto done;
    memset(opaque, 0, sizeof opaque);
    for (k = 0; k < o->object_count; k++) {
        if (cli_mesh_open(ctx, o->objects[k].mesh, 1, &meshes[k]) != SNELL_OK) {
            fprintf(stderr, "snell-render --water: --object %s: %s\n", o->objects[k].mesh, snell_last_error(ctx));
            rc = 2;
            goto done;
        }
        cli_place_matrix(o->objects[k].place, models[k]);
        if (o->objects[k].glass) {
            snell_glass *g = &glass[n_glass++];
            memset(g, 0, sizeof *g);
            g->mesh = meshes[k];
            g->model = models[k];
            g->material.ior = 1.5f;
        } else {
            snell_opaque *op = &opaque[n_opaque++];
            op->mesh = meshes[k];
            op->model = models[k];
            op->color[0] = (float)(0.55 + 0.4 * cos(2.1 * k));
            op->color[1] = (float)(0.55 + 0.4 * cos(2.1 * k + 2.1));
            op->color[2] = (float)(0.55 + 0.4 * cos(2.1 * k + 4.2));
        }
    }
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.water = w;
    fd.opaque = n_opaque ? opaque : NULL;
    fd.opaque_count = n_opaque;
    fd.glass = n_glass ? glass : NULL;
    fd.glass_count = n_glass;
    fd.camera.azimuth = (float)(o->az_deg * PI / 180.0);
    fd.camera.elevation = (float)(o->el_deg * PI / 180.0);
    fd.camera.distance = o->dist;
    fd.camera.target[1] = -0.2f;
    fd.light = o->light;
    for (f = 0; f < o->frames; f++) {
        snell_water_stats ws;
        snell_frame_stats fs;
        for (k = 0; k < o->drop_count; k++)
            if (o->drops[k].frame == f &&
                snell_water_drop(w, o->drops[k].x, o->drops[k].z, o->drops[k].radius, o->drops[k].amplitude) != SNELL_OK) {
                fprintf(stderr, "snell-render --water: --drop %d: %s\n", k + 1, snell_last_error(ctx));
                rc = 2;
                goto done;
            }
        if (snell_water_step(w, o->dt, o->steps, &ws) != SNELL_OK || snell_render(r, &fd, &fs) != SNELL_OK) {
            fprintf(stderr, "snell-render --water: frame %d: %s\n", f, snell_last_error(ctx));
            goto done;
        }
        if (o->stats)
            printf("frame %d: %s, %d steps of %.5f s%s, max |h - mean| %.3g, %s, heights %s%s; caustics: %s\n", f,
                   ws.skipped_settled ? "simulation skipped (settled, undisturbed)" : "simulated", ws.steps_run,
                   (double)ws.dt, ws.dt_clamped ? " (clamped to the stability limit)" : "", (double)ws.max_deviation,
                   ws.settled ? "settled" : "moving", fs.water_uploaded ? "uploaded" : "not uploaded",
                   fs.water_objects ? (fs.water_layers ? ", objects seen under the surface through the scene layers"
                                                       : ", objects searched under the surface")
                                    : "",
                   fs.caustics_reason);
        if (o->save_every > 0 && (f % o->save_every == 0 || f == o->frames - 1)) {
            char path[1024];
            frame_path(o->out, f, path, sizeof path);
            if (!save(ctx, r, o, px, path)) goto done;
        }
    }
    if (o->save_every == 0 && !save(ctx, r, o, px, o->out)) goto done;
    rc = 0;
done:
    free(px);
    for (k = 0; k < MAX_OBJECTS; k++) snell_mesh_destroy(meshes[k]);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    snell_water_destroy(w);
    return rc;
}

int snell_render_water_main(int argc, char **argv)
{
    water_options o;
    snell_ctx *ctx = NULL;
    int rc = parse(argc, argv, &o);
    if (rc <= 0) return rc < 0 ? 0 : 2;
    if (snell_ctx_create(NULL, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-render --water: cannot create a GL context: %s\n", snell_last_error(NULL));
        return 1;
    }
    rc = run(ctx, &o);
    snell_ctx_destroy(ctx);
    return rc;
}
