/* SPDX-License-Identifier: MIT */
/* mesh_3ds.c — glmark2's model formats: Autodesk .3ds (the triangle-mesh
 * chunks only) and glmark2's .jobj text. Both parse a buffer that need not be
 * NUL-terminated and never read past it; a malformed file is refused with
 * SNELL_E_PARSE and the byte offset or line where it went wrong. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "mesh/mesh.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* A model file above 256 MiB is not one of these: refused before it is read. */
#define MODEL_MAX_FILE_BYTES ((size_t)1 << 28)

/* ----------------------------------------------------------------- 3DS */
/* Each chunk: uint16 id, uint32 length including its 6-byte header,
 * little-endian. The path to the geometry is main > editor > object (a
 * NUL-terminated name, then chunks) > triangle mesh > vertex list (uint16 n,
 * n x 3 float32) and face list (uint16 n, n x (3 uint16 + uint16 flags));
 * every other chunk is skipped by its length. */
enum {
    C3DS_MAIN = 0x4D4D,
    C3DS_EDITOR = 0x3D3D,
    C3DS_OBJECT = 0x4000,
    C3DS_TRIMESH = 0x4100,
    C3DS_VERTICES = 0x4110,
    C3DS_FACES = 0x4120
};

typedef struct c3ds {
    snell_ctx *ctx;
    const unsigned char *d;
    size_t size;
    /* pass 1 counts, pass 2 (pos != NULL) fills */
    float *pos;
    uint32_t *idx;
    size_t nv, nt;
} c3ds;

static unsigned rd16(const unsigned char *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }

static uint32_t rd32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float rdf32(const unsigned char *p)
{
    uint32_t u = rd32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The next chunk in [*pos, end): 1 with its id, body and end, 0 when fewer
 * than 6 bytes are left (padding), -1 (message set) when its length does not
 * fit its parent. */
static int next_chunk(c3ds *s, size_t *pos, size_t end, unsigned *id, size_t *body, size_t *cend)
{
    uint32_t len;
    if (end - *pos < 6) return 0;
    *id = rd16(s->d + *pos);
    len = rd32(s->d + *pos + 2);
    if (len < 6 || len > end - *pos) {
        snell__fail(s->ctx, SNELL_E_PARSE, "3DS: chunk 0x%04x at byte %zu has length %lu, %zu bytes left in its parent",
                    *id, *pos, (unsigned long)len, end - *pos);
        return -1;
    }
    *body = *pos + 6;
    *cend = *pos + len;
    *pos = *cend;
    return 1;
}

/* One triangle mesh chunk's vertex and face lists. */
static snell_status read_trimesh(c3ds *s, const char *name, size_t at, size_t end)
{
    size_t vbody = 0, vend = 0, fbody = 0, fend = 0, body, cend, i;
    unsigned id, nv = 0, nf = 0;
    int r;
    while ((r = next_chunk(s, &at, end, &id, &body, &cend)) > 0) {
        if (id == C3DS_VERTICES || id == C3DS_FACES) {
            if ((id == C3DS_VERTICES ? vend : fend) != 0)
                return snell__fail(s->ctx, SNELL_E_PARSE, "3DS object '%s': a second %s list at byte %zu", name,
                                   id == C3DS_VERTICES ? "vertex" : "face", body - 6);
            if (cend - body < 2)
                return snell__fail(s->ctx, SNELL_E_PARSE, "3DS object '%s': chunk 0x%04x at byte %zu has no count",
                                   name, id, body - 6);
        }
        if (id == C3DS_VERTICES) {
            vbody = body;
            vend = cend;
        } else if (id == C3DS_FACES) {
            fbody = body;
            fend = cend;
        }
    }
    if (r < 0) return SNELL_E_PARSE;
    if (fend) {
        nf = rd16(s->d + fbody);
        if ((size_t)nf * 8 > fend - fbody - 2)
            return snell__fail(s->ctx, SNELL_E_PARSE, "3DS object '%s': %u faces do not fit their chunk (%zu bytes)",
                               name, nf, fend - fbody - 2);
    }
    if (vend) {
        nv = rd16(s->d + vbody);
        if ((size_t)nv * 12 > vend - vbody - 2)
            return snell__fail(s->ctx, SNELL_E_PARSE,
                               "3DS object '%s': %u vertices do not fit their chunk (%zu bytes)", name, nv,
                               vend - vbody - 2);
    }
    if (nf == 0) return SNELL_OK; /* a mesh without faces draws nothing */
    if (s->pos) {
        for (i = 0; i < 3 * (size_t)nv; i++) s->pos[3 * s->nv + i] = rdf32(s->d + vbody + 2 + 4 * i);
        for (i = 0; i < nf; i++) {
            const unsigned char *f = s->d + fbody + 2 + 8 * i;
            unsigned k;
            for (k = 0; k < 3; k++) {
                unsigned v = rd16(f + 2 * k);
                if (v >= nv)
                    return snell__fail(s->ctx, SNELL_E_PARSE, "3DS object '%s': face %zu uses vertex %u of %u", name,
                                       i, v, nv);
                s->idx[3 * (s->nt + i) + k] = (uint32_t)(s->nv + v);
            }
        }
    }
    s->nv += nv;
    s->nt += nf;
    return SNELL_OK;
}

/* Keeps only the vertices a face uses, in the order faces first use them (as
 * the OBJ loader does): a vertex no face uses would still count in the
 * mesh's bounds. Smooth normals are the same either way. */
static snell_status compact(c3ds *s, const snell_alloc *al)
{
    uint32_t *map = (uint32_t *)snell__malloc(al, (s->nv + 1) * sizeof(uint32_t));
    float *pos = (float *)snell__calloc(al, 3 * s->nv + 1, sizeof(float));
    size_t i, n = 0;
    if (!map || !pos) {
        snell__free(al, map);
        snell__free(al, pos);
        return snell__fail(s->ctx, SNELL_E_NOMEM, "3DS: out of memory for %zu vertices", s->nv);
    }
    memset(map, 0xff, (s->nv + 1) * sizeof(uint32_t));
    for (i = 0; i < 3 * s->nt; i++) {
        uint32_t v = s->idx[i];
        if (map[v] == 0xffffffffu) {
            memcpy(pos + 3 * n, s->pos + 3 * (size_t)v, 3 * sizeof(float));
            map[v] = (uint32_t)n++;
        }
        s->idx[i] = map[v];
    }
    snell__free(al, map);
    snell__free(al, s->pos);
    s->pos = pos;
    s->nv = n;
    return SNELL_OK;
}

/* Walks main > editor > object > trimesh: counts (pass 1) or fills (pass 2). */
static snell_status walk_3ds(c3ds *s)
{
    size_t p0 = 0, b0, e0;
    unsigned id0;
    int r0, r1, r2, r3;
    while ((r0 = next_chunk(s, &p0, s->size, &id0, &b0, &e0)) > 0) {
        size_t p1 = b0, b1, e1;
        unsigned id1;
        if (id0 != C3DS_MAIN) continue;
        while ((r1 = next_chunk(s, &p1, e0, &id1, &b1, &e1)) > 0) {
            size_t p2 = b1, b2, e2;
            unsigned id2;
            if (id1 != C3DS_EDITOR) continue;
            while ((r2 = next_chunk(s, &p2, e1, &id2, &b2, &e2)) > 0) {
                const unsigned char *nul;
                char name[64];
                size_t p3, b3, e3, n;
                unsigned id3;
                if (id2 != C3DS_OBJECT) continue;
                nul = (const unsigned char *)memchr(s->d + b2, 0, e2 - b2);
                if (!nul)
                    return snell__fail(s->ctx, SNELL_E_PARSE, "3DS: the object at byte %zu has no NUL-ended name",
                                       b2 - 6);
                n = (size_t)(nul - (s->d + b2));
                if (n >= sizeof name) n = sizeof name - 1;
                memcpy(name, s->d + b2, n);
                name[n] = 0;
                for (p3 = (size_t)(nul - s->d) + 1; (r3 = next_chunk(s, &p3, e2, &id3, &b3, &e3)) > 0;) {
                    snell_status st;
                    if (id3 != C3DS_TRIMESH) continue;
                    if ((st = read_trimesh(s, name, b3, e3)) != SNELL_OK) return st;
                }
                if (r3 < 0) return SNELL_E_PARSE;
            }
            if (r2 < 0) return SNELL_E_PARSE;
        }
        if (r1 < 0) return SNELL_E_PARSE;
    }
    return r0 < 0 ? SNELL_E_PARSE : SNELL_OK;
}

snell_status snell_mesh_load_3ds_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    c3ds s;
    snell_status st;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_3ds_mem: out is NULL");
    *out = NULL;
    if (!data && size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_3ds_mem: data is NULL");
    memset(&s, 0, sizeof s);
    s.ctx = ctx;
    s.d = (const unsigned char *)data;
    s.size = size;
    if (size < 6 || rd16(s.d) != C3DS_MAIN)
        return snell__fail(ctx, SNELL_E_PARSE, "3DS: not a .3ds file (no main chunk 0x4D4D at byte 0)");
    if ((st = walk_3ds(&s)) != SNELL_OK) return st;
    if (s.nt == 0) return snell__fail(ctx, SNELL_E_PARSE, "3DS: no triangle mesh with faces (%zu bytes)", size);
    /* each vertex takes 12 bytes of the file and each face 8, so the counts
     * are bounded by its size; the budget still has the last word */
    if (s.nv > SNELL_MESH_MAX_VERTICES || s.nt > SNELL_MESH_MAX_TRIANGLES)
        return snell__fail(ctx, SNELL_E_LIMIT, "3DS: %zu vertices, %zu triangles: too large", s.nv, s.nt);
    if ((st = snell__mesh_budget_check(ctx, s.nv, s.nt, "3DS")) != SNELL_OK) return st;
    s.pos = (float *)snell__calloc(al, 3 * s.nv + 1, sizeof(float));
    s.idx = (uint32_t *)snell__calloc(al, 3 * s.nt, sizeof(uint32_t));
    if (!s.pos || !s.idx) {
        snell__free(al, s.pos);
        snell__free(al, s.idx);
        return snell__fail(ctx, SNELL_E_NOMEM, "3DS: out of memory for %zu vertices", s.nv);
    }
    s.nv = s.nt = 0;
    if ((st = walk_3ds(&s)) != SNELL_OK || (st = compact(&s, al)) != SNELL_OK) {
        snell__free(al, s.pos);
        snell__free(al, s.idx);
        return st;
    }
    return snell__mesh_adopt(ctx, al, s.pos, NULL, s.idx, (uint32_t)s.nv, (uint32_t)s.nt, out);
}

/* ---------------------------------------------------------------- jobj */
/* glmark2's text format: "v x y z", "vn x y z", "vt u v w", "vc r g b" and
 * "i n" (one 0-based index a line, three a triangle). It is rewritten as OBJ
 * text line for line (vt and vc lines left empty, a triangle's face on its
 * third index line), so the OBJ parser's number reading, checks and line
 * numbers apply to it. */
snell_status snell_mesh_load_jobj_mem(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    const char *p = data, *end = data + size;
    char *obj, *o;
    size_t cap, line = 1, nv = 0, nn = 0, ni = 0;
    unsigned long tri[3];
    snell_status st;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_jobj_mem: out is NULL");
    *out = NULL;
    if (!data && size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_jobj_mem: data is NULL");
    if (!data) p = end = "";
    if (size >= 3 && !memcmp(p, "\xEF\xBB\xBF", 3)) p += 3; /* a UTF-8 byte-order mark, as OBJ skips it */
    /* an "i n" line of at least 4 bytes becomes at most 1/3 of "f a//a b//b c//c\n"
     * (3 x 23 bytes): 7 bytes out per byte in is a bound with room */
    if (size > ((size_t)-1) / 8) return snell__fail(ctx, SNELL_E_LIMIT, "jobj: %zu bytes is too large", size);
    cap = 8 * size + 1;
    if ((st = snell__budget_check(ctx, cap, "jobj rewritten as OBJ")) != SNELL_OK) return st;
    obj = o = (char *)snell__malloc(al, cap);
    if (!obj) return snell__fail(ctx, SNELL_E_NOMEM, "jobj: out of memory for %zu bytes", cap);
    while (p < end) {
        const char *nl = (const char *)memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        size_t len = (size_t)(le - p);
        if (len >= 2 && p[0] == 'i' && (p[1] == ' ' || p[1] == '\t')) {
            const char *q = p + 2;
            unsigned long v = 0;
            int digits = 0;
            while (q < le && (*q == ' ' || *q == '\t')) q++;
            for (; q < le && *q >= '0' && *q <= '9' && digits < 10; q++, digits++) v = 10 * v + (unsigned long)(*q - '0');
            while (q < le && (*q == ' ' || *q == '\t' || *q == '\r')) q++;
            if (!digits || q != le || v >= SNELL_MESH_MAX_VERTICES) {
                snell__free(al, obj);
                return snell__fail(ctx, SNELL_E_PARSE, "jobj line %zu: 'i' needs one index below %u", line,
                                   SNELL_MESH_MAX_VERTICES);
            }
            tri[ni++ % 3] = v + 1;
            if (ni % 3 == 0) {
                if (nn)
                    o += sprintf(o, "f %lu//%lu %lu//%lu %lu//%lu", tri[0], tri[0], tri[1], tri[1], tri[2], tri[2]);
                else
                    o += sprintf(o, "f %lu %lu %lu", tri[0], tri[1], tri[2]);
            }
        } else if ((len >= 2 && p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) ||
                   (len >= 3 && p[0] == 'v' && p[1] == 'n' && (p[2] == ' ' || p[2] == '\t'))) {
            if (ni) { /* the OBJ rewrite numbers faces by the vertices before them */
                snell__free(al, obj);
                return snell__fail(ctx, SNELL_E_PARSE, "jobj line %zu: a vertex after the indices", line);
            }
            if (p[1] == 'n') nn++;
            else nv++;
            memcpy(o, p, len);
            o += len;
        } else if (!(len >= 3 && p[0] == 'v' && (p[1] == 't' || p[1] == 'c') && (p[2] == ' ' || p[2] == '\t')) &&
                   !(len == 0 || (len == 1 && p[0] == '\r'))) {
            snell__free(al, obj);
            return snell__fail(ctx, SNELL_E_PARSE, "jobj line %zu: not a v, vn, vt, vc or i line", line);
        }
        *o++ = '\n';
        line++;
        p = nl ? nl + 1 : end;
    }
    if (ni % 3) {
        snell__free(al, obj);
        return snell__fail(ctx, SNELL_E_PARSE, "jobj: %zu indices, not whole triangles", ni);
    }
    if (nn && nn != nv) {
        snell__free(al, obj);
        return snell__fail(ctx, SNELL_E_PARSE, "jobj: %zu normals for %zu vertices", nn, nv);
    }
    st = snell_mesh_load_obj_mem(ctx, obj, (size_t)(o - obj), out);
    snell__free(al, obj);
    if (st != SNELL_OK) { /* the OBJ parser's message, with the jobj's own line numbers */
        char why[SNELL_REASON_SIZE];
        snprintf(why, sizeof why, "%s", snell_last_error(ctx));
        return snell__fail(ctx, st, "jobj (read as OBJ, same line numbers): %s", why);
    }
    return st;
}

/* ---------------------------------------------------------------- files */
typedef snell_status (*mem_loader)(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out);

static snell_status load_3ds_text(snell_ctx *ctx, const char *data, size_t size, snell_mesh **out)
{
    return snell_mesh_load_3ds_mem(ctx, data, size, out);
}

static snell_status load_file(snell_ctx *ctx, const char *path, mem_loader load, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    struct stat sb;
    FILE *f;
    char *buf;
    size_t got;
    snell_status st;
    const char *why;
    int opened;
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load: out is NULL");
    *out = NULL;
    if (!path) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load: path is NULL");
    f = snell__fopen_regular(path, &opened, &why);
    if (!f) return snell__fail(ctx, SNELL_E_IO, opened ? "'%s' is %s" : "cannot open '%s': %s", path, why);
    if (fstat(fileno(f), &sb) != 0) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_IO, "cannot stat '%s'", path);
    }
    if ((unsigned long long)sb.st_size > MODEL_MAX_FILE_BYTES) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_LIMIT, "'%s' is larger than %zu bytes", path, MODEL_MAX_FILE_BYTES);
    }
    if ((st = snell__budget_check(ctx, (size_t)sb.st_size + 1, "a model file")) != SNELL_OK) {
        fclose(f);
        return st;
    }
    buf = (char *)snell__malloc(al, (size_t)sb.st_size + 1);
    if (!buf) {
        fclose(f);
        return snell__fail(ctx, SNELL_E_NOMEM, "out of memory reading '%s'", path);
    }
    got = fread(buf, 1, (size_t)sb.st_size, f);
    if (ferror(f) || got != (size_t)sb.st_size) {
        fclose(f);
        snell__free(al, buf);
        return snell__fail(ctx, SNELL_E_IO, "read error on '%s'", path);
    }
    fclose(f);
    st = load(ctx, buf, got, out);
    snell__free(al, buf);
    if (st != SNELL_OK) {
        char why[256];
        snprintf(why, sizeof why, "%s", snell_last_error(ctx));
        return snell__fail(ctx, st, "'%s': %s", path, why);
    }
    return st;
}

snell_status snell__mesh_load_3ds(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    return load_file(ctx, path, load_3ds_text, out);
}

snell_status snell__mesh_load_jobj(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    return load_file(ctx, path, snell_mesh_load_jobj_mem, out);
}
