/* SPDX-License-Identifier: MIT */
/* bench_spec.c — spec expansion, glmark2 style: "method:key=value:key=v1,v2"
 * (a comma list sweeps) -> one configuration per element of the cartesian
 * product. Keys are the scene/view/material keys below, which every method
 * takes, and the method's own parameters from the library's registry
 * (snell_method_info params, set by snell_glass_set_param). */
#define _POSIX_C_SOURCE 200809L /* strtok_r */
#include "bench.h"
#include "cli_method.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *bench_prog = "snell-bench";

#define MAX_KEYS 16
#define MAX_VALUES 32

/* ------------------------------------------------------ keys of every method */
typedef struct common_key {
    const char *key;
    const char *help;
    int (*apply)(bench_config *c, const char *value); /* 0: bad value (message printed) */
} common_key;

static int bad(const char *key, const char *v, const char *want)
{
    fprintf(stderr, "%s: %s=%s: want %s\n", bench_prog, key, v, want);
    return 0;
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

static int k_scene(bench_config *c, const char *v)
{
    if (!*v || strlen(v) >= sizeof c->scene) return bad("scene", v, "a scene name, a shape name or a mesh path");
    strcpy(c->scene, v);
    return 1;
}

static int k_size(bench_config *c, const char *v)
{
    char tail;
    if (sscanf(v, "%dx%d%c", &c->width, &c->height, &tail) != 2 || c->width < 1 || c->height < 1 ||
        c->width > 8192 || c->height > 8192)
        return bad("size", v, "WxH within 1..8192");
    return 1;
}

static int k_ior(bench_config *c, const char *v) { return parse_vec("ior", v, &c->glass.ior, 1, 0.05f, 100.0f); }

static int k_absorption(bench_config *c, const char *v)
{
    float sigma[3];
    if (!parse_vec("absorption", v, sigma, 3, 0.0f, 1e6f)) return 0;
    snell_glass_set_absorption(&c->glass, sigma);
    return 1;
}

static int k_attenuation(bench_config *c, const char *v)
{
    float a[4];
    if (!parse_vec("attenuation", v, a, 4, 0.0f, 1e6f)) return 0;
    if (a[0] > 1.0f || a[1] > 1.0f || a[2] > 1.0f || !(a[3] > 0.0f))
        return bad("attenuation", v, "r/g/b/distance, colours in 0..1, distance > 0");
    memcpy(c->glass.attenuation_color, a, sizeof c->glass.attenuation_color);
    c->glass.attenuation_distance = a[3];
    return 1;
}

static int k_thickness(bench_config *c, const char *v)
{
    return parse_vec("thickness", v, &c->glass.thickness, 1, 0.0f, 1e6f);
}

static int k_dispersion(bench_config *c, const char *v)
{
    return parse_vec("dispersion", v, &c->glass.dispersion, 1, 0.0f, 20.0f);
}

static int k_dispersion_model(bench_config *c, const char *v)
{
    if (!strcmp(v, "auto")) c->glass.dispersion_model = SNELL_DISPERSION_AUTO;
    else if (!strcmp(v, "per-channel")) c->glass.dispersion_model = SNELL_DISPERSION_PER_CHANNEL;
    else if (!strcmp(v, "one-path")) c->glass.dispersion_model = SNELL_DISPERSION_ONE_PATH;
    else return bad("dispersion_model", v, "auto, per-channel or one-path");
    return 1;
}

static int k_scale(bench_config *c, const char *v)
{
    return parse_vec("scale", v, &c->glass.scale, 1, 1.0f, (float)SNELL_MAX_GLASS_SCALE);
}

static int k_tint(bench_config *c, const char *v) { return parse_vec("tint", v, c->glass.tint, 3, 0.0f, 1.0f); }

static int k_camera(bench_config *c, const char *v)
{
    if (!parse_vec("camera", v, c->cam, 3, -1e4f, 1e4f)) return 0;
    if (!(c->cam[2] > 0.0f)) return bad("camera", v, "az/el/dist (degrees, degrees, distance > 0)");
    c->cam_set = 1;
    return 1;
}

static int k_shading(bench_config *c, const char *v)
{
    if (!strcmp(v, "auto")) c->shading = SNELL_SHADING_AUTO;
    else if (!strcmp(v, "forward")) c->shading = SNELL_SHADING_FORWARD;
    else if (!strcmp(v, "screen")) c->shading = SNELL_SHADING_SCREEN;
    else return bad("shading", v, "auto, forward or screen");
    return 1;
}

/* ssaa=S, msaa=N: the renderer's antialiasing (snell_renderer_desc), in the
 * timed frames and the measured colour frame. */
static int k_ssaa(bench_config *c, const char *v)
{
    return bench_parse_int("ssaa", v, 1, SNELL_MAX_SSAA, &c->ssaa);
}

static int k_msaa(bench_config *c, const char *v)
{
    return bench_parse_int("msaa", v, 1, 64, &c->msaa);
}

/* refine=N: progressive refinement (snell_renderer_desc.refine), measured
 * after N still frames; the timed frames add samples as they go. */
static int k_refine(bench_config *c, const char *v)
{
    return bench_parse_int("refine", v, 1, SNELL_MAX_REFINE, &c->refine);
}

/* lod=R: the scene's glass meshes simplified to the ratio R of their
 * triangles (snell_mesh_simplify) before timing; the references keep the
 * original meshes, so the error measured includes the simplification. */
static int k_lod(bench_config *c, const char *v)
{
    char *end;
    float r;
    errno = 0;
    r = strtof(v, &end);
    if (end == v || *end || errno || !(r > 0.0f && r <= 1.0f))
        return bad("lod", v, "a triangle ratio in (0, 1] (1 = the original mesh)");
    c->lod = r;
    return 1;
}

/* spin=D: the camera turns D degrees about its target every timed frame. */
static int k_spin(bench_config *c, const char *v)
{
    return parse_vec("spin", v, &c->spin, 1, -360.0f, 360.0f);
}

/* scene_layers=L: the frame's scene layers (snell_frame_desc.scene_layers).
 * Not "layers": that is peel's own parameter (its depth layers), and a key
 * that meant the frame's layers for one method and the kernel's for another
 * made peel:layers=2,4,8 sweep the scene layers (issue 25). */
static int k_scene_layers(bench_config *c, const char *v)
{
    if (!bench_parse_int("scene_layers", v, -1, SNELL_MAX_SCENE_LAYERS, &c->scene_layers)) return 0;
    if (c->scene_layers == 1) return bad("scene_layers", v, "-1 (off), 0 (auto) or 2..8");
    return 1;
}

/* methods=M0/M1/...: glass object i drawn with Mi (a registry name or auto),
 * the objects past the list with the spec's method. */
static int k_methods(bench_config *c, const char *v)
{
    const char *p = v;
    c->object_method_count = 0;
    for (;;) {
        const char *e = strchr(p, '/');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        char name[64];
        if (n == 0 || n >= sizeof name || c->object_method_count == SNELL_MAX_GLASS)
            return bad("methods", v, "method names (or auto) separated by /, one per glass object");
        memcpy(name, p, n);
        name[n] = '\0';
        if (snell_method_from_str(name, &c->object_methods[c->object_method_count]) != SNELL_OK)
            return bad("methods", v, "method names (or auto) separated by /, one per glass object");
        c->object_method_count++;
        if (!e) return 1;
        p = e + 1;
    }
}

static const common_key g_common[] = {
    {"scene", "a scene below, a glTF scene file (.gltf/.glb), sphere|cube|torus|goblet|bunny, or a mesh file "
              "(normalised to the unit sphere)", k_scene},
    {"size", "WxH image size", k_size},
    {"ior", "index of refraction of every glass object (default %g)", k_ior},
    {"absorption", "Beer-Lambert coefficient per unit length, a or r/g/b (default 0)", k_absorption},
    {"attenuation", "glTF's form instead: r/g/b/distance, the colour white light turns after distance", k_attenuation},
    {"thickness", "thin walls of this thickness instead of solid glass (default 0: solid)", k_thickness},
    {"tint", "transmission tint r/g/b (default %g/%g/%g)", k_tint},
    {"dispersion", "KHR_materials_dispersion's 20/Abbe number, 0..20 (default 0: none; BK7 0.31, diamond 0.36)",
     k_dispersion},
    {"dispersion_model", "auto (default: one-path), per-channel (three traces) or one-path", k_dispersion_model},
    {"scale", "resolution scale of every glass object: shaded at 1/S of the frame's samples per axis, 1..8 "
              "(default 1; snell_glass_material.scale)", k_scale},
    {"camera", "orbit camera az/el/dist, degrees (default: the scene's, 30/20/3.5 for one mesh)", k_camera},
    {"shading", "auto (default), forward or screen (the renderer's screen-space stage)", k_shading},
    {"ssaa", "supersampling S (the renderer's ssaa: S x S, box-resolved), timed and measured", k_ssaa},
    {"msaa", "multisampling N (the renderer's msaa), timed and measured", k_msaa},
    {"refine", "progressive refinement: the measured colour frame is the mean of N still frames (the renderer's "
               "refine; not with ssaa or msaa), against references of --aa rays a pixel", k_refine},
    {"lod", "glass meshes simplified to this share of their triangles, 0..1 (default 1: the original; the "
            "reference keeps the original)", k_lod},
    {"spin", "degrees the camera turns about its target every timed frame (default 0: a still scene, whose "
             "frames may reuse the last one's work, e.g. the scene layers)", k_spin},
    {"scene_layers", "the frame's scene layers, glass seen through glass: 0 auto (default), -1 off, 2..8 layers at "
                     "most (snell_frame_desc.scene_layers; a method's own layers= is its parameter)", k_scene_layers},
    {"methods", "per glass object (scene order) a method or auto, M0/M1/...; the rest take the spec's method, "
                "the MATCHED reference stays the spec method's model", k_methods},
};
#define COMMON_COUNT ((int)(sizeof g_common / sizeof *g_common))

int bench_spec_key_count(void) { return COMMON_COUNT; }

const char *bench_spec_key_name(int i) { return i >= 0 && i < COMMON_COUNT ? g_common[i].key : NULL; }

void bench_spec_help(FILE *f)
{
    snell_glass_resolved d;
    int k;
    snell_glass_defaults(NULL, &d);
    for (k = 0; k < COMMON_COUNT; k++) {
        char help[256];
        /* the material's defaults are the library's (snell_glass_defaults) */
        if (g_common[k].apply == k_ior) snprintf(help, sizeof help, g_common[k].help, d.material.ior);
        else if (g_common[k].apply == k_tint)
            snprintf(help, sizeof help, g_common[k].help, d.material.tint[0], d.material.tint[1], d.material.tint[2]);
        else snprintf(help, sizeof help, "%s", g_common[k].help);
        fprintf(f, "  %-20s %s\n", g_common[k].key, help);
    }
}

/* -------------------------------------------- per-method bench knowledge */
/* What snell-bench measures a method by comes from its registry entry: the
 * parameters of its default sweep, and the MATCHED reference model it
 * approximates (snell_method_info.ref_interfaces, ref_chord_absorption). */
/* Sets the MATCHED reference model from the method and its resolved parameters. */
static void reference_model(bench_config *c)
{
    snell_glass_resolved r;
    int interfaces = 0;
    c->ref_absorb = c->method->ref_chord_absorption ? SNELL_REF_ABSORB_BOUNDING_SPHERE : SNELL_REF_ABSORB_PATH;
    c->ref_interfaces = c->method->ref_interfaces > 0 ? c->method->ref_interfaces : 10;
    c->ref_terms = 0;
    if (c->method->ref_interfaces > 0 || snell_glass_defaults(&c->glass, &r) != SNELL_OK) return;
    if (snell_glass_get_param(&r.material, c->method->method, "max_interfaces", &interfaces) == SNELL_OK && interfaces > 0)
        c->ref_interfaces = interfaces;
    if (c->method->method == SNELL_METHOD_EXACT) /* its model's terms are the reference's (snell_ref_terms) */
        c->ref_terms = (r.material.exact.fresnel == SNELL_FRESNEL_EXACT ? SNELL_REF_TERM_EXACT_FRESNEL : 0u) |
                       (r.material.exact.inner_fresnel == SNELL_INNER_FRESNEL_ON ? SNELL_REF_TERM_INNER_REFLECTION : 0u) |
                       (r.material.exact.reentry == SNELL_EXACT_REENTRY_ON ? SNELL_REF_TERM_REENTRY : 0u);
}

/* ------------------------------------------------------------- expansion */
typedef struct spec_key {
    const common_key *common;      /* NULL: a method parameter */
    char key[32];
    char values[MAX_VALUES][256];
    int count;
} spec_key;

typedef struct expansion {
    const snell_method_info *method;
    spec_key keys[MAX_KEYS + 2];   /* [0] scene, [1] size, then in spec order */
    int key_count;
    bench_config *out;
    int *n;
} expansion;

static const common_key *find_common(const char *key)
{
    int k;
    for (k = 0; k < COMMON_COUNT; k++)
        if (!strcmp(g_common[k].key, key)) return &g_common[k];
    return NULL;
}

static const snell_param_info *method_param(const snell_method_info *m, const char *key)
{
    int k;
    for (k = 0; k < m->param_count; k++)
        if (!strcmp(m->params[k].name, key)) return &m->params[k];
    return NULL;
}

/* 1 if value is an integer that the library cannot be asked for: every
 * descriptor field reads 0 as "the default" (snell__method_params_resolve),
 * so where a parameter's range holds 0 but its default is not 0 (oliveira's
 * linear steps: 0..32, default 8), "=0" would run the default under the name
 * 0 and a sweep 0,8,16 would time one configuration twice. Enum parameters
 * are exempt: their 0 is named "default" and means it. */
static int zero_inexpressible(const snell_param_info *p, const char *value)
{
    char *end;
    long v;
    if (p->value_names || p->def == 0 || p->min > 0 || p->max < 0) return 0;
    errno = 0;
    v = strtol(value, &end, 10);
    return end != value && !*end && !errno && v == 0;
}

static void refuse_zero(const snell_method_info *m, const snell_param_info *p)
{
    char range[64];
    if (p->min < 0) snprintf(range, sizeof range, "%d%s, 1..%d", p->min, p->min < -1 ? "..-1" : "", p->max);
    else snprintf(range, sizeof range, "1..%d", p->max);
    fprintf(stderr,
            "%s: %s:%s=0: the library reads 0 as the default (%d) for every parameter, so 0 itself "
            "cannot be asked for; give %s, or leave %s= out for the default\n", bench_prog,
            m->name, p->name, p->def, range, p->name);
}

/* The registry's default sweep less the values the bench refuses (above),
 * with a note on stderr naming what was dropped. */
const char *bench_default_sweep(const snell_method_info *m)
{
    static char out[1024];
    char buf[1024], *tok, *save = NULL;
    size_t len = 0;
    if (!m->default_sweep || strlen(m->default_sweep) >= sizeof buf) return m->default_sweep ? m->default_sweep : "";
    strcpy(buf, m->default_sweep);
    out[0] = '\0';
    for (tok = strtok_r(buf, ":", &save); tok; tok = strtok_r(NULL, ":", &save)) {
        char *eq = strchr(tok, '='), *v, *vsave = NULL;
        const snell_param_info *p;
        int kept = 0;
        if (!eq) return m->default_sweep; /* bench_expand_spec says what is wrong with it */
        *eq = '\0';
        p = method_param(m, tok);
        for (v = strtok_r(eq + 1, ",", &vsave); v; v = strtok_r(NULL, ",", &vsave)) {
            if (p && zero_inexpressible(p, v)) {
                fprintf(stderr, "%s: %s's default sweep %s: %s=0 dropped (0 means the default %d here)\n", bench_prog,
                        m->name, m->default_sweep, p->name, p->def);
                continue;
            }
            if (len < sizeof out)
                len += (size_t)snprintf(out + len, sizeof out - len, "%s%s%s%s", kept ? "," : (len ? ":" : ""),
                                        kept ? "" : tok, kept ? "" : "=", v);
            kept = 1;
        }
    }
    return out;
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
            fprintf(stderr, "%s: %s: empty, too long or too many values in '%s'\n", bench_prog, k->key, list);
            return 0;
        }
        memcpy(k->values[k->count], s, n);
        k->values[k->count++][n] = '\0';
        if (!e) return 1;
        s = e + 1;
    }
}

static void config_defaults(bench_config *c, const snell_method_info *m)
{
    memset(c, 0, sizeof *c);
    c->method = m;
    c->glass.method = m->method;
    c->width = c->height = 256;
    c->gpu_median = -1.0;
    c->vs_scene = -1.0;
    c->lod = 1.0f;
}

/* The material keys: a scene file brings its own materials. */
static int is_material_key(const common_key *k)
{
    return k && (k->apply == k_ior || k->apply == k_absorption || k->apply == k_attenuation ||
                 k->apply == k_thickness || k->apply == k_tint || k->apply == k_dispersion ||
                 k->apply == k_dispersion_model);
}

static int apply_key(bench_config *c, const spec_key *k, const char *value)
{
    if (k->common) return k->common->apply(c, value);
    /* the key is one of this method's parameters (checked in bench_expand_spec) */
    return cli_param_set_one(bench_prog, &c->glass, c->method->method, k->key, value);
}

/* Cartesian product of the keys' values, depth-first in key order. */
static int expand(expansion *e, int depth, const char **chosen)
{
    int v;
    if (depth == e->key_count) {
        bench_config *c;
        int k;
        size_t len;
        if (*e->n >= BENCH_MAX_CONFIGS) {
            fprintf(stderr, "%s: more than %d configurations\n", bench_prog, BENCH_MAX_CONFIGS);
            return 0;
        }
        c = &e->out[(*e->n)++];
        config_defaults(c, e->method);
        len = (size_t)snprintf(c->spec, sizeof c->spec, "%s", e->method->name);
        for (k = 0; k < e->key_count; k++) {
            if (is_material_key(e->keys[k].common) && bench_scene_is_file(chosen[0])) {
                fprintf(stderr, "%s: %s=: scene=%s brings its own materials; the material keys apply to "
                                "mesh and named scenes only\n", bench_prog, e->keys[k].key, chosen[0]);
                return 0;
            }
            if (!apply_key(c, &e->keys[k], chosen[k])) return 0;
            if (len < sizeof c->spec)
                len += (size_t)snprintf(c->spec + len, sizeof c->spec - len, ":%s=%s", e->keys[k].key, chosen[k]);
        }
        if (!c->cam_set) bench_scene_camera(c->scene, c->cam);
        reference_model(c);
        return 1;
    }
    for (v = 0; v < e->keys[depth].count; v++) {
        chosen[depth] = e->keys[depth].values[v];
        if (!expand(e, depth + 1, chosen)) return 0;
    }
    return 1;
}

/* "auto": the renderer picks each object's method (snell_method_info has no
 * entry for it). It takes the keys every method takes; its MATCHED reference
 * is FULL's model (any method may draw an object), so vs_matched = vs_full. */
static const snell_method_info g_auto = {SNELL_METHOD_AUTO, "auto", "the cheapest adequate method per object",
                                         "", 0, NULL, 0, NULL, 10, 0, ""};

const snell_method_info *bench_method_info(snell_method m)
{
    return m == SNELL_METHOD_AUTO ? &g_auto : snell_method_info_of(m);
}

static int parse_method(const char *name, const char *spec, const snell_method_info **out)
{
    snell_method m = SNELL_METHOD_COUNT_;
    int i;
    if (snell_method_from_str(name, &m) == SNELL_OK && m == SNELL_METHOD_AUTO) return *out = &g_auto, 1;
    if (snell_method_from_str(name, &m) == SNELL_OK && (*out = snell_method_info_of(m)) != NULL) return 1;
    fprintf(stderr, "%s: unknown method '%s' in '%s'; methods: auto,", bench_prog, name, spec);
    for (i = 0; i < snell_method_count(); i++) fprintf(stderr, "%s %s", i ? "," : "", snell_method_info_at(i)->name);
    fprintf(stderr, "\n");
    return 0;
}

static int default_key(spec_key *k, const char *name, const char *list)
{
    k->common = find_common(name);
    snprintf(k->key, sizeof k->key, "%s", name);
    return split_values(k, list);
}

int bench_expand_spec(const char *spec, const bench_options *o, bench_config *out, int *n)
{
    static expansion e; /* 16 KiB per key: not on the stack */
    char buf[2048], *tok, *save = NULL;
    const char *chosen[MAX_KEYS + 2];
    int k, have_scene = 0, have_size = 0;
    memset(&e, 0, sizeof e);
    if (strlen(spec) >= sizeof buf) return fprintf(stderr, "%s: spec too long\n", bench_prog), 0;
    strcpy(buf, spec);
    tok = strtok_r(buf, ":", &save);
    if (!parse_method(tok ? tok : "", spec, &e.method)) return 0;
    e.key_count = 2; /* scene and size first, so that they lead the canonical spec */
    while ((tok = strtok_r(NULL, ":", &save)) != NULL) {
        char *eq = strchr(tok, '=');
        spec_key *sk;
        const common_key *ck;
        const snell_param_info *mp;
        if (!eq) return fprintf(stderr, "%s: '%s' in '%s' is not key=value\n", bench_prog, tok, spec), 0;
        *eq = '\0';
        /* the method's own parameters first: a method's key always reaches
         * its kernel (tests/test_bench_keys.c checks that no parameter is
         * named like a common key, so neither hides the other) */
        mp = method_param(e.method, tok);
        ck = mp ? NULL : find_common(tok);
        if (!ck && !mp) {
            fprintf(stderr, "%s: method %s has no key '%s' (see --list)%s\n", bench_prog, e.method->name, tok,
                    !strcmp(tok, "layers") ? "; the frame's scene layers are scene_layers=" : "");
            return 0;
        }
        if (!strcmp(tok, "scene")) sk = &e.keys[0], have_scene = 1;
        else if (!strcmp(tok, "size")) sk = &e.keys[1], have_size = 1;
        else if (e.key_count == MAX_KEYS + 2) return fprintf(stderr, "%s: too many keys\n", bench_prog), 0;
        else sk = &e.keys[e.key_count++];
        sk->common = ck;
        snprintf(sk->key, sizeof sk->key, "%s", tok);
        if (!split_values(sk, eq + 1)) return 0;
        for (k = 0; mp && k < sk->count; k++)
            if (zero_inexpressible(mp, sk->values[k])) return refuse_zero(e.method, mp), 0;
    }
    if (!have_scene && !default_key(&e.keys[0], "scene", o->scenes)) return 0;
    if (!have_size && !default_key(&e.keys[1], "size", o->sizes)) return 0;
    for (k = 0; k < e.key_count; k++) chosen[k] = NULL;
    e.out = out;
    e.n = n;
    return expand(&e, 0, chosen);
}
