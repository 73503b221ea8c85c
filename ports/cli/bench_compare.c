/* SPDX-License-Identifier: MIT */
/* bench_compare.c — snell-bench --compare A.json B.json: two runs (two boards,
 * two builds, vsync on and off) side by side. Per configuration, matched by
 * its spec: the median and 99th percentile frame time of each, B's median over
 * A's, and the glass PSNR against FULL of each (null where a run measured no
 * error, as snell-kiosk's). The JSON is snell-bench's own (bench_output.c);
 * the reader below knows only as much JSON as it needs to walk it, and every
 * string it prints is scrubbed of control characters (cli_input.h). */
#include "bench.h"
#include "cli_input.h"
#include "cli_opts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------ a minimal JSON walker */
static const char *ws(const char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    return p;
}

/* Past the JSON number at p (RFC 8259: no hex, no leading '+' or '0', no
 * inf or nan, which strtod would take); NULL if there is none. */
static const char *number_end(const char *p)
{
    if (*p == '-') p++;
    if (*p == '0') p++;
    else if (*p >= '1' && *p <= '9') while (*p >= '0' && *p <= '9') p++;
    else return NULL;
    if (*p == '.') {
        if (!(*++p >= '0' && *p <= '9')) return NULL;
        while (*p >= '0' && *p <= '9') p++;
    }
    if (*p == 'e' || *p == 'E') {
        if (*++p == '+' || *p == '-') p++;
        if (!(*p >= '0' && *p <= '9')) return NULL;
        while (*p >= '0' && *p <= '9') p++;
    }
    return p;
}

/* Past the value at p; NULL if it is not JSON. */
static const char *skip(const char *p, int depth)
{
    p = ws(p);
    if (depth > 64) return NULL;
    if (*p == '"') {
        for (p++; *p && *p != '"'; p++)
            if (*p == '\\' && !*++p) return NULL;
        return *p ? p + 1 : NULL;
    }
    if (*p == '{' || *p == '[') {
        char close = *p == '{' ? '}' : ']';
        p = ws(p + 1);
        if (*p == close) return p + 1;
        for (;;) {
            if (close == '}') {
                if (*p != '"' || !(p = skip(p, depth + 1))) return NULL;
                p = ws(p);
                if (*p++ != ':') return NULL;
            }
            if (!(p = skip(p, depth + 1))) return NULL;
            p = ws(p);
            if (*p == close) return p + 1;
            if (*p++ != ',') return NULL;
            p = ws(p);
        }
    }
    if (*p == '-' || (*p >= '0' && *p <= '9')) return number_end(p);
    if (!strncmp(p, "true", 4) || !strncmp(p, "null", 4)) return p + 4;
    if (!strncmp(p, "false", 5)) return p + 5;
    return NULL;
}

/* The value of member key of the object at obj; NULL if none. */
static const char *member(const char *obj, const char *key)
{
    const char *p = obj ? ws(obj) : NULL;
    size_t n = strlen(key);
    if (!p || *p != '{') return NULL;
    p = ws(p + 1);
    while (*p == '"') {
        const char *k = p + 1, *kend, *v;
        if (!(p = skip(p, 0))) return NULL;
        kend = p - 1; /* the key's closing quote */
        p = ws(p);
        if (*p++ != ':') return NULL;
        v = ws(p);
        if ((size_t)(kend - k) == n && !strncmp(k, key, n)) return v;
        if (!(p = skip(v, 0))) return NULL;
        p = ws(p);
        if (*p != ',') return NULL;
        p = ws(p + 1);
    }
    return NULL;
}

static const char *path2(const char *obj, const char *a, const char *b) { return member(member(obj, a), b); }

/* A string value into out ("" if not a string; escapes kept as written,
 * control characters '?'). */
static void str(const char *v, char *out, size_t n)
{
    const char *e;
    out[0] = '\0';
    if (!v || *v != '"' || !(e = skip(v, 0))) return;
    snprintf(out, n, "%.*s", (int)(e - v - 2), v + 1);
    cli_scrub(out);
}

/* A JSON number's value; NAN for anything else (a string, null, "0x10"). */
static double num(const char *v)
{
    const char *e = v && (*v == '-' || (*v >= '0' && *v <= '9')) ? number_end(v) : NULL;
    char *end;
    double x;
    if (!e) return NAN;
    x = strtod(v, &end);
    return end == e ? x : NAN;
}

/* ----------------------------------------------------------- the runs */
/* A JSON file or a count of results above these is no benchmark run (a full
 * sweep writes a few MB and a few thousand results). */
#define COMPARE_MAX_BYTES ((size_t)64 << 20)
#define COMPARE_MAX_RESULTS 200000

typedef struct entry {
    const char *spec; /* its spec's text in the file, escapes as written; "" without one */
    size_t len;
    const char *result; /* the result object */
} entry;

typedef struct run {
    const char *path;
    char *text;
    entry *results;   /* in the file's order */
    entry *by_spec;   /* the same, sorted by spec */
    size_t n;
} run;

static int by_spec(const void *a, const void *b)
{
    const entry *x = (const entry *)a, *y = (const entry *)b;
    int c = memcmp(x->spec, y->spec, x->len < y->len ? x->len : y->len);
    return c ? c : (x->len > y->len) - (x->len < y->len);
}

static void run_free(run *r)
{
    free(r->text);
    free(r->results);
    free(r->by_spec);
}

static int load(run *r, const char *path)
{
    char why[128], safe[256];
    const char *p, *end;
    size_t len, cap = 0;
    memset(r, 0, sizeof *r);
    r->path = path;
    if (!(r->text = cli_read_input(path, COMPARE_MAX_BYTES, &len, why, sizeof why)))
        return fprintf(stderr, "snell-bench --compare: cannot read '%s': %s\n", cli_safe(path, safe, sizeof safe), why),
               0;
    if (!(end = skip(r->text, 0)) || *ws(end)) {
        fprintf(stderr, "snell-bench --compare: '%s' is not JSON\n", cli_safe(path, safe, sizeof safe));
        return 0;
    }
    p = member(r->text, "results");
    if (!p || *p != '[') {
        fprintf(stderr, "snell-bench --compare: '%s' is not a snell-bench JSON (no \"results\" array)\n",
                cli_safe(path, safe, sizeof safe));
        return 0;
    }
    /* one pass over the results; a lookup is then a binary search, not a walk */
    for (p = ws(p + 1); *p == '{';) {
        const char *sp = member(p, "spec"), *se;
        if (r->n == COMPARE_MAX_RESULTS)
            return fprintf(stderr, "snell-bench --compare: '%s' holds more than %d results\n",
                           cli_safe(path, safe, sizeof safe), COMPARE_MAX_RESULTS),
                   0;
        if (r->n == cap) {
            entry *e = (entry *)realloc(r->results, (cap = cap ? 2 * cap : 64) * sizeof *e);
            if (!e) return fprintf(stderr, "snell-bench --compare: out of memory for %zu results\n", cap), 0;
            r->results = e;
        }
        se = sp && *sp == '"' ? skip(sp, 0) : NULL;
        r->results[r->n].spec = se ? sp + 1 : "";
        r->results[r->n].len = se ? (size_t)(se - sp - 2) : 0;
        r->results[r->n++].result = p;
        if (!(p = skip(p, 0))) break;
        p = ws(p);
        if (*p != ',') break;
        p = ws(p + 1);
    }
    if (r->n && !(r->by_spec = (entry *)malloc(r->n * sizeof *r->by_spec)))
        return fprintf(stderr, "snell-bench --compare: out of memory for %zu results\n", r->n), 0;
    if (r->n) {
        memcpy(r->by_spec, r->results, r->n * sizeof *r->by_spec);
        qsort(r->by_spec, r->n, sizeof *r->by_spec, by_spec);
    }
    return 1;
}

/* The result of r with e's spec; NULL if none. */
static const char *find(const run *r, const entry *e)
{
    const entry *hit = r->n ? (const entry *)bsearch(e, r->by_spec, r->n, sizeof *e, by_spec) : NULL;
    return hit ? hit->result : NULL;
}

/* What a run ran on and under; its device and 1-minute load into dev and load. */
static void describe(const char *tag, const run *r, char *dev, size_t dev_n, double *load)
{
    char v[64], c[64], ren[256], gv[128], board[256], kernel[256], vsync[160], tool[64], prof[64], lb[64], la[64];
    char *end;
    str(path2(r->text, "snell", "version"), v, sizeof v);
    str(path2(r->text, "snell", "commit"), c, sizeof c);
    str(path2(r->text, "gl", "renderer"), ren, sizeof ren);
    if (!ren[0]) str(member(r->text, "gl_renderer"), ren, sizeof ren);
    str(path2(r->text, "gl", "version"), gv, sizeof gv);
    str(path2(r->text, "system", "board"), board, sizeof board);
    str(path2(r->text, "system", "kernel"), kernel, sizeof kernel);
    str(member(r->text, "vsync"), vsync, sizeof vsync);
    str(member(r->text, "tool"), tool, sizeof tool);
    str(member(r->text, "device_profile"), prof, sizeof prof);
    str(member(r->text, "loadavg_before"), lb, sizeof lb);
    str(member(r->text, "loadavg_after"), la, sizeof la);
    {
        char safe[256];
        printf("%s: %s (%s, snell %s, commit %s)\n   GL %s | %s | device profile %s\n   board %s | %s\n"
               "   vsync %s\n   load average %s before, %s after\n",
               tag, cli_safe(r->path, safe, sizeof safe), tool[0] ? tool : "?", v[0] ? v : "?", c[0] ? c : "?",
               ren[0] ? ren : "?", gv[0] ? gv : "?", prof[0] ? prof : "none", board[0] ? board : "not stated",
               kernel[0] ? kernel : "?", vsync[0] ? vsync : "?", lb[0] ? lb : "not stated", la[0] ? la : "not stated");
    }
    snprintf(dev, dev_n, "%s | %s | %s", ren, prof[0] ? prof : "none", board);
    *load = strtod(lb, &end);
    if (end == lb) *load = NAN; /* "unknown" or not stated */
}

/* A figure in a 9-character column whatever its size: 1e308 is no 309-digit number. */
static void cell(double v, const char *fmt)
{
    if (!isfinite(v)) printf("%9s", "-");
    else if (fabs(v) >= 1e6) printf(" %8.2g", v);
    else printf(fmt, v);
}

/* One row: the configuration in A and/or B (either may be NULL). */
static void row(const char *a, const char *b)
{
    double am = num(path2(a, "time_ms", "median")), bm = num(path2(b, "time_ms", "median"));
    char spec[512];
    str(member(a ? a : b, "spec"), spec, sizeof spec);
    printf("%-52s", spec);
    cell(am, " %8.2f");
    cell(num(path2(a, "time_ms", "p99")), " %8.2f");
    cell(bm, " %8.2f");
    cell(num(path2(b, "time_ms", "p99")), " %8.2f");
    cell(am > 0 ? bm / am : NAN, " %8.3f");
    cell(num(path2(a, "vs_full", "psnr_glass_db")), " %8.2f");
    cell(num(path2(b, "vs_full", "psnr_glass_db")), " %8.2f");
    printf("\n");
}

int snell_bench_compare_main(int argc, char **argv)
{
    static const struct option longopts[] = {{"compare", no_argument, NULL, 'c'}, {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    run r[2];
    const char *files[2];
    char dev[2][1024];
    double loadavg[2];
    size_t i;
    int c, nfiles = 0;
    if (cli_wants_help(argc, argv)) {
        printf("usage: snell-bench --compare A.json B.json\n"
               "Two snell-bench (or snell-kiosk --bench) runs side by side: what each ran on (snell version\n"
               "and commit, GL renderer and version, device profile, board, kernel, vsync, load average),\n"
               "a warning where the device or the load differ, then per configuration (by spec) the median\n"
               "and p99 frame time in each, B's median over A's, and the glass PSNR vs FULL in each ('-'\n"
               "where a run has no such figure or no such configuration). Files of at most 64 MiB.\n");
        return 0;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --compare", "--compare --help", argc, argv, "h", longopts)) != -1)
        if (c == '?') return 2;
    for (; optind < argc; optind++) {
        if (nfiles == 2) {
            char safe[256];
            fprintf(stderr, "snell-bench --compare: two JSON files, got a third ('%s')\n",
                    cli_safe(argv[optind], safe, sizeof safe));
            return 2;
        }
        files[nfiles++] = argv[optind];
    }
    if (nfiles != 2) {
        fprintf(stderr, "snell-bench --compare: wants two JSON files, A.json B.json\n");
        return 2;
    }
    if (!load(&r[0], files[0])) {
        run_free(&r[0]);
        return 1;
    }
    if (!load(&r[1], files[1])) {
        run_free(&r[0]);
        run_free(&r[1]);
        return 1;
    }
    describe("A", &r[0], dev[0], sizeof dev[0], &loadavg[0]);
    describe("B", &r[1], dev[1], sizeof dev[1], &loadavg[1]);
    if (strcmp(dev[0], dev[1]))
        printf("warning: the runs differ in GL renderer, device profile or board: B/A compares devices\n");
    /* another process's load slows a run: a half of a core's difference already shows */
    if (!(fabs(loadavg[0] - loadavg[1]) < 0.5))
        printf("warning: the load averages before the runs differ (%s): B/A may be the load's, not the build's\n",
               isnan(loadavg[0]) || isnan(loadavg[1]) ? "or are not stated" : "by 0.5 or more");
    printf("\n%-52s %8s %8s %8s %8s %8s %8s %8s\n", "configuration", "A p50", "A p99", "B p50", "B p99", "B/A",
           "A dB", "B dB");
    /* A's configurations in A's order, then those only B ran */
    for (i = 0; i < r[0].n; i++) row(r[0].results[i].result, find(&r[1], &r[0].results[i]));
    for (i = 0; i < r[1].n; i++)
        if (!find(&r[0], &r[1].results[i])) row(NULL, r[1].results[i].result);
    printf("times in ms per frame (p50: median); B/A: B's median over A's; dB: glass PSNR vs FULL\n");
    run_free(&r[0]);
    run_free(&r[1]);
    return 0;
}
