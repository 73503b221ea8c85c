/* SPDX-License-Identifier: MIT */
/* cli_system.h — what a benchmark run records so that two boards' runs can be
 * compared: the build (version, commit), the GL driver, the kernel and the
 * board, as the system states them; and the tools' --version line. */
#ifndef SNELL_CLI_SYSTEM_H
#define SNELL_CLI_SYSTEM_H

#include <stdio.h>

typedef struct cli_system {
    const char *version, *commit;  /* the build's (snell_build_info.h) */
    char gl_vendor[128], gl_renderer[256], gl_version[128]; /* glGetString; "unknown" without a context */
    char kernel[512];              /* uname: sysname release version machine */
    char board[256];               /* the board's model, "" where the system does not say */
    char board_from[64];           /* the file it came from, "" when none */
} cli_system;

/* Fills s; the GL strings are read from the GL context current on this thread. */
void cli_system_read(cli_system *s);
/* "PROG VERSION (commit C)" on stdout: every tool's --version. Returns 0 (the exit status). */
int cli_print_version(const char *prog);

#endif
