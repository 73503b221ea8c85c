/* SPDX-License-Identifier: MIT */
/* cli_panels.c — the ports' panels file (cli_panels.h). */
#include "cli_panels.h"
#include "cli_input.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_MAX_BYTES 1024 /* a full line of every key is about 300 */

static const char k_keys[] = "center, size, radius, exponent, thickness, bevel, bevel_profile, ior, dispersion, "
                             "frost, tint, rim, light, shadow, group, merge";

/* One field of numbers: its key, where it goes, how many numbers it takes
 * (1..4: radius also takes one for every corner) and their form. */
typedef struct field {
    const char *key;
    size_t offset;
    int count;
    const char *form;
} field;

static const field k_fields[] = {{"center", offsetof(snell_panel, center), 2, "X,Y"},
                                 {"size", offsetof(snell_panel, size), 2, "W,H"},
                                 {"radius", offsetof(snell_panel, radius), 4, "R or R0,R1,R2,R3"},
                                 {"exponent", offsetof(snell_panel, exponent), 1, "a number"},
                                 {"thickness", offsetof(snell_panel, thickness), 1, "a number"},
                                 {"bevel", offsetof(snell_panel, bevel), 1, "a number"},
                                 {"ior", offsetof(snell_panel, ior), 1, "a number"},
                                 {"dispersion", offsetof(snell_panel, dispersion), 1, "a number"},
                                 {"frost", offsetof(snell_panel, frost), 1, "a number"},
                                 {"tint", offsetof(snell_panel, tint), 4, "R,G,B,A"},
                                 {"rim", offsetof(snell_panel, rim), 1, "a number"},
                                 {"light", offsetof(snell_panel, light), 3, "X,Y,Z"},
                                 {"shadow", offsetof(snell_panel, shadow), 4, "RADIUS,OPACITY,DX,DY or none"},
                                 {"merge", offsetof(snell_panel, merge), 1, "a number"}};
#define SEEN_PROFILE (1u << 14)
#define SEEN_GROUP (1u << 15)

static int bad(char *why, size_t n, const char *name, int line, const char *fmt, ...)
{
    char detail[256], safe[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(detail, sizeof detail, fmt, ap);
    va_end(ap);
    snprintf(why, n, "%s line %d: %s", cli_safe(name, safe, sizeof safe), line, detail);
    return 0;
}

/* Up to max comma-separated finite numbers, the whole of s; their count, or -1. */
static int numbers(const char *s, float *out, int max)
{
    int k = 0;
    for (;;) {
        char *end;
        if (k == max) return -1;
        errno = 0;
        out[k] = strtof(s, &end);
        if (end == s || errno || !isfinite(out[k])) return -1;
        k++;
        if (*end == '\0') return k;
        if (*end != ',') return -1;
        s = end + 1;
    }
}

/* key=value into p; 0 with the reason. */
static int set_field(snell_panel *p, const char *key, const char *value, unsigned *seen, char *why, size_t n,
                     const char *name, int line)
{
    char safe[64];
    float v[4];
    size_t k;
    int count;
    for (k = 0; k < sizeof k_fields / sizeof *k_fields; k++) {
        const field *f = &k_fields[k];
        if (strcmp(key, f->key)) continue;
        if (*seen & (1u << k)) return bad(why, n, name, line, "%s given twice", key);
        *seen |= 1u << k;
        if (!strcmp(key, "shadow") && !strcmp(value, "none")) {
            p->shadow[0] = -1.0f;
            return 1;
        }
        count = numbers(value, v, 4);
        if (count == 1 && !strcmp(key, "radius")) v[1] = v[2] = v[3] = v[0], count = 4; /* every corner */
        if (count != f->count)
            return bad(why, n, name, line, "%s wants %s (finite), got '%s'", key, f->form,
                       cli_safe(value, safe, sizeof safe));
        memcpy((char *)p + f->offset, v, sizeof(float) * (size_t)f->count);
        return 1;
    }
    if (!strcmp(key, "bevel_profile")) {
        if (*seen & SEEN_PROFILE) return bad(why, n, name, line, "%s given twice", key);
        *seen |= SEEN_PROFILE;
        if (!strcmp(value, "circular"))
            p->bevel_profile = SNELL_PANEL_BEVEL_CIRCULAR;
        else if (!strcmp(value, "squircle"))
            p->bevel_profile = SNELL_PANEL_BEVEL_SQUIRCLE;
        else
            return bad(why, n, name, line, "bevel_profile wants circular or squircle, got '%s'",
                       cli_safe(value, safe, sizeof safe));
        return 1;
    }
    if (!strcmp(key, "group")) {
        char *end;
        long g;
        if (*seen & SEEN_GROUP) return bad(why, n, name, line, "%s given twice", key);
        *seen |= SEEN_GROUP;
        errno = 0;
        g = strtol(value, &end, 10);
        if (end == value || *end || errno || g < 0 || g > 1000000)
            return bad(why, n, name, line, "group wants an integer >= 0, got '%s'", cli_safe(value, safe, sizeof safe));
        p->group = (int)g;
        return 1;
    }
    return bad(why, n, name, line, "unknown key '%s' (%s)", cli_safe(key, safe, sizeof safe), k_keys);
}

/* One line's text (comment and ends stripped, not empty) into p. */
static int parse_line(char *s, snell_panel *p, char *why, size_t n, const char *name, int line)
{
    unsigned seen = 0;
    char safe[64];
    memset(p, 0, sizeof *p);
    while (*s) {
        char *tok = s, *eq;
        s += strcspn(s, " \t");
        if (*s) *s++ = '\0';
        s += strspn(s, " \t");
        if (!(eq = strchr(tok, '=')) || eq == tok || !eq[1])
            return bad(why, n, name, line, "'%s' is not key=value", cli_safe(tok, safe, sizeof safe));
        *eq = '\0';
        if (!set_field(p, tok, eq + 1, &seen, why, n, name, line)) return 0;
    }
    if (!(seen & 1u)) return bad(why, n, name, line, "a panel needs center=X,Y (pixels from the bottom-left)");
    if (!(seen & 2u)) return bad(why, n, name, line, "a panel needs size=W,H (pixels)");
    return 1;
}

int cli_panels_parse(const char *text, const char *name, cli_panels *out, char *why, size_t why_size)
{
    int line = 0, cap = 0;
    memset(out, 0, sizeof *out);
    while (*text) {
        size_t len = strcspn(text, "\n");
        char buf[LINE_MAX_BYTES + 1], *s, *end;
        line++;
        if (len > LINE_MAX_BYTES) {
            cli_panels_free(out);
            return bad(why, why_size, name, line, "longer than %d bytes", LINE_MAX_BYTES);
        }
        memcpy(buf, text, len);
        buf[len] = '\0';
        text += len + (text[len] == '\n');
        if ((s = strchr(buf, '#'))) *s = '\0';
        s = buf + strspn(buf, " \t\r");
        end = s + strlen(s);
        while (end > s && strchr(" \t\r", end[-1])) *--end = '\0';
        if (!*s) continue;
        if (cli_has_control(s)) {
            cli_panels_free(out);
            return bad(why, why_size, name, line, "a control character");
        }
        if (out->count == SNELL_MAX_PANELS) {
            cli_panels_free(out);
            return bad(why, why_size, name, line, "more than %d panels (SNELL_MAX_PANELS)", SNELL_MAX_PANELS);
        }
        if (out->count == cap) {
            int grow = cap ? 2 * cap : 16;
            snell_panel *p = (snell_panel *)realloc(out->panels, sizeof *p * (size_t)grow);
            int *l = p ? (int *)realloc(out->lines, sizeof *l * (size_t)grow) : NULL;
            if (p) out->panels = p;
            if (l) out->lines = l;
            if (!p || !l) {
                cli_panels_free(out);
                return bad(why, why_size, name, line, "out of memory");
            }
            cap = grow;
        }
        if (!parse_line(s, &out->panels[out->count], why, why_size, name, line)) {
            cli_panels_free(out);
            return 0;
        }
        out->lines[out->count++] = line;
    }
    if (!out->count) {
        char safe[256];
        snprintf(why, why_size, "%s: no panels (one a line: center=X,Y size=W,H ...)",
                 cli_safe(name, safe, sizeof safe));
        return 0;
    }
    return 1;
}

int cli_panels_read(const char *path, cli_panels *out, char *why, size_t why_size)
{
    char reason[128], safe[256];
    size_t len;
    char *text = cli_read_input(path, CLI_PANELS_MAX_BYTES, &len, reason, sizeof reason);
    int ok;
    memset(out, 0, sizeof *out);
    if (!text) {
        snprintf(why, why_size, "%s: %s", cli_safe(path, safe, sizeof safe), reason);
        return 0;
    }
    if (strlen(text) != len) {
        free(text);
        snprintf(why, why_size, "%s: a NUL byte: not a text file", cli_safe(path, safe, sizeof safe));
        return 0;
    }
    ok = cli_panels_parse(text, path, out, why, why_size);
    free(text);
    return ok;
}

const char *cli_panels_where(const cli_panels *p, const char *name, const char *msg, char *buf, size_t n)
{
    const char *at = msg ? strstr(msg, "panels[") : NULL;
    char safe[256];
    int i;
    buf[0] = '\0';
    if (at && sscanf(at, "panels[%d]", &i) == 1 && i >= 0 && i < p->count)
        snprintf(buf, n, " (line %d of %s)", p->lines[i], cli_safe(name, safe, sizeof safe));
    return buf;
}

void cli_panels_free(cli_panels *p)
{
    free(p->panels);
    free(p->lines);
    memset(p, 0, sizeof *p);
}
