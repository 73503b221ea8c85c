/* bench_timer.h — GPU frame time with GL_EXT_disjoint_timer_query, when the
 * context has it; one query in flight (snell-bench ends every frame with glFinish). */
#ifndef SNELL_BENCH_TIMER_H
#define SNELL_BENCH_TIMER_H

#include "snell/snell.h"

/* Available? (resolves the entry points and makes the query object) */
int bench_timer_init(snell_ctx *ctx);
void bench_timer_begin(void);
void bench_timer_end(void);
/* After glFinish: the frame's GPU time in ms, or -1 (disjoint or unavailable). */
double bench_timer_read(void);

#endif
