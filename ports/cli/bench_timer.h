/* SPDX-License-Identifier: MIT */
/* bench_timer.h — GPU frame time with GL_EXT_disjoint_timer_query, when the
 * context has it; one query in flight (snell-bench ends every frame with glFinish). */
#ifndef SNELL_BENCH_TIMER_H
#define SNELL_BENCH_TIMER_H

#include "snell/snell.h"

/* 1: available (resolves the entry points and makes the query object);
 * 0: not available; -1: advertised by a software rasteriser (llvmpipe),
 * where there is no GPU time to report and the query's figure is not
 * reliable (issue 28 saw 1.31 ms beside an 84 ms frame; on Mesa 22.3 here it
 * read 8.98 ms beside 11.96 for single on the bunny at 256^2, 451.9 beside
 * 456.0 for peel): not used, the wall clock is what snell-bench reports. */
int bench_timer_init(snell_ctx *ctx);
void bench_timer_begin(void);
void bench_timer_end(void);
/* After glFinish: the frame's GPU time in ms, or -1 (disjoint or unavailable). */
double bench_timer_read(void);

#endif
