/* SPDX-License-Identifier: MIT */
/* test_stage_seam — the stage seam's variant bits (frame/stage.h): each kernel
 * hook's bits follow the previous hook's in the table's order, from
 * SNELL__GLASS_STAGE_SHIFT, none shared, none numbered by hand; a table whose
 * hooks take more bits than a variant has is refused with SNELL_E_LIMIT; the
 * frame's own table fits, its hooks' masks disjoint and contiguous. */
#include "test_util.h"
#include "frame/glass_program.h"
#include "render/stages.h"

#include <string.h>

static const char *defines(unsigned bits)
{
    (void)bits;
    return "";
}

int main(void)
{
    static snell__program_cache cache;
    snell__kernel_hook one = {1, defines, NULL, 0, NULL}, two = {2, defines, NULL, 0, NULL}, wide = {7, defines, NULL,
                                                                                                  0, NULL};
    snell__stage a, b, c, none;
    const snell__stage *table[4];
    unsigned used = 0, next;
    int i, hooks = 0;
    memset(&a, 0, sizeof a), memset(&b, 0, sizeof b), memset(&c, 0, sizeof c), memset(&none, 0, sizeof none);
    a.kernel = &one, b.kernel = &two, c.kernel = &one;
    /* a, a stage without a hook, b (two bits), c: bits 3, -, 4..5, 6 */
    table[0] = &a, table[1] = &none, table[2] = &b, table[3] = &c;
    CHECK_OK(snell__program_cache_hooks(NULL, &cache, table, NULL, 4));
    CHECK(cache.hooks.shift[0] == SNELL__GLASS_STAGE_SHIFT && cache.hooks.shift[2] == SNELL__GLASS_STAGE_SHIFT + 1 &&
              cache.hooks.shift[3] == SNELL__GLASS_STAGE_SHIFT + 3,
          "shifts %u %u %u", cache.hooks.shift[0], cache.hooks.shift[2], cache.hooks.shift[3]);
    {
        unsigned variant = SNELL__GLASS_ENV_PARABOLOID | 1u | (2u << cache.hooks.shift[2]) | (1u << cache.hooks.shift[3]);
        CHECK(snell__kernel_hook_bits(&cache.hooks, 0, variant) == 0, "a's bits: none set");
        CHECK(snell__kernel_hook_bits(&cache.hooks, 1, variant) == 0, "a stage without a hook has no bits");
        CHECK(snell__kernel_hook_bits(&cache.hooks, 2, variant) == 2, "b's bits: 2");
        CHECK(snell__kernel_hook_bits(&cache.hooks, 3, variant) == 1, "c's bits: 1");
    }
    /* Three hooks of 7 bits (21 + the variant's own 3) do not fit. */
    a.kernel = b.kernel = c.kernel = &wide;
    CHECK(snell__program_cache_hooks(NULL, &cache, table, NULL, 4) == SNELL_E_LIMIT, "24 variant bits accepted");
    CHECK(strstr(snell_last_error(NULL), "24 variant bits") != NULL, "message: %s", snell_last_error(NULL));

    /* The frame's table: every hook's mask above the variant's own bits, next to the previous hook's. */
    CHECK_OK(snell__program_cache_hooks(NULL, &cache, snell__stages, NULL, snell__stage_count));
    next = SNELL__GLASS_STAGE_SHIFT;
    for (i = 0; i < snell__stage_count; i++) {
        const snell__kernel_hook *h = snell__stages[i]->kernel;
        unsigned mask;
        if (!h || !h->variant_bits) continue;
        hooks++;
        mask = ((1u << h->variant_bits) - 1u) << cache.hooks.shift[i];
        CHECK(cache.hooks.shift[i] == next, "%s's bits start at %u, not %u", snell__stages[i]->name,
              cache.hooks.shift[i], next);
        CHECK(!(mask & used), "%s's bits overlap another hook's", snell__stages[i]->name);
        CHECK(h->defines && h->uniforms, "%s's hook has its defines and uniforms", snell__stages[i]->name);
        used |= mask;
        next += (unsigned)h->variant_bits;
    }
    CHECK(next <= SNELL__GLASS_VARIANT_BITS, "the table's hooks take %u bits", next);
    CHECK(hooks >= 2, "the frame's table has kernel hooks (%d)", hooks);
    return test_finish();
}
