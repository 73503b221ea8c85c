/* SPDX-License-Identifier: MIT */
/* render_args.c — snell-render's command line read as a scene: repeated
 * --mesh (glass) and --opaque objects, each followed by its own options, the
 * view and the outputs. Method names and parameters come from the library's
 * registry (cli_method.c); defaults shown in --help from snell_glass_defaults. */
#include "render.h"
#include "cli_method.h"
#include "cli_opts.h"
#include "cli_scene.h"
#include "cli_system.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PROG "snell-render"

void render_usage(FILE *f)
{
    snell_glass_resolved d;
    snell_glass_defaults(NULL, &d);
    fprintf(f,
            "usage: snell-render [options] [--mesh M [glass options]]... [--opaque M [--place P] [--color C]]...\n"
            "Renders refractive glass to a PNG (default: one glass sphere -> snell.png).\n\n"
            "scene (no --mesh: one glass sphere at the origin):\n"
            "  --mesh M               a glass object: OBJ, glTF (.gltf/.glb), .3ds or .jobj file, or %s\n"
            "                         (also shape:NAME); glass options after it apply to it, glass options\n"
            "                         before the first --mesh are the defaults of every glass object\n"
            "  --opaque M             an opaque diffuse object (mesh names as for --mesh)\n"
            "  --opaque N             demo: N opaque cubes orbiting the origin, moving every frame\n"
            "  --place X,Y,Z[,S]      position and uniform scale of the last --mesh or --opaque (default 0,0,0,1)\n"
            "  --color R,G,B          albedo of the last --opaque, 0..1 (default 0.8 grey)\n"
            "  --no-normalize         keep the meshes' own scale (default: fit each in the unit sphere)\n"
            "  --scene FILE           a glTF scene (.gltf/.glb): its glass (KHR_materials_transmission) and\n"
            "                         opaque objects, placed as its nodes say, and its camera unless --camera\n"
            "                         is given (instead of --mesh/--opaque)\n\n"
            "glass (apply to the most recent --mesh):\n"
            "  --ior N                index of refraction, 0.05..100 (default %g)\n"
            "  --absorption R,G,B     Beer-Lambert coefficient per unit length, or one value for all (default 0)\n"
            "  --attenuation R,G,B,D  glTF's form: the colour white light turns after distance D (default none)\n"
            "  --tint R,G,B           multiplies transmitted light (default %g,%g,%g)\n"
            "  --thickness T          a thin wall of thickness T instead of a solid (default 0: solid)\n"
            "  --dispersion D         KHR_materials_dispersion's 20/Abbe number, 0..20 (default 0: none;\n"
            "                         BK7 glass 0.31, diamond 0.36): red, green, blue at 656.3, 587.6, 486.1 nm\n"
            "  --abbe V               the same as an Abbe number V > 1 (dispersion 20/V)\n"
            "  --dispersion-model M   auto (default: one-path), per-channel (the whole trace per channel) or\n"
            "                         one-path (one trace, red and blue re-refracted along it)\n"
            "  --scale S              resolution scale: the glass shaded at 1/S of the frame's samples per axis,\n"
            "                         its edges drawn at full resolution, 1..%d (default 1; also --param scale=S)\n"
            "  --method NAME          auto (default: the cheapest adequate method per object)",
            cli_shape_names, d.material.ior, d.material.tint[0], d.material.tint[1], d.material.tint[2],
            SNELL_MAX_GLASS_SCALE);
    {
        int i;
        for (i = 0; i < snell_method_count(); i++) fprintf(f, ", %s", snell_method_info_at(i)->name);
    }
    fprintf(f, "\n"
               "  --NAME V               a parameter of a method, listed below (NAME: the field it sets,\n"
               "                         snell_glass_material.METHOD.NAME); --param [METHOD.]NAME=V is the same\n");
    cli_method_help(f, "  ", "--", " V");
    fprintf(f,
            "\nview and output:\n"
            "  --env FILE|procedural  environment: procedural (default), an equirectangular image,\n"
            "                         or six faces given as a pattern with %%s (px nx py ny pz nz;\n"
            "                         %%%% for a %%, no other %%)\n"
            "  --size WxH             image size (default 512x512)\n"
            "  --camera AZ,EL,DIST    orbit camera about the origin: degrees, degrees, distance (default 30,20,3.5)\n"
            "  --fov DEG              vertical field of view (default 45)\n"
            "  --view M --projection M  the camera as a host gives it: 16 comma-separated numbers each,\n"
            "                         column-major, GL conventions (any perspective, off-axis included)\n"
            "  --backend NAME         surfaceless (default), pbuffer\n"
            "  --frames N             render N frames and print the median time per frame\n"
            "  --shading MODE         auto (default: screen space for dense meshes), forward, screen\n"
            "  --env-lookup L         environment look-up: auto (default), cube, paraboloid (dual-paraboloid maps),\n"
            "                         paraboloid-direct (dynamic environments' maps rendered straight)\n"
            "  --ssaa S               supersample S x S, box-resolved (2..8; the area average)\n"
            "  --msaa N               multisample N (triangle edges only; not with --ssaa)\n"
            "  --refine N             progressive refinement: the image is the mean of N still frames, each\n"
            "                         moved within the pixel (1..%d; not with --msaa)\n"
            "  --scene-layers L       glass through glass and opaque objects through glass: auto (default: on\n"
            "                         with 2+ glass or glass + opaque objects), off (each glass sees only the\n"
            "                         environment, or its dynamic one), or 2..%d, the most layers peeled\n"
            "  --light dir:X,Y,Z[,I]  a directional light travelling along X,Y,Z of irradiance I (default 1):\n"
            "                         with --floor, caustics and shadows of the glass on the floor\n"
            "  --light spot:PX,PY,PZ,X,Y,Z,A[,I]  a spot light at P shining along X,Y,Z within A radians of\n"
            "                         it, intensity I (irradiance at distance 1; default 1)\n"
            "  --floor Y[,EXTENT]     a receiver plane y = Y, the square |x|,|z| <= EXTENT (default 4)\n"
            "  --photons N            photons per glass object: N x N (16..1024, default 256)\n"
            "  --floor-map N          the floor's light map, N x N texels (16..2048, default 256)\n"
            "  --stats                print the last frame's statistics: per glass object the method used\n"
            "                         and why, warnings, passes, what was skipped\n"
            "  -v, --verbose          the statistics on stderr, and the library's info messages\n"
            "  -o FILE                output PNG (default snell.png)\n"
            "  --trace-pixel X,Y      reference light path of pixel X,Y through the whole scene (repeatable):\n"
            "                         drawn over a second view into FILE_trace.png, points in FILE_trace.json\n"
            "  --panels FILE          glass panels over the frame, one a line: key=value fields named as\n"
            "                         snell_panel's, e.g. 'center=256,256 size=300,160 radius=40 frost=4 group=1'\n"
            "                         (pixels from the bottom-left corner; docs/panels.md)\n"
            "  --under IMAGE          the panels over a PNG (a GL texture the frame draws first), the frame\n"
            "                         its size unless --size is given; without it, over the scene's frame\n"
            "  --reference            with --panels: the reference's image of the same panels over the same\n"
            "                         pixels (snell_ref_panels) into FILE_reference.png beside -o FILE\n"
            "  --2d SCENE             2D lightmap mode (see the 2D options with --2d --help)\n"
            "  --water                water mode: a water surface in a box, with glass (see --water --help)\n"
            "  --version              the version and the commit it was built from\n"
            "  -h, --help             this text\n", SNELL_MAX_REFINE, SNELL_MAX_SCENE_LAYERS);
}

/* n comma-separated finite floats, the whole string. */
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

static int is_count(const char *s)
{
    if (!*s) return 0;
    for (; *s; s++)
        if (*s < '0' || *s > '9') return 0;
    return 1;
}

static int usage_error(const char *fmt, const char *opt, const char *v)
{
    fprintf(stderr, PROG ": ");
    fprintf(stderr, fmt, opt, v);
    fprintf(stderr, "\n");
    return 0;
}

static int in_range3(const float *v, float lo, float hi)
{
    return v[0] >= lo && v[0] <= hi && v[1] >= lo && v[1] <= hi && v[2] >= lo && v[2] <= hi;
}

/* Notes that parameter name (of method, or AUTO: any that has it) was given for g. */
static void remember_param(render_object *g, const char *name, snell_method method)
{
    int i;
    for (i = 0; i < g->given_count; i++)
        if (!strcmp(g->given[i].name, name) && g->given[i].method == method) return;
    if (g->given_count == (int)(sizeof g->given / sizeof *g->given)) return;
    snprintf(g->given[g->given_count].name, sizeof g->given[0].name, "%s", name);
    g->given[g->given_count++].method = method;
}

/* A registry parameter of the current glass: "--NAME V" or "--param [METHOD.]NAME=V".
 * 1 set, 0 bad value (printed), -1 not a parameter name. */
static int method_param(const char *name, const char *v, render_object *g)
{
    int at = 0;
    if (!cli_param_owner(name, &at)) return -1;
    remember_param(g, name, SNELL_METHOD_AUTO);
    return cli_param_set(PROG, &g->material, name, v);
}

/* A parameter that one of the object's methods has: --method M with a parameter
 * only other methods have is refused (AUTO may pick any method, so it takes any). */
static int check_params(const render_object *g, const char *what)
{
    const snell_method_info *mi = snell_method_info_of(g->material.method);
    int i, k;
    if (g->material.method == SNELL_METHOD_AUTO || !mi) return 1;
    for (i = 0; i < g->given_count; i++) {
        int has = g->given[i].method == SNELL_METHOD_AUTO || g->given[i].method == g->material.method;
        for (k = 0; has && g->given[i].method == SNELL_METHOD_AUTO && k < mi->param_count; k++)
            if (!strcmp(mi->params[k].name, g->given[i].name)) break;
        if (!has || (g->given[i].method == SNELL_METHOD_AUTO && k == mi->param_count)) {
            char owners[160] = "";
            size_t len = 0;
            int at = 0;
            const snell_method_info *owner;
            if (g->given[i].method != SNELL_METHOD_AUTO)
                snprintf(owners, sizeof owners, "%s", snell_method_str(g->given[i].method));
            else
                while ((owner = cli_param_owner(g->given[i].name, &at)) != NULL && len < sizeof owners)
                    len += (size_t)snprintf(owners + len, sizeof owners - len, "%s%s", len ? ", " : "", owner->name);
            fprintf(stderr, PROG ": --%s is a parameter of %s, not of --method %s (%s); see --help\n",
                    g->given[i].name, owners, mi->name, what);
            return 0;
        }
    }
    return 1;
}

static int scale_option(const char *v, snell_glass_material *m)
{
    if (!parse_floats(v, &m->scale, 1) || !(m->scale >= 1.0f && m->scale <= (float)SNELL_MAX_GLASS_SCALE))
        return usage_error("%s wants a number in 1..8, got '%s'", "--scale", v);
    return 1;
}

static int param_option(const char *v, render_object *g)
{
    snell_glass_material *m = &g->material;
    char name[96];
    const char *eq = strchr(v, '='), *dot;
    snell_method method;
    if (!eq || eq == v || (size_t)(eq - v) >= sizeof name)
        return usage_error("%s wants [METHOD.]NAME=VALUE, got '%s'", "--param", v);
    memcpy(name, v, (size_t)(eq - v));
    name[eq - v] = '\0';
    dot = strchr(name, '.');
    if (!strcmp(name, "scale")) return scale_option(eq + 1, m); /* every method's: the material's own field */
    if (!dot) {
        int r = method_param(name, eq + 1, g);
        return r >= 0 ? r : usage_error("%s: no method has a parameter '%s' (see --help)", "--param", name);
    }
    name[dot - name] = '\0';
    if (!cli_method_parse(PROG, name, &method)) return 0;
    remember_param(g, dot + 1, method);
    return cli_param_set_one(PROG, m, method, dot + 1, eq + 1);
}

/* Options of the most recent glass object. 1 handled, 0 bad value, -1 not a glass option. */
static int glass_option(const char *a, const char *v, render_object *g)
{
    snell_glass_material *m = &g->material;
    if (!strcmp(a, "--ior")) {
        if (!parse_floats(v, &m->ior, 1) || m->ior < 0.05f || m->ior > 100.0f)
            return usage_error("%s wants a number in 0.05..100, got '%s'", a, v);
    } else if (!strcmp(a, "--absorption")) {
        float s[3];
        if (parse_floats(v, s, 1)) s[1] = s[2] = s[0];
        else if (!parse_floats(v, s, 3)) return usage_error("%s wants R,G,B (or one value), got '%s'", a, v);
        if (!in_range3(s, 0.0f, 1e6f)) return usage_error("%s wants coefficients in 0..1e6, got '%s'", a, v);
        snell_glass_set_absorption(m, s);
    } else if (!strcmp(a, "--attenuation")) {
        float c[4];
        if (!parse_floats(v, c, 4) || !in_range3(c, 0.0f, 1.0f) || !(c[3] > 0.0f))
            return usage_error("%s wants R,G,B,DISTANCE with colours in 0..1 and DISTANCE > 0, got '%s'", a, v);
        memcpy(m->attenuation_color, c, sizeof m->attenuation_color);
        m->attenuation_distance = c[3];
    } else if (!strcmp(a, "--tint")) {
        if (!parse_floats(v, m->tint, 3) || !in_range3(m->tint, 0.0f, 1e3f))
            return usage_error("%s wants R,G,B >= 0, got '%s'", a, v);
    } else if (!strcmp(a, "--thickness")) {
        if (!parse_floats(v, &m->thickness, 1) || m->thickness < 0.0f)
            return usage_error("%s wants a thickness >= 0, got '%s'", a, v);
    } else if (!strcmp(a, "--dispersion")) {
        if (!parse_floats(v, &m->dispersion, 1) || m->dispersion < 0.0f || m->dispersion > 20.0f)
            return usage_error("%s wants a number in 0..20, got '%s'", a, v);
    } else if (!strcmp(a, "--abbe")) {
        float abbe;
        if (!parse_floats(v, &abbe, 1) || snell_glass_set_abbe(m, abbe) != SNELL_OK)
            return usage_error("%s wants an Abbe number > 1, got '%s'", a, v);
    } else if (!strcmp(a, "--dispersion-model")) {
        if (!strcmp(v, "auto")) m->dispersion_model = SNELL_DISPERSION_AUTO;
        else if (!strcmp(v, "per-channel")) m->dispersion_model = SNELL_DISPERSION_PER_CHANNEL;
        else if (!strcmp(v, "one-path")) m->dispersion_model = SNELL_DISPERSION_ONE_PATH;
        else return usage_error("%s wants auto, per-channel or one-path, got '%s'", a, v);
    } else if (!strcmp(a, "--scale")) {
        return scale_option(v, m);
    } else if (!strcmp(a, "--method")) {
        if (!cli_method_parse(PROG, v, &m->method)) return 0;
    } else if (!strcmp(a, "--param")) {
        return param_option(v, g);
    } else if (!strncmp(a, "--", 2)) {
        return method_param(a + 2, v, g);
    } else {
        return -1;
    }
    return 1;
}

/* A new glass (--mesh) or opaque (--opaque MESH) object; NULL if the list is full. */
static render_object *add_object(render_options *o, const char *mesh, int opaque)
{
    render_object *obj;
    snell_shape shape;
    if (cli_is_shape_spec(mesh) && !cli_shape_from_name(mesh, &shape)) {
        fprintf(stderr, PROG ": unknown shape '%s' (%s)\n", mesh + 6, cli_shape_names);
        return NULL;
    }
    if (opaque ? o->opaque_count + o->orbit >= SNELL_MAX_OPAQUE : o->glass_count >= SNELL_MAX_GLASS) {
        fprintf(stderr, PROG ": more than %d %s objects\n", opaque ? SNELL_MAX_OPAQUE : SNELL_MAX_GLASS,
                opaque ? "opaque" : "glass");
        return NULL;
    }
    obj = opaque ? &o->opaque[o->opaque_count++] : &o->glass[o->glass_count++];
    if (opaque) memset(obj, 0, sizeof *obj);
    else *obj = o->base;
    obj->mesh = mesh;
    obj->placed = 0;
    obj->place[0] = obj->place[1] = obj->place[2] = 0.0f;
    obj->place[3] = 1.0f;
    return obj;
}

/* View, output and mode options. 1 handled, 0 bad value, -1 unknown. */
static int view_option(const char *a, const char *v, render_options *o)
{
    if (!strcmp(a, "--env")) {
        char why[160];
        if (!cli_env_spec_check(v, why, sizeof why)) {
            fprintf(stderr, PROG ": %s '%s': %s; only %%s (the face: px nx py ny pz nz) and %%%% (a %%) may follow "
                            "a %%\n", a, v, why);
            return 0;
        }
        o->env = strcmp(v, "procedural") ? v : NULL;
    } else if (!strcmp(a, "--size")) {
        char tail;
        if (sscanf(v, "%dx%d%c", &o->width, &o->height, &tail) != 2 || o->width < 1 || o->height < 1 ||
            o->width > 16384 || o->height > 16384)
            return usage_error("%s wants WxH within 1..16384, got '%s'", a, v);
        o->size_given = 1;
    } else if (!strcmp(a, "--panels")) {
        char why[512];
        cli_panels_free(&o->panels); /* a second --panels replaces the first */
        if (!cli_panels_read(v, &o->panels, why, sizeof why)) {
            fprintf(stderr, PROG ": --panels %s\n", why);
            return 0;
        }
        o->panels_file = v;
    } else if (!strcmp(a, "--under")) {
        o->under_file = v;
    } else if (!strcmp(a, "--camera")) {
        float c[3];
        if (!parse_floats(v, c, 3) || !(c[2] > 0.0f))
            return usage_error("%s wants AZ,EL,DIST with DIST > 0, got '%s'", a, v);
        o->az_deg = c[0];
        o->el_deg = c[1];
        o->dist = c[2];
        o->camera_given = 1;
    } else if (!strcmp(a, "--view") || !strcmp(a, "--projection")) {
        int view = !strcmp(a, "--view");
        if (!parse_floats(v, view ? o->view : o->projection, 16))
            return usage_error("%s wants 16 comma-separated numbers (column-major), got '%s'", a, v);
        *(view ? &o->view_given : &o->projection_given) = 1;
    } else if (!strcmp(a, "--fov")) {
        if (!parse_floats(v, &o->fov_deg, 1) || !(o->fov_deg > 1.0f && o->fov_deg < 179.0f))
            return usage_error("%s wants degrees in 1..179, got '%s'", a, v);
        o->fov_given = 1;
    } else if (!strcmp(a, "--backend")) {
        if (!strcmp(v, "surfaceless")) o->backend = SNELL_BACKEND_SURFACELESS;
        else if (!strcmp(v, "pbuffer")) o->backend = SNELL_BACKEND_PBUFFER;
        else return usage_error("%s: unknown backend '%s' (surfaceless, pbuffer)", a, v);
    } else if (!strcmp(a, "--shading")) {
        if (!strcmp(v, "auto")) o->shading = SNELL_SHADING_AUTO;
        else if (!strcmp(v, "forward")) o->shading = SNELL_SHADING_FORWARD;
        else if (!strcmp(v, "screen")) o->shading = SNELL_SHADING_SCREEN;
        else return usage_error("%s: unknown shading '%s' (auto, forward, screen)", a, v);
    } else if (!strcmp(a, "--env-lookup")) {
        if (!strcmp(v, "auto")) o->env_lookup = SNELL_ENV_LOOKUP_AUTO;
        else if (!strcmp(v, "cube")) o->env_lookup = SNELL_ENV_LOOKUP_CUBE;
        else if (!strcmp(v, "paraboloid")) o->env_lookup = SNELL_ENV_LOOKUP_DUAL_PARABOLOID;
        else if (!strcmp(v, "paraboloid-direct")) o->env_lookup = SNELL_ENV_LOOKUP_DUAL_PARABOLOID_DIRECT;
        else return usage_error("%s: unknown look-up '%s' (auto, cube, paraboloid, paraboloid-direct)", a, v);
    } else if (!strcmp(a, "--ssaa")) {
        if (!parse_int(v, &o->ssaa) || o->ssaa < 1 || o->ssaa > SNELL_MAX_SSAA)
            return usage_error("%s wants 1..8, got '%s'", a, v);
    } else if (!strcmp(a, "--msaa")) {
        if (!parse_int(v, &o->msaa) || o->msaa < 1 || o->msaa > 64)
            return usage_error("%s wants 1..64, got '%s'", a, v);
    } else if (!strcmp(a, "--refine")) {
        if (!parse_int(v, &o->refine) || o->refine < 1 || o->refine > SNELL_MAX_REFINE)
            return usage_error("%s wants 1..4096, got '%s'", a, v);
    } else if (!strcmp(a, "--scene-layers")) {
        if (!strcmp(v, "auto")) o->scene_layers = 0;
        else if (!strcmp(v, "off")) o->scene_layers = -1;
        else if (!parse_int(v, &o->scene_layers) || o->scene_layers < 2 || o->scene_layers > SNELL_MAX_SCENE_LAYERS)
            return usage_error("%s wants auto, off or 2..8 (SNELL_MAX_SCENE_LAYERS), got '%s'", a, v);
    } else if (!strcmp(a, "--frames")) {
        if (!parse_int(v, &o->frames) || o->frames < 1 || o->frames > 100000)
            return usage_error("%s wants 1..100000, got '%s'", a, v);
    } else if (!strcmp(a, "--trace-pixel")) {
        float xy[2];
        if (o->trace_count == 16 || !parse_floats(v, xy, 2) || xy[0] != floorf(xy[0]) || xy[1] != floorf(xy[1]))
            return usage_error("%s wants X,Y (integers, at most 16 pixels), got '%s'", a, v);
        o->trace_xy[2 * o->trace_count] = (int)xy[0];
        o->trace_xy[2 * o->trace_count++ + 1] = (int)xy[1];
    } else if (!strcmp(a, "--light")) {
        float l[8] = {0, 0, 0, 1, 0, 0, 0, 1};
        int spot = !strncmp(v, "spot:", 5);
        if (spot ? (!parse_floats(v + 5, l, 8) && !parse_floats(v + 5, l, 7)) || !(l[6] > 0.0f && l[6] <= 1.5f) ||
                       l[3] * l[3] + l[4] * l[4] + l[5] * l[5] == 0.0f || !(l[7] >= 0.0f)
                 : strncmp(v, "dir:", 4) || (!parse_floats(v + 4, l, 4) && !parse_floats(v + 4, l, 3)) ||
                       l[0] * l[0] + l[1] * l[1] + l[2] * l[2] == 0.0f || !(l[3] >= 0.0f))
            return usage_error("%s wants dir:X,Y,Z[,I] or spot:PX,PY,PZ,X,Y,Z,ANGLE[,I] (direction not zero, "
                               "ANGLE 0..1.5 radians, I >= 0), got '%s'", a, v);
        o->light.type = spot ? SNELL_LIGHT_SPOT : SNELL_LIGHT_DIRECTIONAL;
        if (spot) memcpy(o->light.position, l, sizeof o->light.position);
        memcpy(o->light.direction, spot ? l + 3 : l, sizeof o->light.direction);
        o->light.spot_angle = spot ? l[6] : 0.0f;
        o->light.color[0] = o->light.color[1] = o->light.color[2] = spot ? l[7] : l[3];
    } else if (!strcmp(a, "--photons")) {
        if (!parse_int(v, &o->light.photons) || o->light.photons < 16 || o->light.photons > 1024)
            return usage_error("%s wants 16..1024, got '%s'", a, v);
    } else if (!strcmp(a, "--floor")) {
        float f[2] = {0, 4};
        if ((!parse_floats(v, f, 2) && !parse_floats(v, f, 1)) || !(f[1] > 0.0f))
            return usage_error("%s wants Y[,EXTENT] (EXTENT > 0), got '%s'", a, v);
        o->receiver.height = f[0];
        o->receiver.extent = f[1];
    } else if (!strcmp(a, "--floor-map")) {
        if (!parse_int(v, &o->receiver.map_size) || o->receiver.map_size < 16 || o->receiver.map_size > 2048)
            return usage_error("%s wants 16..2048, got '%s'", a, v);
    } else if (!strcmp(a, "-o")) {
        o->out = v;
    } else {
        return -1;
    }
    return 1;
}

static void set_defaults(render_options *o)
{
    memset(o, 0, sizeof *o);
    o->base.mesh = "sphere";
    o->base.place[3] = 1.0f;
    o->out = "snell.png";
    o->width = o->height = 512;
    o->az_deg = 30.0f;
    o->el_deg = 20.0f;
    o->dist = 3.5f;
    o->fov_deg = 45.0f;
    o->frames = 1;
    o->normalize = 1;
}

/* The long options: the fixed ones, then every method parameter of the
 * registry (--NAME V). Each value is its index + 256. */
static const struct option *long_options(void)
{
    static const char *const valued[] = {"scene", "mesh", "opaque", "place", "color", "env", "size", "camera", "fov",
                                         "view", "projection", "backend", "shading", "env-lookup", "ssaa", "msaa",
                                         "refine", "scene-layers", "frames", "trace-pixel", "panels", "under", "ior", "absorption", "attenuation",
                                         "tint", "thickness", "dispersion", "abbe", "dispersion-model", "scale",
                                         "method", "param", "light", "photons", "floor", "floor-map"};
    static const char *const flags[] = {"no-normalize", "stats", "verbose", "reference", "help", "version"};
    static struct option opts[256];
    static int n;
    size_t k;
    int i, j;
    if (n) return opts;
    for (k = 0; k < sizeof valued / sizeof *valued; k++) opts[n] = (struct option){valued[k], required_argument, NULL, 256 + n}, n++;
    for (k = 0; k < sizeof flags / sizeof *flags; k++) opts[n] = (struct option){flags[k], no_argument, NULL, 256 + n}, n++;
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *m = snell_method_info_at(i);
        for (j = 0; j < m->param_count && n < 255; j++) {
            int seen = 0, q;
            for (q = 0; q < n && !seen; q++) seen = !strcmp(opts[q].name, m->params[j].name);
            if (!seen) opts[n] = (struct option){m->params[j].name, required_argument, NULL, 256 + n}, n++;
        }
    }
    opts[n] = (struct option){NULL, 0, NULL, 0};
    return opts;
}

int render_parse_args(int argc, char **argv, render_options *o)
{
    /* cur: the last --mesh or --opaque (--place); glass: the last --mesh, or
     * base before the first (glass options); opaque: cur if it is opaque. */
    render_object *cur = NULL, *glass, *opaque = NULL;
    const struct option *longopts = long_options();
    int i, r, c;
    set_defaults(o);
    glass = &o->base;
    if (cli_wants_help(argc, argv)) { /* --help wherever it is */
        render_usage(stdout);
        return -1;
    }
    cli_opts_reset();
    while ((c = cli_getopt(PROG, "--help", argc, argv, "o:vh", longopts)) != -1) {
        char name[64];
        const char *a = name, *v = optarg;
        if (c == '?') return 0;
        if (c >= 256) snprintf(name, sizeof name, "--%s", longopts[c - 256].name);
        else snprintf(name, sizeof name, "-%c", c);
        if (!strcmp(a, "--no-normalize")) {
            o->normalize = 0;
            continue;
        } else if (!strcmp(a, "--stats")) {
            o->stats = 1;
            continue;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            o->verbose = 1;
            continue;
        } else if (!strcmp(a, "--reference")) {
            o->reference = 1;
            continue;
        } else if (!strcmp(a, "--version")) {
            cli_print_version(PROG);
            return -1;
        }
        if (!strcmp(a, "--scene")) {
            o->scene_file = v;
        } else if (!strcmp(a, "--mesh")) {
            if (!(cur = glass = add_object(o, v, 0))) return 0;
            opaque = NULL;
        } else if (!strcmp(a, "--opaque") && is_count(v)) {
            if (!parse_int(v, &o->orbit) || o->orbit + o->opaque_count > SNELL_MAX_OPAQUE) {
                fprintf(stderr, PROG ": --opaque N: at most %d opaque objects in all, got '%s'\n", SNELL_MAX_OPAQUE, v);
                return 0;
            }
        } else if (!strcmp(a, "--opaque")) {
            if (!(cur = opaque = add_object(o, v, 1))) return 0;
        } else if (!strcmp(a, "--place")) {
            render_object *t = cur ? cur : &o->base;
            if (parse_floats(v, t->place, 3)) t->place[3] = 1.0f;
            else if (!parse_floats(v, t->place, 4) || !(t->place[3] > 0.0f))
                return usage_error("%s wants X,Y,Z or X,Y,Z,SCALE with SCALE > 0, got '%s'", a, v);
            t->placed = 1;
        } else if (!strcmp(a, "--color")) {
            if (!opaque) return usage_error("%s applies to an --opaque object; give it after --opaque MESH%s", a, "");
            if (!parse_floats(v, opaque->color, 3) || !in_range3(opaque->color, 0.0f, 1.0f))
                return usage_error("%s wants R,G,B in 0..1, got '%s'", a, v);
        } else if ((r = view_option(a, v, o)) >= 0 || (r = glass_option(a, v, glass)) >= 0) {
            if (!r) return 0;
        } else {
            fprintf(stderr, PROG ": unknown option '%s'; see --help\n", a);
            return 0;
        }
    }
    if (optind < argc) {
        fprintf(stderr, PROG ": unexpected argument '%s'; see --help\n", argv[optind]);
        return 0;
    }
    if (o->glass_count == 0 && !check_params(&o->base, "the default sphere")) return 0;
    for (i = 0; i < o->glass_count; i++) {
        char what[300];
        snprintf(what, sizeof what, "--mesh %s", o->glass[i].mesh);
        if (!check_params(&o->glass[i], what)) return 0;
    }
    if (o->scene_file && (o->glass_count > 0 || o->opaque_count > 0 || o->orbit > 0))
        return usage_error("--scene %s gives the objects; it does not combine with --mesh or --opaque%s", o->scene_file, "");
    if (o->view_given != o->projection_given)
        return usage_error("--view and --projection go together%s%s", "", "");
    if (o->view_given && (o->camera_given || o->fov_given))
        return usage_error("--view and --projection give the whole camera; --camera and --fov do not combine "
                           "with them%s%s", "", "");
    if ((o->under_file || o->reference) && !o->panels_file)
        return usage_error("%s draws glass panels: give --panels FILE%s", o->under_file ? "--under" : "--reference", "");
    if (o->under_file && (o->scene_file || o->glass_count > 0 || o->opaque_count > 0 || o->orbit > 0))
        return usage_error("--under draws its picture over the whole frame, panels over it: no --scene, --mesh or "
                           "--opaque with it%s%s", "", "");
    if (o->panels_file && o->trace_count)
        return usage_error("--trace-pixel traces the scene, not its panels: not with --panels%s%s", "", "");
    if (o->glass_count > 0 && o->base.placed) {
        fprintf(stderr, PROG ": --place before the first --mesh places nothing when --mesh is given; put it after "
                        "the --mesh it moves\n");
        return 0;
    }
    return 1;
}
