/* SPDX-License-Identifier: MIT */
/* registry.c — the method registry: every kernel is one entry of g_methods
 * (in cost order); AUTO walks it, CLIs list its names and parameters, and
 * the generic parameter code below resolves and validates each method's
 * nested struct from its snell_param_info table. Adding a method: its file
 * under src/methods/, its shaders, its tests, and one line here. */
#include "frame/method.h"
#include "frame/material.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The registry: one line M(name, NAME) per method, in cost order where it
 * is adequate (AUTO takes the first adequate one): layered is adequate only
 * on convex meshes, where it costs less than the cubemap (layered.c
 * DEFAULT_CONVEX_STEPS), so it comes before it; on concave meshes AUTO
 * passes it by. cmake/components.cmake reads these lines:
 * each method but single and cubemap becomes an option SNELL_WITH_<NAME>,
 * and the entry of one built without is left out here (SNELL__BUILT_<name>,
 * snell_components.h). */
#define SNELL__REGISTRY(M) \
    M(single, SINGLE)      \
    M(layered, LAYERED)    \
    M(cubemap, CUBEMAP)    \
    M(wyman, WYMAN)        \
    M(oliveira, OLIVEIRA)  \
    M(peel, PEEL)          \
    M(exact, EXACT)        \
    M(hybrid, HYBRID)

/* SNELL__IF_<0|1>(x): x when built. Two levels so that SNELL__BUILT_<name>
 * expands to its value before it is pasted. */
#define SNELL__IF_0(...)
#define SNELL__IF_1(...) __VA_ARGS__
#define SNELL__IF(flag, ...) SNELL__IF_(flag, __VA_ARGS__)
#define SNELL__IF_(flag, ...) SNELL__IF_##flag(__VA_ARGS__)

#define DECLARE(name, NAME) SNELL__IF(SNELL__BUILT_##name, extern const snell__method snell__method_##name;)
SNELL__REGISTRY(DECLARE)
#undef DECLARE

#define ENTRY(name, NAME) SNELL__IF(SNELL__BUILT_##name, &snell__method_##name, )
static const snell__method *const g_methods[] = {SNELL__REGISTRY(ENTRY)};
#undef ENTRY

/* Every method of the enum, built or not, for messages about those left out. */
#define NAME_OF(name, NAME) {SNELL_METHOD_##NAME, #name, "SNELL_WITH_" #NAME},
static const struct {
    snell_method id;
    const char *name, *option;
} g_all_methods[] = {SNELL__REGISTRY(NAME_OF)};
#undef NAME_OF
#define ALL_METHOD_COUNT ((int)(sizeof g_all_methods / sizeof *g_all_methods))

#define METHOD_COUNT ((int)(sizeof g_methods / sizeof *g_methods))

const char *const snell__back_detail_names[3] = {"default", "auto", "full"};
const char *const snell__fresnel_names[3] = {"default", "schlick", "exact"};
const char *const snell__inner_fresnel_names[3] = {"auto", "off", "on"};

int snell_method_count(void) { return METHOD_COUNT; }

const snell_method_info *snell_method_info_at(int i)
{
    return i >= 0 && i < METHOD_COUNT ? g_methods[i]->info : NULL;
}

const snell__method *snell__method_get(snell_method id)
{
    int i;
    for (i = 0; i < METHOD_COUNT; i++)
        if (g_methods[i]->info->method == id) return g_methods[i];
    return NULL;
}

snell_status snell__method_unbuilt(snell_method id, const char *who)
{
    int i;
    for (i = 0; i < ALL_METHOD_COUNT; i++)
        if (g_all_methods[i].id == id)
            return snell__fail(NULL, SNELL_E_UNSUPPORTED, "%smethod %s: built without %s (configure with -D%s=ON)", who,
                               g_all_methods[i].name, g_all_methods[i].option, g_all_methods[i].option);
    return snell__fail(NULL, SNELL_E_INVALID_ARG, "%sunknown method %d", who, (int)id);
}

const snell_method_info *snell_method_info_of(snell_method m)
{
    const snell__method *e = snell__method_get(m);
    return e ? e->info : NULL;
}

const char *snell_method_str(snell_method m)
{
    const snell_method_info *i = snell_method_info_of(m);
    if (m == SNELL_METHOD_AUTO) return "auto";
    return i ? i->name : "unknown";
}

snell_status snell_method_from_str(const char *name, snell_method *out)
{
    int i;
    if (!name || !out) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_method_from_str: NULL argument");
    if (strcmp(name, "auto") == 0) {
        *out = SNELL_METHOD_AUTO;
        return SNELL_OK;
    }
    for (i = 0; i < METHOD_COUNT; i++)
        if (strcmp(name, g_methods[i]->info->name) == 0) {
            *out = g_methods[i]->info->method;
            return SNELL_OK;
        }
    for (i = 0; i < ALL_METHOD_COUNT; i++)
        if (strcmp(name, g_all_methods[i].name) == 0) return snell__method_unbuilt(g_all_methods[i].id, "");
    return snell__fail(NULL, SNELL_E_INVALID_ARG, "unknown method \"%s\"", name);
}

static int *param_ptr(snell_glass_material *m, const snell__method *e, int i)
{
    return (int *)((char *)m + e->info->params[i].offset);
}

/* Zero = default, filled first; then the resolved value must lie in min..max. */
static snell_status params_resolve(const snell__method *e, snell_glass_material *m, int object)
{
    int i;
    for (i = 0; i < e->info->param_count; i++) {
        const snell_param_info *p = &e->info->params[i];
        int *v = param_ptr(m, e, i);
        if (*v == 0) *v = p->def;
        if (*v < p->min || *v > p->max)
            return snell__fail(NULL, SNELL_E_INVALID_ARG, "glass %d: %s.%s = %d outside %d..%d", object,
                               e->info->name, p->name, *v, p->min, p->max);
    }
    return SNELL_OK;
}

snell_status snell__glass_resolve_all(const snell_glass_material *in, int object, snell_glass_resolved *out)
{
    snell_glass_material *m = &out->material;
    snell_status st = snell__glass_resolve(in, object, out);
    int i;
    if (st != SNELL_OK) return st;
    if (m->method != SNELL_METHOD_AUTO && !snell__method_get(m->method)) {
        char who[32];
        snprintf(who, sizeof who, "glass %d: ", object);
        return snell__method_unbuilt(m->method, who);
    }
    for (i = 0; i < METHOD_COUNT && st == SNELL_OK; i++) st = params_resolve(g_methods[i], m, object);
    return st;
}

snell_status snell_glass_defaults(const snell_glass_material *in, snell_glass_resolved *out)
{
    if (!out) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_defaults: out is NULL");
    return snell__glass_resolve_all(in, 0, out);
}

snell_status snell_glass_set_param(snell_glass_material *m, snell_method method, const char *name,
                                   const char *value)
{
    const snell__method *e = snell__method_get(method);
    int i, j;
    if (!m || !name || !value) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_set_param: NULL argument");
    if (!e) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_set_param: method %s has no parameters",
                               snell_method_str(method));
    for (i = 0; i < e->info->param_count; i++) {
        const snell_param_info *p = &e->info->params[i];
        char *end;
        long v;
        if (strcmp(p->name, name) != 0) continue;
        if (p->value_names)
            for (j = 0; j <= p->max - p->min; j++)
                if (strcmp(p->value_names[j], value) == 0) {
                    *param_ptr(m, e, i) = p->min + j;
                    return SNELL_OK;
                }
        v = strtol(value, &end, 10);
        if (end == value || *end || v < p->min || v > p->max) {
            char names[128] = "";
            size_t n = 0;
            for (j = 0; p->value_names && j <= p->max - p->min && n < sizeof names; j++)
                n += (size_t)snprintf(names + n, sizeof names - n, "%s%s", j ? "|" : " or ", p->value_names[j]);
            return snell__fail(NULL, SNELL_E_INVALID_ARG, "%s.%s: \"%s\" is not a value in %d..%d%s", e->info->name,
                               p->name, value, p->min, p->max, names);
        }
        *param_ptr(m, e, i) = (int)v;
        return SNELL_OK;
    }
    return snell__fail(NULL, SNELL_E_INVALID_ARG, "method %s has no parameter \"%s\"", e->info->name, name);
}

snell_status snell_glass_get_param(const snell_glass_material *m, snell_method method, const char *name, int *value)
{
    const snell__method *e = snell__method_get(method);
    int i;
    if (!m || !name || !value) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_glass_get_param: NULL argument");
    if (!e) return snell__method_unbuilt(method, "snell_glass_get_param: ");
    for (i = 0; i < e->info->param_count; i++)
        if (strcmp(e->info->params[i].name, name) == 0) {
            *value = *param_ptr((snell_glass_material *)m, e, i);
            return SNELL_OK;
        }
    return snell__fail(NULL, SNELL_E_INVALID_ARG, "method %s has no parameter \"%s\"", e->info->name, name);
}

void snell_glass_copy_method_params(snell_glass_material *dst, const snell_glass_material *src)
{
    int i, j;
    if (!dst || !src) return;
    for (i = 0; i < METHOD_COUNT; i++)
        for (j = 0; j < g_methods[i]->info->param_count; j++)
            *param_ptr(dst, g_methods[i], j) = *param_ptr((snell_glass_material *)src, g_methods[i], j);
}

int snell_object_counter(const snell_object_stats *st, const char *name)
{
    const snell_method_info *info = st ? snell_method_info_of(st->method_used) : NULL;
    int i;
    if (!info || !name) return -1;
    for (i = 0; i < info->counter_count && i < SNELL_MAX_METHOD_COUNTERS; i++)
        if (strcmp(info->counters[i].name, name) == 0) return st->counters[i];
    return -1;
}
