/* SPDX-License-Identifier: MIT */
/* panels_diff — the ports' panels tests' pixel check: two PNGs of one size,
 * a frame without panels and one with them, and the box (x0,y0,x1,y1 in
 * pixels from the bottom-left, as snell_panel's) where a panel lies. Exit 0
 * when most pixels inside the box differ and every pixel farther than MARGIN
 * outside it is equal; 1 if not; 2 on bad input.
 *
 *   panels_diff PLAIN.png PANELS.png X0,Y0,X1,Y1 MARGIN */
#include "snell/snell.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    uint8_t *a = NULL, *b = NULL;
    int wa, ha, wb, hb, x, y, margin, inside = 0, inside_diff = 0, outside = 0, outside_diff = 0, rc = 2;
    float box[4];
    if (argc != 5 || sscanf(argv[3], "%f,%f,%f,%f", &box[0], &box[1], &box[2], &box[3]) != 4 ||
        sscanf(argv[4], "%d", &margin) != 1) {
        fprintf(stderr, "usage: panels_diff PLAIN.png PANELS.png X0,Y0,X1,Y1 MARGIN\n");
        return 2;
    }
    if (snell_image_read(argv[1], &wa, &ha, &a) != SNELL_OK || snell_image_read(argv[2], &wb, &hb, &b) != SNELL_OK) {
        fprintf(stderr, "panels_diff: %s\n", snell_last_error(NULL));
        goto done;
    }
    if (wa != wb || ha != hb) {
        fprintf(stderr, "panels_diff: %dx%d against %dx%d\n", wa, ha, wb, hb);
        goto done;
    }
    for (y = 0; y < ha; y++)
        for (x = 0; x < wa; x++) {
            float px = x + 0.5f, py = (float)(ha - 1 - y) + 0.5f; /* PNG rows top first */
            size_t i = 4 * ((size_t)y * (size_t)wa + (size_t)x);
            int differ = memcmp(a + i, b + i, 3) != 0;
            if (px > box[0] && px < box[2] && py > box[1] && py < box[3]) {
                inside++;
                inside_diff += differ;
            } else if (px < box[0] - margin || px > box[2] + margin || py < box[1] - margin || py > box[3] + margin) {
                outside++;
                outside_diff += differ;
            }
        }
    printf("panels_diff: %d of %d pixels inside the box differ, %d of %d outside it\n", inside_diff, inside,
           outside_diff, outside);
    rc = inside > 0 && inside_diff * 2 > inside && outside_diff == 0 ? 0 : 1;
done:
    snell_image_free(a);
    snell_image_free(b);
    return rc;
}
