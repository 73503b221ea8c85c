/* SPDX-License-Identifier: MIT */
/* matrix.c — whether a model or camera matrix has an inverse in float, and
 * if not, whether it is singular or its determinant only leaves float's range. */
#include "core/core.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

static int all_finite(const float *v, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* The determinant of a column-major 4x4 in double, where float's overflows
 * or underflows (2x2 minors of the first two and last two rows). */
static double det_double(const float m[16])
{
    double a[16], s[6], c[6];
    int i;
    for (i = 0; i < 16; i++) a[i] = m[i];
    s[0] = a[0] * a[5] - a[4] * a[1];
    s[1] = a[0] * a[9] - a[8] * a[1];
    s[2] = a[0] * a[13] - a[12] * a[1];
    s[3] = a[4] * a[9] - a[8] * a[5];
    s[4] = a[4] * a[13] - a[12] * a[5];
    s[5] = a[8] * a[13] - a[12] * a[9];
    c[0] = a[2] * a[7] - a[6] * a[3];
    c[1] = a[2] * a[11] - a[10] * a[3];
    c[2] = a[2] * a[15] - a[14] * a[3];
    c[3] = a[6] * a[11] - a[10] * a[7];
    c[4] = a[6] * a[15] - a[14] * a[7];
    c[5] = a[10] * a[15] - a[14] * a[11];
    return s[0] * c[5] - s[1] * c[4] + s[2] * c[3] + s[3] * c[2] - s[4] * c[1] + s[5] * c[0];
}

void snell__mat4_inv(const float m[16], float inv[16])
{
    glm_mat4_inv((vec4 *)(void *)m, (vec4 *)(void *)inv);
}

void snell__mat4_mul(const float a[16], const float b[16], float out[16])
{
    glm_mat4_mul((vec4 *)(void *)a, (vec4 *)(void *)b, (vec4 *)(void *)out);
}

int snell__matrix_invertible(const float m[16], char *why, size_t n)
{
    mat4 a, inv;
    float det;
    double d = det_double(m);
    memcpy(a, m, sizeof a);
    det = glm_mat4_det(a);
    if (fabsf(det) > 0.0f && isfinite(det)) {
        snell__mat4_inv((const float *)a, (float *)inv);
        if (all_finite((const float *)inv, 16)) return 1;
    }
    /* an invertible matrix whose determinant float cannot hold is no singular one */
    if (why && d != 0.0 && isfinite(d) && fabs(d) > 1.0)
        snprintf(why, n, "is too large for float (its determinant %g overflows)", d);
    else if (why && d != 0.0 && isfinite(d))
        snprintf(why, n, "is singular in float (its determinant %g underflows)", d);
    else if (why)
        snprintf(why, n, "is singular (determinant %g)", d);
    return 0;
}
