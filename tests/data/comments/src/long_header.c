/* SPDX-License-Identifier: MIT */
/* long_header.c — a header of eleven lines: one more than a file header may
 * have (line 3)
 * have (line 4)
 * have (line 5)
 * have (line 6)
 * have (line 7)
 * have (line 8)
 * have (line 9)
 * have (line 10)
 * have (line 11)
 * take. */
int long_header;
