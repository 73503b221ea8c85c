/* SPDX-License-Identifier: MIT */
/* mesh_obj.c — Wavefront OBJ loader (v, vn, vt, f; everything else ignored).
 * Own bounded parser: works on a buffer that need not be NUL-terminated, never
 * reads past it, and reports malformed input with the line number. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "mesh/mesh.h"

#include <sys/stat.h>

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Whole-file reads are capped: an OBJ above 1 GiB is not a glass object. */
#define OBJ_MAX_FILE_BYTES ((size_t)1 << 30)
#define NO_INDEX 0xffffffffu

typedef struct obj_parser {
    snell_ctx *ctx;
    const snell_alloc *al;
    const char *p, *end;
    unsigned long line;
    /* input attribute arrays (as in the file) */
    float *pos;  size_t npos, cap_pos;   /* 3 floats each */
    float *nrm;  size_t nnrm, cap_nrm;   /* 3 floats each */
    size_t ntex;                         /* vt only counted: indices must be valid */
    /* output vertices: one per unique (v, vn) pair */
    uint32_t *out_v, *out_n; size_t nout, cap_out;
    /* hash (v, vn) -> output vertex; open addressing, keys packed v<<32|vn */
    uint64_t *hkeys; uint32_t *hvals; size_t hcap; /* hcap is a power of two or 0 */
    /* triangles in output vertex ids */
    uint32_t *tri; size_t ntri, cap_tri;
    /* scratch for one face's corners */
    uint32_t *face; size_t cap_face;
    /* bytes held by all the arrays above: one request against the memory
     * budget (they live together until the mesh is built) */
    size_t bytes;
} obj_parser;

/* The capacity grow() moves cap to for need elements; 0 on overflow. */
static size_t grown_cap(size_t cap, size_t need, size_t elem)
{
    size_t ncap = cap ? cap : 64;
    int ok = 1;
    while (ncap < need) {
        if (ncap > ((size_t)-1) / 2) return 0;
        ncap *= 2;
    }
    (void)snell__mul_size(ncap, elem, &ok);
    return ok ? ncap : 0;
}

/* Grows *arr (elements of size elem) so it holds at least need elements. */
static int grow(const snell_alloc *al, void **arr, size_t *cap, size_t need, size_t elem)
{
    size_t ncap;
    void *np;
    if (need <= *cap) return 1;
    ncap = grown_cap(*cap, need, elem);
    if (!ncap) return 0;
    np = snell__realloc(al, *arr, ncap * elem);
    if (!np) return 0;
    *arr = np;
    *cap = ncap;
    return 1;
}

static snell_status nomem(obj_parser *ps)
{
    return snell__fail(ps->ctx, SNELL_E_NOMEM, "OBJ line %lu: out of memory", ps->line);
}

/* SNELL_OK if the parser's arrays may grow by `more` bytes within the memory budget. */
static snell_status budget(obj_parser *ps, size_t more)
{
    char what[64];
    size_t total = ps->bytes + more;
    if (total >= more && total <= snell__ctx_budget(ps->ctx)) return SNELL_OK;
    snprintf(what, sizeof what, "OBJ line %lu: the parsed arrays", ps->line);
    return snell__budget_check(ps->ctx, total >= more ? total : (size_t)-1, what);
}

/* grow() of one of the parser's arrays, counted against the budget. */
static snell_status pgrow(obj_parser *ps, void **arr, size_t *cap, size_t need, size_t elem)
{
    size_t old = *cap, ncap;
    snell_status st;
    if (need <= old) return SNELL_OK;
    ncap = grown_cap(old, need, elem);
    if (!ncap) return nomem(ps);
    if ((st = budget(ps, (ncap - old) * elem)) != SNELL_OK) return st;
    if (!grow(ps->al, arr, cap, need, elem)) return nomem(ps);
    ps->bytes += (ncap - old) * elem;
    return SNELL_OK;
}

/* Horizontal whitespace; a backslash before the newline continues the line
 * (OBJ spec), so it is whitespace too, and the line counter moves on. */
static void skip_ws(obj_parser *ps)
{
    for (;;) {
        const char *p = ps->p;
        if (p < ps->end && (*p == ' ' || *p == '\t' || *p == '\v' || *p == '\f')) {
            ps->p++;
        } else if (p < ps->end && *p == '\\') {
            const char *q = p + 1;
            if (q < ps->end && *q == '\r') q++;
            if (q < ps->end && *q == '\n') {
                ps->p = q + 1;
                ps->line++;
            } else {
                return;
            }
        } else {
            return;
        }
    }
}

/* True at the end of the statement: end of buffer, newline, or a comment. */
static int at_eol(const obj_parser *ps)
{
    return ps->p >= ps->end || *ps->p == '\n' || *ps->p == '\r' || *ps->p == '#';
}

static int is_delim(const obj_parser *ps, const char *p)
{
    (void)ps;
    return p >= ps->end || *p == ' ' || *p == '\t' || *p == '\v' || *p == '\f' || *p == '\r' ||
           *p == '\n' || *p == '#' || *p == '\\';
}

static void skip_to_next_line(obj_parser *ps)
{
    const char *nl = (const char *)memchr(ps->p, '\n', (size_t)(ps->end - ps->p));
    ps->p = nl ? nl + 1 : ps->end;
    ps->line++;
}

static const double k_pow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* Decimal float parser, [sign] digits [. digits] [e [sign] digits].
 * Written by hand instead of strtof because strtof honours LC_NUMERIC (a host
 * app running under a "de_DE" locale would read "0.5" as 0) and needs a
 * NUL-terminated string, which a memory buffer is not. Up to 19 significant
 * digits are kept (plenty for float). nan/inf and values outside the float
 * range are rejected. Returns 1 and advances on success. */
static int parse_float(obj_parser *ps, float *out)
{
    const char *p = ps->p, *e = ps->end;
    int neg = 0, digits = 0, sig = 0;
    long exp10 = 0;
    uint64_t mant = 0;
    double v;
    if (p < e && (*p == '+' || *p == '-')) neg = (*p++ == '-');
    for (; p < e && *p >= '0' && *p <= '9'; p++, digits++) {
        if (sig < 19) {
            if (mant || *p != '0') { mant = mant * 10 + (uint64_t)(*p - '0'); sig++; }
        } else {
            exp10++;
        }
    }
    if (p < e && *p == '.') {
        for (p++; p < e && *p >= '0' && *p <= '9'; p++, digits++) {
            if (sig < 19) {
                if (mant || *p != '0') { mant = mant * 10 + (uint64_t)(*p - '0'); sig++; }
                exp10--;
            }
        }
    }
    if (!digits) return 0;
    if (p < e && (*p == 'e' || *p == 'E')) {
        int eneg = 0, edigits = 0;
        long ev = 0;
        p++;
        if (p < e && (*p == '+' || *p == '-')) eneg = (*p++ == '-');
        for (; p < e && *p >= '0' && *p <= '9'; p++, edigits++)
            if (ev < 100000) ev = ev * 10 + (*p - '0');
        if (!edigits) return 0;
        exp10 += eneg ? -ev : ev;
    }
    if (!is_delim(ps, p)) return 0;
    v = (double)mant;
    if (mant == 0) {
        v = 0.0;
    } else if (exp10 >= 0) {
        if (exp10 > 60) return 0; /* certainly beyond FLT_MAX (mant >= 1) */
        v = exp10 <= 22 ? v * k_pow10[exp10] : v * pow(10.0, (double)exp10);
    } else {
        if (exp10 < -80) v = 0.0; /* underflows float (mant < 1e19) */
        else v = -exp10 <= 22 ? v / k_pow10[-exp10] : v * pow(10.0, (double)exp10);
    }
    if (!(fabs(v) <= FLT_MAX)) return 0;
    *out = (float)(neg ? -v : v);
    ps->p = p;
    return 1;
}

/* Optionally signed decimal integer that fits in 32 bits; 0 if none/overflow. */
static int parse_int(obj_parser *ps, long *out)
{
    const char *p = ps->p, *e = ps->end;
    int neg = 0, digits = 0;
    long v = 0;
    if (p < e && (*p == '+' || *p == '-')) neg = (*p++ == '-');
    for (; p < e && *p >= '0' && *p <= '9'; p++, digits++) {
        v = v * 10 + (*p - '0');
        if (v > 0x7fffffffL) return 0;
    }
    if (!digits) return 0;
    *out = neg ? -v : v;
    ps->p = p;
    return 1;
}

/* Reads n floats of a v/vn statement into dst (extra values are ignored:
 * "v x y z w" and the common "v x y z r g b" colour extension). */
static snell_status parse_vec3(obj_parser *ps, const char *what, float *dst)
{
    int k;
    for (k = 0; k < 3; k++) {
        skip_ws(ps);
        if (at_eol(ps))
            return snell__fail(ps->ctx, SNELL_E_PARSE, "OBJ line %lu: '%s' needs 3 coordinates, found %d",
                               ps->line, what, k);
        if (!parse_float(ps, &dst[k]))
            return snell__fail(ps->ctx, SNELL_E_PARSE,
                               "OBJ line %lu: coordinate %d of '%s' is not a finite number", ps->line, k + 1, what);
    }
    return SNELL_OK;
}

/* OBJ indices are 1-based; negative ones count back from the last element
 * defined so far. Elements must be defined before they are used, so the check
 * happens here and the error names the line. */
static int resolve_index(long idx, size_t count, uint32_t *out)
{
    if (idx > 0) {
        if ((size_t)idx > count) return 0;
        *out = (uint32_t)(idx - 1);
        return 1;
    }
    if (idx < 0) {
        if ((size_t)(-idx) > count) return 0;
        *out = (uint32_t)(count - (size_t)(-idx));
        return 1;
    }
    return 0;
}

static uint64_t hash64(uint64_t k)
{
    /* splitmix64 finaliser: good spread for sequential indices */
    k ^= k >> 30; k *= 0xbf58476d1ce4e5b9ull;
    k ^= k >> 27; k *= 0x94d049bb133111ebull;
    return k ^ (k >> 31);
}

static int hash_rehash(obj_parser *ps, size_t ncap)
{
    uint64_t *nk;
    uint32_t *nv;
    size_t i;
    nk = (uint64_t *)snell__calloc(ps->al, ncap, sizeof *nk);
    nv = (uint32_t *)snell__calloc(ps->al, ncap, sizeof *nv);
    if (!nk || !nv) {
        snell__free(ps->al, nk);
        snell__free(ps->al, nv);
        return 0;
    }
    /* key 0 marks an empty slot, so stored keys are offset by one */
    for (i = 0; i < ps->hcap; i++)
        if (ps->hkeys[i]) {
            size_t h = (size_t)hash64(ps->hkeys[i]) & (ncap - 1);
            while (nk[h]) h = (h + 1) & (ncap - 1);
            nk[h] = ps->hkeys[i];
            nv[h] = ps->hvals[i];
        }
    snell__free(ps->al, ps->hkeys);
    snell__free(ps->al, ps->hvals);
    ps->hkeys = nk;
    ps->hvals = nv;
    ps->hcap = ncap;
    return 1;
}

/* Output vertex id of the pair (v, vn), created on first use. */
static snell_status vertex_id(obj_parser *ps, uint32_t v, uint32_t n, uint32_t *out)
{
    uint64_t key = (((uint64_t)v << 32) | n) + 1; /* never 0: v < 2^26 */
    size_t h;
    if ((ps->nout + 1) * 2 > ps->hcap) {
        size_t ncap = ps->hcap ? ps->hcap * 2 : 1024;
        size_t more = (ncap - ps->hcap) * (sizeof *ps->hkeys + sizeof *ps->hvals);
        snell_status st = budget(ps, more);
        if (st != SNELL_OK) return st;
        if (!hash_rehash(ps, ncap)) return nomem(ps);
        ps->bytes += more;
    }
    h = (size_t)hash64(key) & (ps->hcap - 1);
    while (ps->hkeys[h]) {
        if (ps->hkeys[h] == key) {
            *out = ps->hvals[h];
            return SNELL_OK;
        }
        h = (h + 1) & (ps->hcap - 1);
    }
    if (ps->nout >= SNELL_MESH_MAX_VERTICES)
        return snell__fail(ps->ctx, SNELL_E_LIMIT, "OBJ line %lu: more than %u unique vertices", ps->line,
                           SNELL_MESH_MAX_VERTICES);
    if (ps->nout + 1 > ps->cap_out) {
        /* out_v and out_n share one capacity, grown together */
        size_t cap_v = ps->cap_out, cap_n = ps->cap_out;
        snell_status st;
        if ((st = pgrow(ps, (void **)&ps->out_v, &cap_v, ps->nout + 1, sizeof(uint32_t))) != SNELL_OK ||
            (st = pgrow(ps, (void **)&ps->out_n, &cap_n, ps->nout + 1, sizeof(uint32_t))) != SNELL_OK)
            return st;
        ps->cap_out = cap_v < cap_n ? cap_v : cap_n;
    }
    ps->out_v[ps->nout] = v;
    ps->out_n[ps->nout] = n;
    ps->hkeys[h] = key;
    ps->hvals[h] = (uint32_t)ps->nout;
    *out = (uint32_t)ps->nout++;
    return SNELL_OK;
}

/* One face corner: v, v/vt, v//vn or v/vt/vn (empty fields allowed). */
static snell_status parse_corner(obj_parser *ps, int corner, uint32_t *out)
{
    long iv, it, in;
    uint32_t v, t, n = NO_INDEX;
    snell_status st;
    if (!parse_int(ps, &iv) || !resolve_index(iv, ps->npos, &v))
        goto bad;
    if (ps->p < ps->end && *ps->p == '/') {
        ps->p++;
        if (ps->p < ps->end && *ps->p != '/' && !is_delim(ps, ps->p)) {
            if (!parse_int(ps, &it) || !resolve_index(it, ps->ntex, &t)) goto bad;
        }
        if (ps->p < ps->end && *ps->p == '/') {
            ps->p++;
            if (!is_delim(ps, ps->p)) {
                if (!parse_int(ps, &in) || !resolve_index(in, ps->nnrm, &n)) goto bad;
            }
        }
    }
    if (!is_delim(ps, ps->p)) goto bad;
    st = vertex_id(ps, v, n, out);
    return st;
bad:
    return snell__fail(ps->ctx, SNELL_E_PARSE,
                       "OBJ line %lu: face corner %d is malformed or references an undefined element "
                       "(%zu v, %zu vt, %zu vn defined so far)",
                       ps->line, corner + 1, ps->npos, ps->ntex, ps->nnrm);
}

/* f statement. Polygons are fan-triangulated from their first corner, which is
 * correct for convex (and star-from-first-corner) polygons — what exporters
 * write; concave n-gons would need ear clipping. */
static snell_status parse_face(obj_parser *ps)
{
    size_t n = 0, i;
    snell_status st;
    for (;;) {
        skip_ws(ps);
        if (at_eol(ps)) break;
        if ((st = pgrow(ps, (void **)&ps->face, &ps->cap_face, n + 1, sizeof(uint32_t))) != SNELL_OK) return st;
        st = parse_corner(ps, (int)(n < 0x7fffffff ? n : 0x7fffffff), &ps->face[n]);
        if (st != SNELL_OK) return st;
        n++;
    }
    if (n < 3)
        return snell__fail(ps->ctx, SNELL_E_PARSE, "OBJ line %lu: face has %zu corners, needs at least 3",
                           ps->line, n);
    if (ps->ntri + (n - 2) > SNELL_MESH_MAX_TRIANGLES)
        return snell__fail(ps->ctx, SNELL_E_LIMIT, "OBJ line %lu: more than %u triangles", ps->line,
                           SNELL_MESH_MAX_TRIANGLES);
    if ((st = pgrow(ps, (void **)&ps->tri, &ps->cap_tri, 3 * (ps->ntri + n - 2), sizeof(uint32_t))) != SNELL_OK)
        return st;
    for (i = 1; i + 1 < n; i++) {
        uint32_t *t = ps->tri + 3 * ps->ntri++;
        t[0] = ps->face[0];
        t[1] = ps->face[i];
        t[2] = ps->face[i + 1];
    }
    return SNELL_OK;
}

static snell_status parse_statement(obj_parser *ps)
{
    const char *kw = ps->p;
    size_t len;
    snell_status st;
    while (!is_delim(ps, ps->p)) ps->p++;
    len = (size_t)(ps->p - kw);
    if (len == 1 && kw[0] == 'v') {
        if (ps->npos >= SNELL_MESH_MAX_VERTICES)
            return snell__fail(ps->ctx, SNELL_E_LIMIT, "OBJ line %lu: more than %u positions", ps->line,
                               SNELL_MESH_MAX_VERTICES);
        st = pgrow(ps, (void **)&ps->pos, &ps->cap_pos, 3 * (ps->npos + 1), sizeof(float));
        if (st != SNELL_OK) return st;
        {
            st = parse_vec3(ps, "v", ps->pos + 3 * ps->npos);
            if (st != SNELL_OK) return st;
        }
        ps->npos++;
    } else if (len == 2 && kw[0] == 'v' && kw[1] == 'n') {
        if (ps->nnrm >= SNELL_MESH_MAX_VERTICES)
            return snell__fail(ps->ctx, SNELL_E_LIMIT, "OBJ line %lu: more than %u normals", ps->line,
                               SNELL_MESH_MAX_VERTICES);
        st = pgrow(ps, (void **)&ps->nrm, &ps->cap_nrm, 3 * (ps->nnrm + 1), sizeof(float));
        if (st != SNELL_OK) return st;
        {
            st = parse_vec3(ps, "vn", ps->nrm + 3 * ps->nnrm);
            if (st != SNELL_OK) return st;
        }
        ps->nnrm++;
    } else if (len == 2 && kw[0] == 'v' && kw[1] == 't') {
        /* Texture coordinates are not kept, but they are checked and counted so
         * that face indices into them can be validated. */
        float uv;
        skip_ws(ps);
        if (at_eol(ps) || !parse_float(ps, &uv))
            return snell__fail(ps->ctx, SNELL_E_PARSE, "OBJ line %lu: 'vt' needs a finite number", ps->line);
        if (ps->ntex >= SNELL_MESH_MAX_VERTICES)
            return snell__fail(ps->ctx, SNELL_E_LIMIT, "OBJ line %lu: more than %u texture coordinates",
                               ps->line, SNELL_MESH_MAX_VERTICES);
        ps->ntex++;
    } else if (len == 1 && kw[0] == 'f') {
        return parse_face(ps);
    }
    /* everything else (o, g, s, usemtl, mtllib, l, p, vp, curves...) is ignored */
    return SNELL_OK;
}

static void parser_free(obj_parser *ps)
{
    snell__free(ps->al, ps->pos);
    snell__free(ps->al, ps->nrm);
    snell__free(ps->al, ps->out_v);
    snell__free(ps->al, ps->out_n);
    snell__free(ps->al, ps->hkeys);
    snell__free(ps->al, ps->hvals);
    snell__free(ps->al, ps->tri);
    snell__free(ps->al, ps->face);
}

/* Builds the output arrays. Vertices with a usable file normal keep it
 * (renormalised); the others get the area-weighted smooth normal of their
 * position, accumulated over every face that uses that position. */
static snell_status build_mesh(obj_parser *ps, snell_mesh **out)
{
    const snell_alloc *al = ps->al;
    size_t nv = ps->nout, nt = ps->ntri, i;
    float *opos = NULL, *onrm = NULL, *smooth = NULL;
    uint32_t *oidx = NULL, *tmp = NULL;
    int need_smooth = 0;
    snell_status st;
    /* the output arrays join the parser's, which are freed after this */
    if ((st = budget(ps, 24 * nv)) != SNELL_OK) return st;
    ps->bytes += 24 * nv;
    opos = (float *)snell__calloc(al, 3 * nv, sizeof(float));
    onrm = (float *)snell__calloc(al, 3 * nv, sizeof(float));
    if (!opos || !onrm) goto oom;
    for (i = 0; i < nv; i++) {
        uint32_t n = ps->out_n[i];
        memcpy(opos + 3 * i, ps->pos + 3 * (size_t)ps->out_v[i], 3 * sizeof(float));
        if (n != NO_INDEX) {
            const float *s = ps->nrm + 3 * (size_t)n;
            double len = sqrt((double)s[0] * s[0] + (double)s[1] * s[1] + (double)s[2] * s[2]);
            if (len > 1e-20) {
                onrm[3 * i + 0] = (float)(s[0] / len);
                onrm[3 * i + 1] = (float)(s[1] / len);
                onrm[3 * i + 2] = (float)(s[2] / len);
                continue;
            }
            ps->out_n[i] = NO_INDEX; /* zero-length file normal: use the smooth one */
        }
        need_smooth = 1;
    }
    if (need_smooth) {
        if ((st = budget(ps, 12 * (ps->npos + nt))) != SNELL_OK) {
            snell__free(al, opos);
            snell__free(al, onrm);
            return st;
        }
        smooth = (float *)snell__calloc(al, 3 * ps->npos, sizeof(float));
        tmp = (uint32_t *)snell__calloc(al, 3 * nt, sizeof(uint32_t));
        if (!smooth || !tmp) goto oom;
        for (i = 0; i < 3 * nt; i++) tmp[i] = ps->out_v[ps->tri[i]];
        snell__mesh_compute_normals(ps->pos, tmp, (uint32_t)ps->npos, (uint32_t)nt, smooth);
        for (i = 0; i < nv; i++)
            if (ps->out_n[i] == NO_INDEX) memcpy(onrm + 3 * i, smooth + 3 * (size_t)ps->out_v[i], 3 * sizeof(float));
        snell__free(al, smooth);
        snell__free(al, tmp);
        smooth = NULL;
        tmp = NULL;
    }
    /* hand the triangle array over: it is exactly the index buffer */
    oidx = ps->tri;
    ps->tri = NULL;
    return snell__mesh_adopt(ps->ctx, al, opos, onrm, oidx, (uint32_t)nv, (uint32_t)nt, out);
oom:
    snell__free(al, opos);
    snell__free(al, onrm);
    snell__free(al, smooth);
    snell__free(al, tmp);
    return snell__fail(ps->ctx, SNELL_E_NOMEM, "OBJ: out of memory building a mesh of %zu vertices", nv);
}

snell_status snell_mesh_load_obj_mem(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out)
{
    obj_parser ps;
    snell_status st = SNELL_OK;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_obj_mem: out is NULL");
    *out = NULL;
    if (!data && size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_obj_mem: data is NULL");
    memset(&ps, 0, sizeof ps);
    ps.ctx = ctx;
    ps.al = snell__ctx_alloc(ctx);
    ps.p = data;
    ps.end = data + size;
    ps.line = 1;
    /* a UTF-8 byte-order mark (editors on Windows write one) is no part of
     * the first line, whose keyword it would hide */
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) ps.p += 3;
    while (ps.p < ps.end) {
        const char *ls;
        skip_ws(&ps);
        ls = ps.p;
        /* Text only: NUL and other control bytes mean this is not an OBJ file. */
        {
            const char *q = ls;
            const char *nl = (const char *)memchr(q, '\n', (size_t)(ps.end - q));
            const char *le = nl ? nl : ps.end;
            for (; q < le; q++) {
                unsigned char c = (unsigned char)*q;
                if (c < 0x20 && c != '\t' && c != '\r' && c != '\v' && c != '\f') {
                    st = snell__fail(ctx, SNELL_E_PARSE, "OBJ line %lu: binary data (byte 0x%02x)", ps.line, c);
                    goto done;
                }
            }
        }
        if (!at_eol(&ps)) {
            st = parse_statement(&ps);
            if (st != SNELL_OK) goto done;
            skip_ws(&ps);
            /* trailing data after a v/vn/vt statement is ignored (colour
             * extensions); anything up to the newline is skipped */
        }
        if (ps.p < ps.end) skip_to_next_line(&ps);
    }
    if (ps.ntri == 0) {
        st = snell__fail(ctx, SNELL_E_PARSE, "OBJ: no faces (%lu lines, %zu vertices)", ps.line, ps.npos);
        goto done;
    }
    st = build_mesh(&ps, out);
done:
    parser_free(&ps);
    return st;
}

snell_status snell_mesh_load_obj(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    FILE *f;
    char *buf = NULL;
    size_t len = 0, cap = 0;
    snell_status st;
    const char *why;
    int opened;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_obj: out is NULL");
    *out = NULL;
    if (!path) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_obj: path is NULL");
    f = snell__fopen_regular(path, &opened, &why);
    if (!f && !opened) return snell__fail(ctx, SNELL_E_IO, "cannot open '%s': %s", path, why);
    if (!f) return snell__fail(ctx, SNELL_E_IO, "OBJ: '%s' is %s", path, why);
    /* read in chunks (works for files whose size changes) */
    for (;;) {
        size_t got;
        if (len == cap) {
            if (cap >= OBJ_MAX_FILE_BYTES) {
                fclose(f);
                snell__free(al, buf);
                return snell__fail(ctx, SNELL_E_LIMIT, "'%s' is larger than %zu bytes", path, OBJ_MAX_FILE_BYTES);
            }
            if (cap && 2 * cap > snell__ctx_budget(ctx)) {
                char what[320];
                fclose(f);
                snell__free(al, buf);
                snprintf(what, sizeof what, "reading '%.256s' (more than %zu bytes)", path, cap);
                return snell__budget_check(ctx, 2 * cap, what);
            }
            if (!grow(al, (void **)&buf, &cap, cap ? cap * 2 : 65536, 1)) {
                fclose(f);
                snell__free(al, buf);
                return snell__fail(ctx, SNELL_E_NOMEM, "out of memory reading '%s'", path);
            }
        }
        got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        fclose(f);
        snell__free(al, buf);
        return snell__fail(ctx, SNELL_E_IO, "read error on '%s'", path);
    }
    fclose(f);
    st = snell_mesh_load_obj_mem(ctx, buf, len, out);
    snell__free(al, buf);
    return st;
}
