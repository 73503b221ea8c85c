/* SPDX-License-Identifier: MIT */
/* planted.c — comments check_comments.sh must fail on (tests/scripts.cmake,
 * source_comments_fail), beside legitimate ones it must pass. */
#define A 1 /* the faster path: 12% cheaper */
#define B 2 /* mean error 0.4 degrees against FULL */
#define C 3 /* It was slower with a stack */
#define D 4 /* the clears were ~3% of a frame */
#define E 5 /* a miss per segment was a tenth of the frame */
#define F 6 /* within 1% of the extent, with 5% to spare, fits 95% of the budget */
#define G 7 /* share of pixels with error > 1 degree; the camera it was drawn with */
static const char *const msg = "12% cheaper, it was 5"; /* a string is code, not a comment */
