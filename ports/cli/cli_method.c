/* SPDX-License-Identifier: MIT */
/* cli_method.c — method names and parameters from the library's registry. */
#include "cli_method.h"

#include <string.h>

int cli_method_parse(const char *prog, const char *name, snell_method *out)
{
    int i;
    if (snell_method_from_str(name, out) == SNELL_OK) return 1;
    fprintf(stderr, "%s: unknown method '%s'; methods: auto", prog, name);
    for (i = 0; i < snell_method_count(); i++) fprintf(stderr, ", %s", snell_method_info_at(i)->name);
    fprintf(stderr, "\n");
    return 0;
}

const snell_method_info *cli_param_owner(const char *name, int *start)
{
    int i, k;
    for (i = *start; i < snell_method_count(); i++) {
        const snell_method_info *mi = snell_method_info_at(i);
        for (k = 0; k < mi->param_count; k++)
            if (!strcmp(mi->params[k].name, name)) {
                *start = i + 1;
                return mi;
            }
    }
    *start = i;
    return NULL;
}

/* "default|plain|oct" for an enum parameter, "" otherwise. */
static void value_names(const snell_param_info *p, char *buf, size_t n)
{
    size_t len = 0;
    int v;
    buf[0] = '\0';
    for (v = p->min; p->value_names && v <= p->max && len < n; v++)
        len += (size_t)snprintf(buf + len, n - len, "%s%s", v > p->min ? "|" : "", p->value_names[v - p->min]);
}

int cli_param_set_one(const char *prog, snell_glass_material *m, snell_method method, const char *name,
                      const char *value)
{
    /* the library's message names the range and any value names */
    if (snell_glass_set_param(m, method, name, value) == SNELL_OK) return 1;
    fprintf(stderr, "%s: %s\n", prog, snell_last_error(NULL));
    return 0;
}

int cli_param_set(const char *prog, snell_glass_material *m, const char *name, const char *value)
{
    const snell_method_info *mi;
    int at = 0, found = 0;
    while ((mi = cli_param_owner(name, &at)) != NULL) {
        found = 1;
        if (!cli_param_set_one(prog, m, mi->method, name, value)) return 0;
    }
    if (!found) fprintf(stderr, "%s: no method has a parameter '%s'\n", prog, name);
    return found;
}

const char *cli_param_value_str(const snell_param_info *p, int value, char *buf, size_t n)
{
    if (p->value_names && value >= p->min && value <= p->max) return p->value_names[value - p->min];
    snprintf(buf, n, "%d", value);
    return buf;
}

/* Writes text from column `column` on, broken at spaces before column 104. */
static void wrap(FILE *f, const char *text, int column)
{
    const int width = 104 - column;
    while ((int)strlen(text) > width) {
        int cut = width;
        while (cut > 0 && text[cut] != ' ') cut--;
        if (cut == 0) break;
        fprintf(f, "%.*s\n%*s", cut, text, column, "");
        text += cut + 1;
    }
    fprintf(f, "%s\n", text);
}

void cli_method_help(FILE *f, const char *indent, const char *prefix, const char *suffix)
{
    int i, k;
    for (i = 0; i < snell_method_count(); i++) {
        const snell_method_info *mi = snell_method_info_at(i);
        fprintf(f, "%smethod %s: %s\n%s  needs: %s\n", indent, mi->name, mi->summary, indent, mi->needs);
        for (k = 0; k < mi->param_count; k++) {
            const snell_param_info *p = &mi->params[k];
            char key[64], range[160], def[32], text[512];
            snprintf(key, sizeof key, "%s%s%s", prefix, p->name, suffix);
            if (p->value_names) value_names(p, range, sizeof range);
            else snprintf(range, sizeof range, "%d..%d", p->min, p->max);
            snprintf(text, sizeof text, "%s (default %s): %s", range, cli_param_value_str(p, p->def, def, sizeof def),
                     p->help);
            fprintf(f, "%s  %-20s ", indent, key);
            wrap(f, text, (int)strlen(indent) + 23);
        }
    }
}
