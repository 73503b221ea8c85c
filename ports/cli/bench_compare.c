/* SPDX-License-Identifier: MIT */
/* bench_compare.c — snell-bench --compare A.json B.json: two runs (two boards,
 * two builds, vsync on and off) side by side. Per configuration, matched by
 * its spec: the median and 99th percentile frame time of each, B's median over
 * A's, and the glass PSNR against FULL of each (null where a run measured no
 * error, as snell-kiosk's). The JSON is snell-bench's own (bench_output.c);
 * the reader below knows only as much JSON as it needs to walk it. */
#include "bench.h"
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
    if (*p == '-' || (*p >= '0' && *p <= '9')) {
        char *end;
        strtod(p, &end);
        return end;
    }
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

/* A string value into out ("" if not a string; escapes kept as written). */
static void str(const char *v, char *out, size_t n)
{
    const char *e;
    out[0] = '\0';
    if (!v || *v != '"' || !(e = skip(v, 0))) return;
    snprintf(out, n, "%.*s", (int)(e - v - 2), v + 1);
}

static double num(const char *v)
{
    char *end;
    double x;
    if (!v) return NAN;
    x = strtod(v, &end);
    return end == v ? NAN : x;
}

/* ----------------------------------------------------------- the runs */
typedef struct run {
    const char *path;
    char *text;
    const char *results;           /* the array */
} run;

static int load(run *r, const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    r->path = path;
    r->text = NULL;
    if (!f) return fprintf(stderr, "snell-bench --compare: cannot read '%s'\n", path), 0;
    if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0 ||
        !(r->text = (char *)malloc((size_t)n + 1)) || fread(r->text, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        free(r->text);
        r->text = NULL;
        return fprintf(stderr, "snell-bench --compare: cannot read '%s'\n", path), 0;
    }
    fclose(f);
    r->text[n] = '\0';
    r->results = member(r->text, "results");
    if (!skip(r->text, 0) || !r->results || *r->results != '[') {
        fprintf(stderr, "snell-bench --compare: '%s' is not a snell-bench JSON (no \"results\" array)\n", path);
        free(r->text);
        r->text = NULL;
        return 0;
    }
    return 1;
}

/* The result of r whose spec is spec; NULL if none. */
static const char *find(const run *r, const char *spec)
{
    const char *p = ws(r->results + 1);
    char s[512];
    while (*p == '{') {
        str(member(p, "spec"), s, sizeof s);
        if (!strcmp(s, spec)) return p;
        if (!(p = skip(p, 0))) return NULL;
        p = ws(p);
        if (*p != ',') return NULL;
        p = ws(p + 1);
    }
    return NULL;
}

static void describe(const char *tag, const run *r)
{
    char v[64], c[64], ren[256], gv[128], board[256], kernel[256], vsync[160], tool[64];
    str(path2(r->text, "snell", "version"), v, sizeof v);
    str(path2(r->text, "snell", "commit"), c, sizeof c);
    str(path2(r->text, "gl", "renderer"), ren, sizeof ren);
    if (!ren[0]) str(member(r->text, "gl_renderer"), ren, sizeof ren);
    str(path2(r->text, "gl", "version"), gv, sizeof gv);
    str(path2(r->text, "system", "board"), board, sizeof board);
    str(path2(r->text, "system", "kernel"), kernel, sizeof kernel);
    str(member(r->text, "vsync"), vsync, sizeof vsync);
    str(member(r->text, "tool"), tool, sizeof tool);
    printf("%s: %s (%s, snell %s, commit %s)\n   GL %s | %s\n   board %s | %s\n   vsync %s\n", tag, r->path,
           tool[0] ? tool : "?", v[0] ? v : "?", c[0] ? c : "?", ren[0] ? ren : "?", gv[0] ? gv : "?",
           board[0] ? board : "not stated", kernel[0] ? kernel : "?", vsync[0] ? vsync : "?");
}

static void cell(double v, const char *fmt)
{
    if (isfinite(v)) printf(fmt, v);
    else printf("%9s", "-");
}

/* One row: the configuration in A and/or B (either may be NULL). */
static void row(const char *spec, const char *a, const char *b)
{
    double am = num(path2(a, "time_ms", "median")), bm = num(path2(b, "time_ms", "median"));
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
    const char *p, *files[2];
    char spec[512];
    int c, nfiles = 0;
    if (cli_wants_help(argc, argv)) {
        printf("usage: snell-bench --compare A.json B.json\n"
               "Two snell-bench (or snell-kiosk --bench) runs side by side: what each ran on (snell version\n"
               "and commit, GL renderer and version, board, kernel, vsync), then per configuration (by\n"
               "spec) the median and p99 frame time in each, B's median over A's, and the glass PSNR vs\n"
               "FULL in each ('-' where a run has no such figure or no such configuration).\n");
        return 0;
    }
    cli_opts_reset();
    while ((c = cli_getopt("snell-bench --compare", "--compare --help", argc, argv, "h", longopts)) != -1)
        if (c == '?') return 2;
    for (; optind < argc; optind++) {
        if (nfiles == 2) {
            fprintf(stderr, "snell-bench --compare: two JSON files, got a third ('%s')\n", argv[optind]);
            return 2;
        }
        files[nfiles++] = argv[optind];
    }
    if (nfiles != 2) {
        fprintf(stderr, "snell-bench --compare: wants two JSON files, A.json B.json\n");
        return 2;
    }
    if (!load(&r[0], files[0])) return 1;
    if (!load(&r[1], files[1])) {
        free(r[0].text);
        return 1;
    }
    describe("A", &r[0]);
    describe("B", &r[1]);
    printf("\n%-52s %8s %8s %8s %8s %8s %8s %8s\n", "configuration", "A p50", "A p99", "B p50", "B p99", "B/A",
           "A dB", "B dB");
    /* A's configurations in A's order, then those only B ran */
    for (p = ws(r[0].results + 1); *p == '{';) {
        str(member(p, "spec"), spec, sizeof spec);
        row(spec, p, find(&r[1], spec));
        if (!(p = skip(p, 0))) break;
        p = ws(p);
        if (*p != ',') break;
        p = ws(p + 1);
    }
    for (p = ws(r[1].results + 1); *p == '{';) {
        str(member(p, "spec"), spec, sizeof spec);
        if (!find(&r[0], spec)) row(spec, NULL, p);
        if (!(p = skip(p, 0))) break;
        p = ws(p);
        if (*p != ',') break;
        p = ws(p + 1);
    }
    printf("times in ms per frame (p50: median); B/A: B's median over A's; dB: glass PSNR vs FULL\n");
    free(r[0].text);
    free(r[1].text);
    return 0;
}
