/* SPDX-License-Identifier: MIT */
/* cli_opts.h — the tools' one way to read flags: getopt_long, with one
 * message per error ("PROG: unknown option '--x'; see --help", "PROG: --frames
 * needs a value; see --help") instead of getopt's own. */
#ifndef SNELL_CLI_OPTS_H
#define SNELL_CLI_OPTS_H

#include <getopt.h>

/* getopt_long(argc, argv, shortopts, longopts) with its messages off; on an
 * unknown option or a missing value prints the message (see is the help
 * to point at, e.g. "--help" or "--budget --help") and returns '?'. Call with
 * optind = 1 first (cli_opts_reset). */
int cli_getopt(const char *prog, const char *see, int argc, char **argv, const char *shortopts,
               const struct option *longopts);
/* Starts a new parse (getopt's state is global). */
void cli_opts_reset(void);
/* 1 if any argument is -h or --help (wherever it is, even after a bad one). */
int cli_wants_help(int argc, char **argv);

#endif
