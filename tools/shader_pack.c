/* SPDX-License-Identifier: MIT */
/* shader_pack.c — build-time tool (runs on the build machine, never linked
 * into libsnell): packs the embedded shaders, already stripped by
 * cmake/embed_shaders.cmake, into one stream that src/core/program.c
 * (lz_unpack) unpacks once at run time. One stream for all files, so a chunk's
 * words are matched across every program that includes it.
 *
 *   shader_pack OUT.c SYMBOL REL1 FILE1 [REL2 FILE2 ...]
 *
 * Stream: LZ77 (matches of 2..273 bytes at any distance back) coded by an
 * adaptive binary range coder, LZMA's (11-bit probabilities moved by 1/32 of
 * the way each bit; 5 bytes flushed at the end, the first always 0), with a
 * smaller model. Each item starts with an is-match bit (context: the last item
 * was a literal, a match or a repeat):
 *   literal  8 bits, a bit tree in the context of the previous byte's top 3 bits;
 *   repeat   is-rep bit 1, then the length: a match at the last distance again;
 *   match    is-rep bit 0, the length, then the distance - 1: a 6-bit slot
 *            (a bit tree per length 2, 3, 4, more), slots 0..3 the distance
 *            itself, slot s >= 4 (2 | s & 1) << (s/2 - 1) plus s/2 - 1 extra
 *            bits, high first, each with its own probability per slot.
 * A length - 2 is a choice bit (0: 3 more bits, 0..7), a second (0: 3 bits,
 * 8..15; 1: 8 bits, 16..271); matches and repeats have their own.
 * The model's layout is LZ_* below; program.c's must be the same.
 * Parsing is optimal for prices from the model as the previous pass left it
 * (three passes, the first priced at the model's start). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    LZ_IS_MATCH = 0, LZ_IS_REP = 3, LZ_LIT = 6, LZ_LEN = LZ_LIT + 8 * 256, LZ_SLOT = LZ_LEN + 2 * 274,
    LZ_EXTRA = LZ_SLOT + 4 * 64, LZ_PROBS = LZ_EXTRA + 48 * 24
};
#define MAX_LEN 273
#define HASH_BITS 16
#define CHAIN 4096 /* candidates tried per position, nearest first */

static uint16_t g_p[LZ_PROBS];

/* ---- the range coder ---- */
typedef struct coder {
    uint64_t low;
    uint32_t range;
    unsigned char cache;
    size_t cache_size, n;
    unsigned char *out;
} coder;

static void shift_low(coder *c)
{
    if ((uint32_t)c->low < 0xFF000000u || (c->low >> 32) != 0) {
        unsigned char carry = (unsigned char)(c->low >> 32), b = c->cache;
        do {
            c->out[c->n++] = (unsigned char)(b + carry);
            b = 0xFF;
        } while (--c->cache_size != 0);
        c->cache = (unsigned char)(c->low >> 24);
    }
    c->cache_size++;
    c->low = (c->low & 0x00FFFFFFu) << 8;
}

static void put_bit(coder *c, unsigned k, unsigned bit)
{
    uint16_t *p = &g_p[k];
    uint32_t bound = (c->range >> 11) * *p;
    if (bit) {
        c->low += bound;
        c->range -= bound;
        *p = (uint16_t)(*p - (*p >> 5));
    } else {
        c->range = bound;
        *p = (uint16_t)(*p + ((2048 - *p) >> 5));
    }
    while (c->range < 1u << 24) {
        c->range <<= 8;
        shift_low(c);
    }
}

/* ---- prices: 1/16 bit, of coding the value with the model as it is ---- */
static unsigned g_price[128]; /* -16 log2(p / 2048) for p in steps of 16 */

static unsigned price_bit(unsigned k, unsigned bit)
{
    return g_price[(bit ? 2048 - g_p[k] : g_p[k]) >> 4];
}

/* Codes (c non-NULL) or prices an nbits-bit value in the bit tree at k. */
static unsigned tree(coder *c, unsigned k, int nbits, unsigned v)
{
    unsigned m = 1, price = 0;
    while (nbits-- > 0) {
        unsigned bit = v >> nbits & 1;
        if (c) put_bit(c, k + m, bit);
        else price += price_bit(k + m, bit);
        m = m << 1 | bit;
    }
    return price;
}

static unsigned bit(coder *c, unsigned k, unsigned b)
{
    if (c) put_bit(c, k, b);
    return c ? 0 : price_bit(k, b);
}

static unsigned len_code(coder *c, unsigned k, unsigned l) /* l = length - 2 */
{
    if (l < 8) return bit(c, k, 0) + tree(c, k + 2, 3, l);
    if (l < 16) return bit(c, k, 1) + bit(c, k + 1, 0) + tree(c, k + 10, 3, l - 8);
    return bit(c, k, 1) + bit(c, k + 1, 1) + tree(c, k + 18, 8, l - 16);
}

static unsigned literal(coder *c, unsigned state, const unsigned char *in, size_t i)
{
    return bit(c, LZ_IS_MATCH + state, 0) + tree(c, LZ_LIT + (i ? in[i - 1] >> 5 : 0) * 256u, 8, in[i]);
}

static unsigned repeat(coder *c, unsigned state, size_t len)
{
    return bit(c, LZ_IS_MATCH + state, 1) + bit(c, LZ_IS_REP + state, 1) + len_code(c, LZ_LEN + 274, (unsigned)len - 2);
}

static unsigned match(coder *c, unsigned state, size_t len, size_t dist)
{
    unsigned d = (unsigned)dist - 1, slot = d, n = 0, price;
    int nb;
    while (d >> n > 1) n++;
    if (d >= 4) slot = 2 * n + (d >> (n - 1) & 1);
    price = bit(c, LZ_IS_MATCH + state, 1) + bit(c, LZ_IS_REP + state, 0) + len_code(c, LZ_LEN, (unsigned)len - 2);
    price += tree(c, LZ_SLOT + (len < 5 ? (unsigned)len - 2 : 3) * 64u, 6, slot);
    if (slot >= 4)
        for (nb = (int)(slot >> 1) - 1; nb-- > 0;) price += bit(c, LZ_EXTRA + slot * 24 + (unsigned)nb, d >> nb & 1);
    return price;
}

/* ---- parsing ---- */
typedef struct node {
    uint64_t cost;           /* of the cheapest way to code in[0 .. here) */
    uint32_t len, dist, rep; /* its last item (dist 0: a literal) and the distance a repeat would take */
    uint32_t next;           /* on the path chosen: where the next item ends */
    unsigned state;          /* 0 literal, 1 match, 2 repeat */
} node;

static uint32_t hash3(const unsigned char *p)
{
    return ((uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]) * 2654435761u >> (32 - HASH_BITS);
}

static void reach(node *to, uint64_t cost, size_t len, size_t dist, size_t rep, unsigned state)
{
    if (cost >= to->cost) return;
    to->cost = cost;
    to->len = (uint32_t)len;
    to->dist = (uint32_t)dist;
    to->rep = (uint32_t)rep;
    to->state = state;
}

/* One pass: the cheapest parse at the prices of the model as it is, then
 * that parse coded from a fresh model (which the next pass prices from). */
static size_t pack_pass(const unsigned char *in, size_t n, unsigned char *out, node *nd, int32_t *head, int32_t *prev)
{
    coder c = {0, 0xFFFFFFFFu, 0, 1, 0, NULL};
    size_t i, k;
    memset(head, -1, sizeof(int32_t) << HASH_BITS);
    for (i = 0; i <= n; i++) nd[i].cost = UINT64_MAX;
    memset(&nd[0], 0, sizeof nd[0]);
    for (i = 0; i < n; i++) {
        const node *a = &nd[i];
        size_t best = 1;
        if (i + 3 <= n) {
            uint32_t h = hash3(in + i);
            prev[i] = head[h];
            head[h] = (int32_t)i;
        }
        reach(&nd[i + 1], a->cost + literal(NULL, a->state, in, i), 1, 0, a->rep, 0);
        if (a->rep) {
            size_t l = 0;
            while (i + l < n && l < MAX_LEN && in[i + l] == in[i + l - a->rep]) l++;
            for (k = 2; k <= l; k++) reach(&nd[i + k], a->cost + repeat(NULL, a->state, k), k, a->rep, a->rep, 2);
        }
        if (i + 3 <= n) {
            int32_t cand = prev[i];
            int tries = CHAIN;
            for (; cand >= 0 && tries-- > 0 && best < MAX_LEN; cand = prev[cand]) {
                size_t l = 0, dist = i - (size_t)cand;
                while (i + l < n && l < MAX_LEN && in[(size_t)cand + l] == in[i + l]) l++;
                for (k = best + 1; k <= l; k++) /* each length at its nearest distance */
                    reach(&nd[i + k], a->cost + match(NULL, a->state, k, dist), k, dist, dist, 1);
                if (l > best) best = l;
            }
        }
    }
    /* The path back from the end, linked forward, then coded from a fresh model. */
    for (i = n; i > 0; i -= nd[i].len) nd[i - nd[i].len].next = (uint32_t)i;
    for (k = 0; k < LZ_PROBS; k++) g_p[k] = 1024;
    c.out = out;
    for (i = 0; i < n; i = nd[i].next) {
        const node *to = &nd[nd[i].next];
        if (to->dist == 0) literal(&c, nd[i].state, in, i);
        else if (to->state == 2) repeat(&c, nd[i].state, to->len);
        else match(&c, nd[i].state, to->len, to->dist);
    }
    for (k = 0; k < 5; k++) shift_low(&c);
    return c.n;
}

static size_t compress(const unsigned char *in, size_t n, unsigned char *out)
{
    node *nd = (node *)malloc((n + 1) * sizeof *nd);
    int32_t *head = (int32_t *)malloc(sizeof(int32_t) << HASH_BITS), *prev = (int32_t *)malloc((n + 1) * sizeof *prev);
    size_t packed = 0, k;
    int pass;
    if (!nd || !head || !prev) return 0;
    for (k = 0; k < 128; k++) { /* -16 log2 x, x = (16 k + 8) / 2048, to 1/256 bit without libm */
        double x = ((double)k * 16 + 8) / 2048, l = 0, b = 0.5;
        int i;
        while (x < 1) x *= 2, l -= 1; /* x in [1, 2): log2 = l + the bits below */
        for (i = 0; i < 8; i++, b /= 2)
            if ((x *= x) >= 2) x /= 2, l += b;
        g_price[k] = (unsigned)(-16 * l + 0.5);
    }
    for (k = 0; k < LZ_PROBS; k++) g_p[k] = 1024;
    for (pass = 0; pass < 3; pass++) packed = pack_pass(in, n, out, nd, head, prev);
    free(nd);
    free(head);
    free(prev);
    return packed;
}

static unsigned char *read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    long len;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return NULL;
    }
    buf = (unsigned char *)malloc((size_t)len + 1);
    if (buf && fread(buf, 1, (size_t)len, f) != (size_t)len) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *n = (size_t)len;
    return buf;
}

int main(int argc, char **argv)
{
    size_t total = 0, packed, i, nfiles;
    unsigned char *all = NULL, *out;
    size_t *offsets;
    FILE *f;
    if (argc < 3 || (argc - 3) % 2 != 0) {
        fprintf(stderr, "usage: shader_pack OUT.c SYMBOL [REL FILE]...\n");
        return 2;
    }
    nfiles = (size_t)(argc - 3) / 2;
    offsets = (size_t *)calloc(nfiles + 1, sizeof *offsets);
    for (i = 0; i < nfiles; i++) {
        size_t n = 0;
        unsigned char *text = read_file(argv[4 + 2 * i], &n), *grown;
        if (!text || !offsets) {
            fprintf(stderr, "shader_pack: cannot read %s\n", argv[4 + 2 * i]);
            return 1;
        }
        grown = (unsigned char *)realloc(all, total + n + 1);
        if (!grown) return 1;
        all = grown;
        offsets[i] = total;
        memcpy(all + total, text, n);
        all[total + n] = 0; /* each file NUL-terminated in the unpacked text */
        total += n + 1;
        free(text);
    }
    if (total >= 1u << 24) {
        fprintf(stderr, "shader_pack: %zu bytes of shaders: more than the unpacker's 16 MiB\n", total);
        return 1;
    }
    out = (unsigned char *)malloc(2 * total + 16); /* at worst about 9 bits a byte */
    if (!out) return 1;
    packed = compress(all, total, out);
    if (!packed) return 1;
    f = fopen(argv[1], "w");
    if (!f) {
        fprintf(stderr, "shader_pack: cannot write %s\n", argv[1]);
        return 1;
    }
    fprintf(f, "/* generated by tools/shader_pack.c: %zu bytes of shaders in %zu; do not edit */\n", total, packed);
    fprintf(f, "#include <stddef.h>\n#include \"core/shaders_embedded.h\"\n\n");
    fprintf(f, "static const unsigned char packed[%zu] = {\n", packed);
    for (i = 0; i < packed; i++) fprintf(f, "%u,%s", out[i], i % 24 == 23 ? "\n" : "");
    fprintf(f, "};\n\nstatic char unpacked[%zu];\n\n", total);
    fprintf(f, "const snell_shader_file %s[] = {\n", argv[2]);
    for (i = 0; i < nfiles; i++) fprintf(f, "    {\"%s\", unpacked + %zu},\n", argv[3 + 2 * i], offsets[i]);
    fprintf(f, "    {NULL, NULL}\n};\n\n");
    fprintf(f, "const snell_shader_pack %s_pack = {packed, sizeof packed, unpacked, sizeof unpacked};\n", argv[2]);
    fclose(f);
    free(out);
    free(all);
    free(offsets);
    return 0;
}
