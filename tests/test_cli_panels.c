/* SPDX-License-Identifier: MIT */
/* test_cli_panels — the ports' panels file (ports/cli/cli_panels.c): every
 * field read into snell_panel, defaults left zero, and hostile text refused
 * with its line and the reason: unknown keys, wrong counts, NaN, a key twice,
 * a line past its bound, more than SNELL_MAX_PANELS panels, control
 * characters, an empty file; the library's "panels[i]" mapped to its line. */
#include "test_util.h"
#include "cli_panels.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* text must be refused with a message holding want. */
static void refused(const char *text, const char *want)
{
    cli_panels p;
    char why[512] = "";
    int ok = cli_panels_parse(text, "f.txt", &p, why, sizeof why);
    CHECK(!ok && strstr(why, want) && !p.panels && !p.count, "'%.60s': want \"%s\", got %d \"%s\"", text, want, ok,
          why);
}

int main(void)
{
    cli_panels p;
    char why[512], where[128];
    char *big;
    size_t k;
    int ok = cli_panels_parse("# header\n\n  center=640,360 size=400,240 radius=40 ior=1.5 frost=4 group=1  # a\r\n"
                              "center=1,2 size=3,4 radius=1,2,3,4 exponent=4 thickness=9 bevel=-1 "
                              "bevel_profile=squircle dispersion=0.5 tint=1,0.5,0.25,0.2 rim=-1 light=0,1,1 "
                              "shadow=8,0.5,1,-2 merge=-1\n"
                              "center=0,0 size=1,1 shadow=none\n",
                              "f.txt", &p, why, sizeof why);
    CHECK(ok && p.count == 3, "three panels: %s", ok ? "" : why);
    if (ok && p.count == 3) {
        const snell_panel *a = &p.panels[0], *b = &p.panels[1];
        CHECK(a->center[0] == 640 && a->center[1] == 360 && a->size[0] == 400 && a->size[1] == 240, "centre, size");
        CHECK(a->radius[0] == 40 && a->radius[3] == 40 && a->ior == 1.5f && a->frost == 4 && a->group == 1,
              "one radius for every corner, ior, frost, group");
        CHECK(a->exponent == 0 && a->bevel == 0 && a->tint[3] == 0 && a->shadow[0] == 0, "the rest left 0");
        CHECK(b->radius[0] == 1 && b->radius[1] == 2 && b->radius[2] == 3 && b->radius[3] == 4, "four radii in order");
        CHECK(b->exponent == 4 && b->thickness == 9 && b->bevel == -1 && b->bevel_profile == SNELL_PANEL_BEVEL_SQUIRCLE,
              "exponent, thickness, bevel, profile");
        CHECK(b->dispersion == 0.5f && b->tint[2] == 0.25f && b->tint[3] == 0.2f && b->rim == -1 && b->light[2] == 1,
              "dispersion, tint, rim, light");
        CHECK(b->shadow[0] == 8 && b->shadow[3] == -2 && b->merge == -1, "shadow, merge");
        CHECK(p.panels[2].shadow[0] < 0, "shadow=none: a negative radius");
        CHECK(p.lines[0] == 3 && p.lines[1] == 4 && p.lines[2] == 5, "lines %d %d %d", p.lines[0], p.lines[1],
              p.lines[2]);
        cli_panels_where(&p, "f.txt", "panels[1].ior must be 1..3 (0 = 1.5)", where, sizeof where);
        CHECK(!strcmp(where, " (line 4 of f.txt)"), "where: '%s'", where);
        cli_panels_where(&p, "f.txt", "panels[7].ior", where, sizeof where);
        CHECK(!where[0], "an index past the file names no line");
    }
    cli_panels_free(&p);

    refused("center=1,2 size=3,4\ncenter=1,2\n", "f.txt line 2: a panel needs size=W,H");
    refused("size=3,4\n", "line 1: a panel needs center=X,Y");
    refused("center=1,2 size=3,4 blur=2\n", "line 1: unknown key 'blur' (center, size,");
    refused("center=1,2 size=3\n", "line 1: size wants W,H (finite), got '3'");
    refused("center=1,2 size=nan,4\n", "size wants W,H");
    refused("center=1,2 size=3,4 ior=inf\n", "ior wants a number");
    refused("center=1,2 size=3,4 ior=1e99\n", "ior wants a number");
    refused("center=1,2 size=3,4 radius=1,2\n", "radius wants R or R0,R1,R2,R3");
    refused("center=1,2 size=3,4 tint=1,1,1\n", "tint wants R,G,B,A");
    refused("center=1,2 size=3,4 ior=1.5 ior=1.4\n", "ior given twice");
    refused("center=1,2 size=3,4 group=1 group=2\n", "group given twice");
    refused("center=1,2 size=3,4 group=-1\n", "group wants an integer >= 0");
    refused("center=1,2 size=3,4 bevel_profile=round\n", "bevel_profile wants circular or squircle");
    refused("center=1,2 size=3,4 frost\n", "'frost' is not key=value");
    refused("center=1,2 size=3,4 =3\n", "'=3' is not key=value");
    refused("center=1,2 size=3,4 ior=\n", "'ior=' is not key=value");
    refused("center=1,2 size=3,4 ior=1.5,\n", "ior wants a number");
    refused("center=1,2 size=3,4 \x1b[2J\n", "line 1: a control character");
    refused("# nothing\n\n", "f.txt: no panels");
    refused("", "f.txt: no panels");
    /* a line past 1,024 bytes, and one panel past SNELL_MAX_PANELS */
    big = (char *)malloc(64 * (SNELL_MAX_PANELS + 2));
    memset(big, ' ', 2000);
    memcpy(big + 2000, "center=1,2 size=3,4\n", 21);
    refused(big, "line 1: longer than 1024 bytes");
    for (k = 0; k <= SNELL_MAX_PANELS; k++) memcpy(big + 20 * k, "center=1,2 size=3,4\n", 21);
    refused(big, "line 4097: more than 4096 panels");
    free(big);
    /* a file that is no regular file, and one that is not there */
    CHECK(!cli_panels_read(".", &p, why, sizeof why) && strstr(why, "a directory"), "a directory: %s", why);
    CHECK(!cli_panels_read("no_such_panels.txt", &p, why, sizeof why) && strstr(why, "No such file"), "missing: %s",
          why);
    return test_finish();
}
