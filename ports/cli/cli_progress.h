/* SPDX-License-Identifier: MIT */
/* cli_progress.h — the ports' progress line for long work (the reference
 * tracer, through snell_ref_params.progress): percent done, time so far and
 * an ETA on stderr, redrawn in place; only on a terminal and never with -q,
 * so logs and pipes get nothing. The library itself never prints. */
#ifndef SNELL_CLI_PROGRESS_H
#define SNELL_CLI_PROGRESS_H

typedef struct cli_progress {
    char what[96];                 /* "reference FULL" */
    double t0;                     /* cli_now_ms() at the start */
} cli_progress;

/* 1 when progress should be shown: not quiet and stderr is a terminal. */
int cli_progress_wanted(int quiet);
/* Starts timing the work called what. */
void cli_progress_start(cli_progress *p, const char *what);
/* A snell_ref_progress_fn; user is a started cli_progress. Prints
 * "\r  WHAT: 42% (3.1 s, ETA 4.3 s)" and, at 1.0, "WHAT: done in 7.4 s\n". */
void cli_progress_report(double done, void *user);

#endif
