/* SPDX-License-Identifier: MIT */
/* test_bench_keys — every key snell-bench's spec parser accepts changes the
 * configuration it names, and nothing else (issue 25 item 4: peel:layers=
 * once set the frame's scene layers, because the common keys were looked up
 * before the method's parameters, so a peel sweep measured one configuration
 * three times without a word). A CPU test of ports/cli/bench_spec.c.
 *
 * For every method of the registry (snell_method_info_at):
 *  - each common key (bench_spec_key_name) with a non-default value from the
 *    table below: the bytes of the bench_config that differ from the one
 *    parsed without the key lie in the fields the table names for it, and the
 *    fields it must change did change (the canonical spec string aside);
 *  - each of the method's parameters (info->params) with a value other than
 *    its default and other than 0: exactly the bytes snell_glass_set_param
 *    writes for it in a zeroed material changed, inside bench_config.glass
 *    (plus the MATCHED reference's cap for "max_interfaces", which the bench
 *    derives from it), and snell_glass_get_param reads the value back;
 *  - an integer parameter whose range holds 0 but whose default is not 0
 *    (oliveira and peel linear_steps, guard_band): the library reads 0 as
 *    "the default" (snell_glass_material: zero = default), so "=0" cannot ask
 *    for 0; the bench must refuse it rather than run the default under the
 *    name 0;
 *  - no method parameter carries a common key's name (one of the two would be
 *    unreachable for that method);
 *  - the method's default sweep expands and holds no configuration twice.
 * A common key without a case in the table fails, so a new key brings its case. */
#include "bench.h"
#include "test_util.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

typedef struct field {
    size_t off, size;
} field;

#define F(member) {offsetof(bench_config, member), sizeof(((bench_config *)0)->member)}
#define NONE {0, 0}

typedef struct common_case {
    const char *key, *value;
    field must[3];  /* fields the key must change (size 0: unused) */
    field may[1];   /* fields that follow from it by design */
} common_case;

static const common_case g_cases[] = {
    /* the orbit camera is the scene's own unless camera= is given */
    {"scene", "torus", {F(scene), NONE, NONE}, {F(cam)}},
    {"size", "64x32", {F(width), F(height), NONE}, {NONE}},
    {"ior", "1.33", {F(glass.ior), NONE, NONE}, {NONE}},
    /* snell_glass_set_absorption stores glTF's form: colour after a distance */
    {"absorption", "0.5", {F(glass.attenuation_color), F(glass.attenuation_distance), NONE}, {NONE}},
    {"attenuation", "0.5/0.6/0.7/2", {F(glass.attenuation_color), F(glass.attenuation_distance), NONE}, {NONE}},
    {"thickness", "0.1", {F(glass.thickness), NONE, NONE}, {NONE}},
    {"tint", "0.5/0.6/0.7", {F(glass.tint), NONE, NONE}, {NONE}},
    {"dispersion", "0.31", {F(glass.dispersion), NONE, NONE}, {NONE}},
    {"dispersion_model", "per-channel", {F(glass.dispersion_model), NONE, NONE}, {NONE}},
    {"scale", "2", {F(glass.scale), NONE, NONE}, {NONE}},
    {"camera", "10/40/5", {F(cam), F(cam_set), NONE}, {NONE}},
    {"shading", "forward", {F(shading), NONE, NONE}, {NONE}},
    {"ssaa", "2", {F(ssaa), NONE, NONE}, {NONE}},
    {"msaa", "4", {F(msaa), NONE, NONE}, {NONE}},
    {"refine", "16", {F(refine), NONE, NONE}, {NONE}},
    {"lod", "0.5", {F(lod), NONE, NONE}, {NONE}},
    {"spin", "2", {F(spin), NONE, NONE}, {NONE}},
    {"scene_layers", "-1", {F(scene_layers), NONE, NONE}, {NONE}},
    {"methods", "single/cubemap", {F(object_methods), F(object_method_count), NONE}, {NONE}},
};
#define CASE_COUNT ((int)(sizeof g_cases / sizeof *g_cases))

static bench_options g_opt;
static bench_config *g_base, *g_test;

static int in_field(size_t i, field f) { return f.size && i >= f.off && i < f.off + f.size; }

/* Parses spec alone into *out (one configuration); 0 if the parser refused it. */
static int parse_one(const char *spec, bench_config *out)
{
    static bench_config cs[4];
    int n = 0;
    if (!bench_expand_spec(spec, &g_opt, cs, &n)) return 0;
    CHECK(n == 1, "%s: %d configurations, want 1", spec, n);
    memcpy(out, &cs[0], sizeof *out); /* padding too: the comparison is bytewise */
    return n == 1;
}

/* Bytes of a and b that differ, outside spec[], must lie in must[] or may[];
 * each of must[] must hold a difference. */
static void check_diff(const char *spec, const bench_config *a, const bench_config *b, const field *must, int nmust,
                       const field *may, int nmay)
{
    const unsigned char *pa = (const unsigned char *)a, *pb = (const unsigned char *)b;
    const field spec_f = F(spec);
    int changed[4] = {0, 0, 0, 0}, k, stray = 0;
    size_t i, first_stray = 0;
    for (i = 0; i < sizeof *a; i++) {
        int allowed = 0;
        if (pa[i] == pb[i] || in_field(i, spec_f)) continue;
        for (k = 0; k < nmust; k++)
            if (in_field(i, must[k])) changed[k] = allowed = 1;
        for (k = 0; k < nmay; k++)
            if (in_field(i, may[k])) allowed = 1;
        if (!allowed && !stray++) first_stray = i;
    }
    CHECK(stray == 0, "%s: %d byte(s) changed outside the named field(s), the first at offset %zu of bench_config "
                      "(scene_layers at %zu, glass at %zu)",
          spec, stray, first_stray, offsetof(bench_config, scene_layers), offsetof(bench_config, glass));
    for (k = 0; k < nmust; k++)
        CHECK(changed[k], "%s: the field at offset %zu (%zu bytes) did not change", spec, must[k].off, must[k].size);
}

static void common_keys(const snell_method_info *m)
{
    int k, c;
    for (k = 0; k < bench_spec_key_count(); k++) {
        const char *key = bench_spec_key_name(k);
        char spec[256];
        int nmust = 0;
        for (c = 0; c < CASE_COUNT && strcmp(g_cases[c].key, key); c++) {}
        if (c == CASE_COUNT) {
            CHECK(0, "common key %s: no case in tests/test_bench_keys.c's table", key);
            continue;
        }
        while (nmust < 3 && g_cases[c].must[nmust].size) nmust++;
        snprintf(spec, sizeof spec, "%s:%s=%s", m->name, key, g_cases[c].value);
        if (!parse_one(m->name, g_base)) {
            CHECK(0, "%s: refused", m->name);
            return;
        }
        if (!parse_one(spec, g_test)) {
            CHECK(0, "%s: refused", spec);
            continue;
        }
        check_diff(spec, g_base, g_test, g_cases[c].must, nmust, g_cases[c].may, g_cases[c].may[0].size ? 1 : 0);
    }
    /* and every case names a key the parser has (a renamed key leaves none behind) */
    for (c = 0; c < CASE_COUNT; c++) {
        int found = 0;
        for (k = 0; k < bench_spec_key_count(); k++) found |= !strcmp(bench_spec_key_name(k), g_cases[c].key);
        CHECK(found, "the table's key %s is not one the parser accepts", g_cases[c].key);
    }
}

/* A value of p other than its default and other than 0 (0 = default). */
static const char *other_value(const snell_param_info *p, char *buf, size_t n)
{
    int v;
    if (p->value_names) {
        for (v = p->min; v <= p->max; v++)
            if (v != p->def && v != 0) return p->value_names[v - p->min];
        return NULL;
    }
    if (p->def + 1 <= p->max && p->def + 1 != 0) v = p->def + 1;
    else if (p->def - 1 >= p->min && p->def - 1 != 0) v = p->def - 1;
    else return NULL;
    snprintf(buf, n, "%d", v);
    return buf;
}

/* The bytes snell_glass_set_param writes for (m, p, value) in a zeroed
 * material: where the bench must write it, independent of the bench. */
static field param_field(const snell_method_info *m, const snell_param_info *p, const char *value)
{
    snell_glass_material z, s;
    const unsigned char *a = (const unsigned char *)&z, *b = (const unsigned char *)&s;
    size_t i, lo = sizeof z, hi = 0;
    field f = {0, 0};
    memset(&z, 0, sizeof z);
    s = z;
    if (snell_glass_set_param(&s, m->method, p->name, value) != SNELL_OK) return f;
    for (i = 0; i < sizeof z; i++)
        if (a[i] != b[i]) {
            if (i < lo) lo = i;
            hi = i + 1;
        }
    if (hi == 0 || hi - lo > sizeof(int)) return f;
    /* the whole int the value lives in (snell_param_info: integer parameters) */
    lo -= lo % sizeof(int);
    f.off = offsetof(bench_config, glass) + lo;
    f.size = sizeof(int);
    return f;
}

static void method_params(const snell_method_info *m)
{
    int k, j;
    for (k = 0; k < m->param_count; k++) {
        const snell_param_info *p = &m->params[k];
        char buf[32], spec[256];
        const char *value = other_value(p, buf, sizeof buf);
        field must[1], may[1] = {F(ref_interfaces)};
        int got = 0;
        for (j = 0; j < bench_spec_key_count(); j++)
            CHECK(strcmp(bench_spec_key_name(j), p->name) != 0,
                  "method %s's parameter %s has the name of a common bench key: one of them is unreachable",
                  m->name, p->name);
        if (!value) {
            printf("%s %s: no value other than the default to set\n", m->name, p->name);
            continue;
        }
        must[0] = param_field(m, p, value);
        CHECK(must[0].size > 0, "%s %s=%s: snell_glass_set_param wrote nothing", m->name, p->name, value);
        snprintf(spec, sizeof spec, "%s:%s=%s", m->name, p->name, value);
        if (!parse_one(m->name, g_base) || !parse_one(spec, g_test)) {
            CHECK(0, "%s: refused", spec);
            continue;
        }
        /* the parameters the reference's model follows: its cap, exact's terms */
        if (m->method == SNELL_METHOD_EXACT && strcmp(p->name, "max_interfaces") != 0) may[0] = (field)F(ref_terms);
        check_diff(spec, g_base, g_test, must, 1, may,
                   strcmp(p->name, "max_interfaces") == 0 || (m->method == SNELL_METHOD_EXACT &&
                   (!strcmp(p->name, "fresnel") || !strcmp(p->name, "inner_fresnel") || !strcmp(p->name, "reentry"))));
        CHECK_OK(snell_glass_get_param(&g_test->glass, m->method, p->name, &got));
        printf("%-22s -> %s.%s = %d\n", spec, m->name, p->name, got);

        /* "=0" for an integer whose 0 the library resolves to another default */
        if (!p->value_names && p->min <= 0 && p->max >= 0) {
            snprintf(spec, sizeof spec, "%s:%s=0", m->name, p->name);
            if (p->def != 0) {
                int accepted = parse_one(spec, g_test);
                CHECK(!accepted, "%s: accepted, but the library runs its default %d for 0", spec, p->def);
                if (!accepted) printf("%-22s refused (0 resolves to the default %d)\n", spec, p->def);
            } else {
                CHECK(parse_one(spec, g_test), "%s: refused, but 0 is its default", spec);
            }
        }
    }
}

/* The registry's default sweep, as the bench runs it (bench_default_sweep):
 * it expands, and no two of its configurations are the same one under two
 * names (oliveira's linear_steps=0,8,16 was 8, 8, 16). */
static void default_sweep(const snell_method_info *m)
{
    static bench_config cs[64];
    const char *sweep = bench_default_sweep(m);
    const field spec_f = F(spec);
    char spec[1100];
    int n = 0, i, j;
    snprintf(spec, sizeof spec, "%s%s%s", m->name, *sweep ? ":" : "", sweep);
    if (!bench_expand_spec(spec, &g_opt, cs, &n)) {
        CHECK(0, "%s's default sweep %s: refused", m->name, spec);
        return;
    }
    printf("%s's default sweep: %s (%d configurations)\n", m->name, spec, n);
    for (i = 0; i < n; i++)
        for (j = i + 1; j < n; j++) {
            bench_config a = cs[i], b = cs[j];
            memset((char *)&a + spec_f.off, 0, spec_f.size);
            memset((char *)&b + spec_f.off, 0, spec_f.size);
            CHECK(memcmp(&a, &b, sizeof a) != 0, "%s's default sweep: %s and %s are one configuration", m->name,
                  cs[i].spec, cs[j].spec);
        }
}

int main(void)
{
    int i;
    memset(&g_opt, 0, sizeof g_opt);
    strcpy(g_opt.scenes, "sphere");
    strcpy(g_opt.sizes, "256x256");
    g_base = (bench_config *)calloc(1, sizeof *g_base);
    g_test = (bench_config *)calloc(1, sizeof *g_test);
    if (!g_base || !g_test) return 1;
    CHECK(snell_method_count() > 0, "an empty registry");
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *m = snell_method_info_at(i);
        common_keys(m);
        method_params(m);
        default_sweep(m);
    }
    free(g_base);
    free(g_test);
    return test_finish();
}
