/* SPDX-License-Identifier: MIT */
/* snell-render — renders one frame of a scene of glass and opaque objects to PNG.
 * With no arguments: one glass sphere in the procedural environment, written
 * to snell.png. main reads as the pipeline: options -> context -> scene ->
 * environment -> renderer -> frames -> statistics -> PNG -> traced pixels.
 * Exit status 0 on success, 1 on a runtime failure, 2 on bad usage. */
#include "render.h"
#include "cli_input.h"
#include "cli_scene.h"
#include "cli_time.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* The scene handed to snell_render: meshes loaded once per distinct name. */
typedef struct render_scene {
    snell_mesh *meshes[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE + 1];
    const char *mesh_names[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE + 1];
    int mesh_normalized[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE + 1];
    int mesh_count;
    snell_glass glass[SNELL_MAX_GLASS];
    const char *glass_names[SNELL_MAX_GLASS];
    float glass_models[SNELL_MAX_GLASS][16];
    int glass_count;
    snell_opaque opaque[SNELL_MAX_OPAQUE];
    float opaque_models[SNELL_MAX_OPAQUE][16];
    int opaque_count;
    int orbit_first, orbit;         /* opaque[orbit_first ..] are the --opaque N cubes */
    snell_scene_file *file;         /* --scene: owns the meshes and matrices the lists point to */
    char camera_note[200];          /* --scene: where the camera came from (--stats) */
} render_scene;

static int g_verbose;

static void log_cb(snell_log_level level, const char *msg, void *user)
{
    (void)user;
    /* Errors come back as a status whose message (snell_last_error) main
     * prints once where the call failed; -v shows the library's whole log. */
    if (level == SNELL_LOG_WARN || (g_verbose && level >= SNELL_LOG_INFO)) fprintf(stderr, "snell: %s\n", msg);
}

/* The mesh called name (a shape or a file), loaded on first use. */
static snell_status scene_mesh(snell_ctx *ctx, render_scene *s, const char *name, int normalize, snell_mesh **out)
{
    snell_status st;
    snell_shape a, b;
    int i;
    for (i = 0; i < s->mesh_count; i++)
        if (s->mesh_normalized[i] == normalize &&
            (!strcmp(s->mesh_names[i], name) ||
             (cli_shape_from_name(name, &a) && cli_shape_from_name(s->mesh_names[i], &b) && a == b))) {
            *out = s->meshes[i];
            return SNELL_OK;
        }
    if ((st = cli_mesh_open(ctx, name, normalize, out)) != SNELL_OK) {
        fprintf(stderr, "snell-render: mesh: %s\n", snell_last_error(ctx));
        return st;
    }
    s->mesh_names[s->mesh_count] = name;
    s->mesh_normalized[s->mesh_count] = normalize;
    s->meshes[s->mesh_count++] = *out;
    return SNELL_OK;
}

static snell_status build_scene(snell_ctx *ctx, const render_options *o, render_scene *s)
{
    const render_object *glass = o->glass_count ? o->glass : &o->base;
    snell_mesh *mesh;
    snell_status st;
    int i;
    memset(s, 0, sizeof *s);
    if (o->scene_file) {
        const snell_glass *g;
        const snell_opaque *p;
        if ((st = snell_scene_load_gltf(ctx, o->scene_file, 0, &s->file)) != SNELL_OK) {
            fprintf(stderr, "snell-render: scene: %s\n", snell_last_error(ctx));
            return st;
        }
        g = snell_scene_file_glass(s->file, &s->glass_count);
        p = snell_scene_file_opaque(s->file, &s->opaque_count);
        for (i = 0; i < s->glass_count; i++) {
            s->glass[i] = g[i];
            s->glass_names[i] = snell_scene_file_glass_name(s->file, i);
        }
        for (i = 0; i < s->opaque_count; i++) s->opaque[i] = p[i];
        s->orbit_first = s->opaque_count;
        return SNELL_OK;
    }
    s->glass_count = o->glass_count ? o->glass_count : 1;
    for (i = 0; i < s->glass_count; i++) {
        const render_object *g = &glass[i];
        if ((st = scene_mesh(ctx, s, g->mesh, o->normalize, &mesh)) != SNELL_OK) return st;
        s->glass[i].mesh = mesh;
        s->glass[i].material = g->material;
        s->glass_names[i] = cli_is_shape_spec(g->mesh) ? g->mesh + 6 : g->mesh;
        if (g->placed) {
            cli_place_matrix(g->place, s->glass_models[i]);
            s->glass[i].model = s->glass_models[i];
        }
    }
    for (i = 0; i < o->opaque_count; i++) {
        const render_object *p = &o->opaque[i];
        if ((st = scene_mesh(ctx, s, p->mesh, o->normalize, &mesh)) != SNELL_OK) return st;
        s->opaque[i].mesh = mesh;
        memcpy(s->opaque[i].color, p->color, sizeof p->color);
        if (p->placed) {
            cli_place_matrix(p->place, s->opaque_models[i]);
            s->opaque[i].model = s->opaque_models[i];
        }
    }
    s->orbit_first = o->opaque_count;
    s->orbit = o->orbit;
    if (o->orbit > 0 && (st = scene_mesh(ctx, s, "cube", 0, &mesh)) != SNELL_OK) return st;
    for (i = 0; i < o->orbit; i++) {
        snell_opaque *c = &s->opaque[s->orbit_first + i];
        c->mesh = mesh;
        c->model = s->opaque_models[s->orbit_first + i];
        c->color[0] = (float)(0.5 + 0.5 * cos(2.1 * i));
        c->color[1] = (float)(0.5 + 0.5 * cos(2.1 * i + 2.1));
        c->color[2] = (float)(0.5 + 0.5 * cos(2.1 * i + 4.2));
    }
    s->opaque_count = o->opaque_count + o->orbit;
    return SNELL_OK;
}

/* The --opaque N demo: cubes of size 0.4 on a circle of radius 2.2 about the origin, turning with the frame. */
static void move_orbit(render_scene *s, int frame)
{
    int k;
    for (k = 0; k < s->orbit; k++) {
        float *m = s->opaque_models[s->orbit_first + k];
        double ang = 2.0 * PI * k / s->orbit + 0.15 * frame;
        memset(m, 0, 16 * sizeof *m);
        m[0] = m[5] = m[10] = 0.2f;
        m[12] = (float)(2.2 * cos(ang));
        m[13] = (float)(0.3 * sin(3.0 * ang));
        m[14] = (float)(2.2 * sin(ang));
        m[15] = 1.0f;
    }
}

static void skipped_str(unsigned bits, char *buf, size_t n)
{
    static const char *const names[] = {"passthrough", "outside-view", "prepare", "env-update",
                                        "back-faces",  "analysis",     "search",    "back-detail", "dynamic-env"};
    size_t k, len = 0;
    buf[0] = '\0';
    for (k = 0; k < sizeof names / sizeof *names; k++)
        if ((bits & (1u << k)) && len < n)
            len += (size_t)snprintf(buf + len, n - len, "%s%s", len ? "+" : "", names[k]);
    if (!len) snprintf(buf, n, "none");
}

/* One line for the frame, one per glass object: its IOR (resolved), what drew it and why. */
static void print_stats(FILE *f, const snell_frame_stats *fs, const render_scene *s)
{
    int i;
    fprintf(f, "stats: frame passes %d, cpu %.3f ms, glass %d, opaque drawn %d, background %d, fragment %s, "
            "scene layers %d peeled %d used (%s)\n",
            fs->passes, fs->cpu_ms, fs->glass_count, fs->opaque_drawn, fs->background_drawn,
            fs->fragment_mediump ? "mediump" : "highp", fs->scene_layer_passes, fs->scene_layers,
            fs->scene_layers_reason);
    fprintf(f, "stats: stages run: %s\n", fs->stages);
    if (s->file) fprintf(f, "stats: camera: %s\n", s->camera_note);
    if (fs->caustics_reason[0]) fprintf(f, "stats: caustics: %s (%d photons)\n", fs->caustics_reason, fs->caustics_photons);
    if (fs->refine_reason[0]) fprintf(f, "stats: refine: %s\n", fs->refine_reason);
    if (fs->panels_drawn || fs->panels_reason[0])
        fprintf(f, "stats: panels: %d drawn, %d captures, dropped%s%s%s: %s\n", fs->panels_drawn, fs->panels_captures,
                fs->panels_dropped ? "" : " nothing", fs->panels_dropped & SNELL_PANELS_DROPPED_FROST ? " frost" : "",
                fs->panels_dropped & SNELL_PANELS_DROPPED_DISPERSION ? " dispersion" : "", fs->panels_reason);
    for (i = 0; i < fs->glass_count; i++) {
        const snell_object_stats *g = &fs->glass[i];
        snell_glass_resolved m;
        const snell_method_info *info = snell_method_info_of(g->method_used);
        char skipped[160], layers[160] = "";
        size_t len = 0;
        int k;
        skipped_str(g->skipped, skipped, sizeof skipped);
        /* The method's own counters, as its registry entry names them. */
        for (k = 0; info && k < info->counter_count && len < sizeof layers; k++) {
            if (g->counters[k] >= 0)
                len += (size_t)snprintf(layers + len, sizeof layers - len, ", %s %d", info->counters[k].name,
                                        g->counters[k]);
            else
                len += (size_t)snprintf(layers + len, sizeof layers - len, ", %s not counted", info->counters[k].name);
        }
        if (snell_glass_defaults(&s->glass[i].material, &m) != SNELL_OK) m.material.ior = NAN;
        fprintf(f,
                "stats: glass %d (%s, ior %g): method %s, warning %d, passes %d, prepared %d, env_updated %d, "
                "skipped %s, draw_order %d, view_depth %.3f, hidden_fraction %.4f, shading %s (%.1f px/triangle)%s, "
                "scale %g, env %s, reason: %s\n",
                i, s->glass_names[i], m.material.ior, snell_method_str(g->method_used), g->warning, g->passes,
                g->prepared, g->env_updated, skipped, g->draw_order, g->view_depth, g->hidden_fraction,
                g->screen_space ? "screen" : "forward", g->pixels_per_triangle, layers, g->scale,
                g->env_paraboloid ? "dual-paraboloid" : "cube", g->reason);
    }
}

/* Frame 0 warms up (uploads, shader JIT); with --frames N the median of the
 * following frames is reported, each ended by glFinish. */
static int render_frames(snell_ctx *ctx, snell_renderer *r, const render_options *o, render_scene *s,
                         const snell_frame_desc *fd, snell_frame_stats *fs)
{
    double *times = (double *)calloc((size_t)o->frames, sizeof *times);
    int i, last = o->frames > 1 ? o->frames : 0;
    if (!times) {
        fprintf(stderr, "snell-render: out of memory\n");
        return 0;
    }
    if (o->refine - 1 > last) last = o->refine - 1; /* --refine N: N frames at least */
    for (i = 0; i <= last; i++) {
        double t0 = cli_now_ms();
        move_orbit(s, i);
        if (snell_render(r, fd, fs) != SNELL_OK) {
            char where[300];
            fprintf(stderr, "snell-render: render: %s%s\n", snell_last_error(ctx),
                    cli_panels_where(&o->panels, o->panels_file ? o->panels_file : "", snell_last_error(ctx), where,
                                     sizeof where));
            free(times);
            return 0;
        }
        snell_renderer_finish(r);
        if (i > 0 && i <= o->frames) times[i - 1] = cli_now_ms() - t0;
    }
    if (o->frames > 1) {
        double med = cli_median(times, o->frames); /* sorts */
        printf("%dx%d: median %.3f ms/frame over %d frames (min %.3f, max %.3f) on %s\n", o->width, o->height, med,
               o->frames, times[0], times[o->frames - 1], snell_ctx_gl_renderer(ctx));
    }
    free(times);
    return 1;
}

static int write_image(snell_ctx *ctx, snell_renderer *r, const render_options *o)
{
    uint8_t *pixels = (uint8_t *)malloc((size_t)o->width * (size_t)o->height * 4);
    int ok = 0;
    if (!pixels) fprintf(stderr, "snell-render: out of memory for a %dx%d image\n", o->width, o->height);
    else if (snell_renderer_read_rgba(r, pixels) != SNELL_OK)
        fprintf(stderr, "snell-render: readback: %s\n", snell_last_error(ctx));
    else if (snell_write_png(o->out, o->width, o->height, pixels) != SNELL_OK)
        fprintf(stderr, "snell-render: %s\n", snell_last_error(NULL));
    else ok = 1;
    if (ok) printf("wrote %s (%dx%d)\n", o->out, o->width, o->height);
    free(pixels);
    return ok;
}

int main(int argc, char **argv)
{
    static render_options o;
    static render_scene scene;
    snell_ctx_desc cd;
    snell_ctx *ctx = NULL;
    snell_env *env = NULL;
    snell_renderer *r = NULL;
    snell_renderer_desc rd;
    render_panels panels;
    snell_frame_desc fd;
    snell_frame_stats fs;
    int i, rc = 1;

    if (!cli_args_clean("snell-render", argc, argv)) return 2;
    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--2d")) return snell_render2d_main(argc, argv);
        else if (!strcmp(argv[i], "--water")) return snell_render_water_main(argc, argv);
    if ((i = render_parse_args(argc, argv, &o)) <= 0) return i < 0 ? 0 : 2;
    g_verbose = o.verbose;

    memset(&cd, 0, sizeof cd);
    cd.backend = o.backend;
    cd.log = log_cb;
    if (snell_ctx_create(&cd, &ctx) != SNELL_OK) {
        fprintf(stderr, "snell-render: cannot create a GL context: %s\n", snell_last_error(NULL));
        return 1;
    }
    memset(&panels, 0, sizeof panels);
    if (!render_panels_open(ctx, &o, &panels)) goto done;
    /* --under: a frame of panels only, over the picture: no scene to build */
    if (!o.under_file && build_scene(ctx, &o, &scene) != SNELL_OK) goto done;
    if (!o.under_file && cli_env_open(ctx, o.env, &env) != SNELL_OK) {
        fprintf(stderr, "snell-render: environment: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&rd, 0, sizeof rd);
    rd.width = o.width;
    rd.height = o.height;
    rd.shading = o.shading;
    rd.env_lookup = o.env_lookup;
    rd.ssaa = o.ssaa;
    rd.msaa = o.msaa;
    rd.refine = o.refine;
    if (snell_renderer_create(ctx, &rd, &r) != SNELL_OK) {
        fprintf(stderr, "snell-render: renderer: %s\n", snell_last_error(ctx));
        goto done;
    }
    memset(&fd, 0, sizeof fd);
    fd.env = env;
    fd.glass = scene.glass;
    fd.glass_count = scene.glass_count;
    fd.opaque = scene.opaque_count ? scene.opaque : NULL;
    fd.opaque_count = scene.opaque_count;
    fd.scene_layers = o.scene_layers;
    fd.light = o.light;
    fd.receiver = o.receiver;
    fd.camera.azimuth = (float)(o.az_deg * PI / 180.0);
    fd.camera.elevation = (float)(o.el_deg * PI / 180.0);
    fd.camera.distance = o.dist;
    fd.camera.fov_y = (float)(o.fov_deg * PI / 180.0);
    /* A scene file's camera; without one, the scene framed from the
     * --camera direction and --fov (its target and distance replaced). */
    if (scene.file && o.camera_given) {
        snprintf(scene.camera_note, sizeof scene.camera_note, "--camera");
    } else if (scene.file && snell_scene_file_camera(scene.file, &fd.camera)) {
        if (o.fov_given) fd.camera.fov_y = (float)(o.fov_deg * PI / 180.0);
        snprintf(scene.camera_note, sizeof scene.camera_note, "the file's");
    } else if (scene.file) {
        if (snell_scene_file_frame(scene.file, (float)o.width / (float)o.height, &fd.camera) != SNELL_OK) {
            fprintf(stderr, "snell-render: scene: %s\n", snell_last_error(NULL));
            goto done;
        }
        snprintf(scene.camera_note, sizeof scene.camera_note,
                 "framed the scene's bounds (the file has none): target (%g, %g, %g), distance %g",
                 fd.camera.target[0], fd.camera.target[1], fd.camera.target[2], fd.camera.distance);
    }

    if (o.view_given) { /* the host's matrices replace every orbit value above */
        fd.camera.kind = SNELL_CAMERA_MATRICES;
        memcpy(fd.camera.view, o.view, sizeof fd.camera.view);
        memcpy(fd.camera.projection, o.projection, sizeof fd.camera.projection);
        if (scene.file) snprintf(scene.camera_note, sizeof scene.camera_note, "--view and --projection");
    }
    render_panels_frame(&o, &panels, &fd);
    if (!render_panels_plain(ctx, r, &o, &panels, &fd)) goto done;
    if (!render_frames(ctx, r, &o, &scene, &fd, &fs)) goto done;
    if (o.stats) print_stats(stdout, &fs, &scene);
    if (o.verbose) print_stats(stderr, &fs, &scene);
    if (!write_image(ctx, r, &o) || !render_panels_reference(&o, &panels)) goto done;
    if (o.trace_count &&
        (rc = snell_render_trace_pixels(ctx, &fd, o.width, o.height, o.trace_xy, o.trace_count, o.out)) != 0)
        goto done;
    rc = 0;
done:
    render_panels_close(&panels);
    cli_panels_free(&o.panels);
    snell_renderer_destroy(r);
    snell_env_destroy(env);
    for (i = 0; i < scene.mesh_count; i++) snell_mesh_destroy(scene.meshes[i]);
    snell_scene_file_destroy(scene.file);
    snell_ctx_destroy(ctx);
    return rc;
}
