/* SPDX-License-Identifier: MIT */
/* cli_progress.c — the progress line with an ETA (cli_progress.h). */
#define _POSIX_C_SOURCE 200809L /* fileno */
#include "cli_progress.h"
#include "cli_time.h"

#include <stdio.h>
#include <unistd.h>

int cli_progress_wanted(int quiet)
{
    return !quiet && isatty(fileno(stderr));
}

void cli_progress_start(cli_progress *p, const char *what)
{
    snprintf(p->what, sizeof p->what, "%s", what);
    p->t0 = cli_now_ms();
}

void cli_progress_report(double done, void *user)
{
    const cli_progress *p = (const cli_progress *)user;
    double s = (cli_now_ms() - p->t0) / 1000.0;
    /* \033[K clears what a longer earlier line left on the right */
    if (done >= 1.0)
        fprintf(stderr, "\r    %s: done in %.1f s\033[K\n", p->what, s);
    else if (done > 0.0)
        fprintf(stderr, "\r    %s: %3.0f%% (%.1f s, ETA %.1f s)\033[K", p->what, 100.0 * done, s,
                s * (1.0 - done) / done);
    fflush(stderr);
}
