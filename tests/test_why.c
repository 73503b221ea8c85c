/* SPDX-License-Identifier: MIT */
/* test_why — the reasons people read (snell__why, core/core.c): a text that
 * fits is kept whole; a longer one is cut at the buffer's end and says so
 * with "...", never through a UTF-8 character; appending after a cut one
 * (as the water floor appends to the caustics reason) cannot overrun. */
#include "test_util.h"
#include "core/core.h"

#include <string.h>

int main(void)
{
    char b[SNELL_REASON_SIZE], small[8];
    memset(b, 'x', sizeof b);
    snell__why(b, sizeof b, "made: %d glass casting", 3);
    CHECK(!strcmp(b, "made: 3 glass casting"), "whole: '%s'", b);

    /* exactly n - 1 bytes: whole, no marker */
    snell__why(small, sizeof small, "%s", "1234567");
    CHECK(!strcmp(small, "1234567"), "fits exactly: '%s'", small);
    /* one byte more: cut, and says so */
    snell__why(small, sizeof small, "%s", "12345678");
    CHECK(!strcmp(small, "1234..."), "cut: '%s'", small);
    /* a word cut in the middle is followed by the marker, not by the end of the text */
    snell__why(small, sizeof small, "a %s", "blurred");
    CHECK(!strcmp(small, "a bl..."), "cut word: '%s'", small);
    /* a two-byte character (U+00D7, the multiplication sign) over the cut goes whole */
    snell__why(small, sizeof small, "%s", "1234\xc3\x97zzz");
    CHECK(!strcmp(small, "1234..."), "UTF-8 kept whole: '%s'", small);
    snell__why(small, sizeof small, "%s", "123\xc3\x97zzzz");
    CHECK(!strcmp(small, "123..."), "UTF-8 not split: '%s'", small);

    /* a caustics reason longer than the buffer (render/caustics.c's format), then the water floor's part after it */
    snell__why(b, sizeof b, "made: %d glass casting%s%s; %s; %d opaque lit%s; paths: %d BVH, %d depth maps%s", 8,
               " (the spot light inside a bounding sphere: no photons)", " (clear ones pass)",
               "4096x4096 RGBA32F light map (texels > caster radius/4: blurred)", 16, " (light-frame caustic map)", 4, 4,
               ", 4 chained (beams overlap: 2 groups), 1 alone: over 4 overlap");
    CHECK(strlen(b) == sizeof b - 1 && !strcmp(b + sizeof b - 4, "..."), "long reason not marked: '%s'", b);
    {
        size_t used = strlen(b);
        snell__why(b + used, sizeof b - used, "; water floor: made");
        CHECK(strlen(b) == sizeof b - 1, "appended past the end: %zu", strlen(b));
    }
    /* sizes too small to mark: still terminated */
    snell__why(small, 3, "%s", "abcdef");
    CHECK(!strcmp(small, "ab"), "n = 3: '%s'", small);
    snell__why(small, 1, "%s", "abcdef");
    CHECK(small[0] == '\0', "n = 1");
    snell__why(NULL, 8, "%s", "x"); /* nothing to write to: no crash */
    return test_finish();
}
