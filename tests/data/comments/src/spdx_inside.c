/* SPDX-License-Identifier: MIT
 * spdx_inside.c — the licence in the header comment itself; ten lines
 * in all (line 3)
 * in all (line 4)
 * in all (line 5)
 * in all (line 6)
 * in all (line 7)
 * in all (line 8)
 * in all (line 9)
 * pass. */
int spdx_inside;
