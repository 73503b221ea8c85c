/* SPDX-License-Identifier: MIT */
/* cli_opts.c — getopt_long with one message per error (cli_opts.h). */
#include "cli_opts.h"

#include <stdio.h>
#include <string.h>

void cli_opts_reset(void)
{
    optind = 1;
    opterr = 0;
}

int cli_wants_help(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return 1;
    return 0;
}

int cli_getopt(const char *prog, const char *see, int argc, char **argv, const char *shortopts,
               const struct option *longopts)
{
    char opts[128];
    const char *arg;
    int c;
    /* a leading ':' makes a missing value ':' rather than '?' */
    snprintf(opts, sizeof opts, ":%s", shortopts);
    opterr = 0;
    c = getopt_long(argc, argv, opts, longopts, NULL);
    if (c != '?' && c != ':') return c;
    arg = optind > 1 && optind - 1 < argc ? argv[optind - 1] : "";
    if (c == ':') {
        /* the option whose value is missing: a long one by its text, a short one by its letter */
        if (strncmp(arg, "--", 2) == 0) fprintf(stderr, "%s: %s needs a value; see %s\n", prog, arg, see);
        else fprintf(stderr, "%s: -%c needs a value; see %s\n", prog, optopt, see);
    } else if (optopt > 0 && strncmp(arg, "--", 2) != 0) {
        fprintf(stderr, "%s: unknown option '-%c'; see %s\n", prog, optopt, see);
    } else {
        fprintf(stderr, "%s: unknown option '%s'; see %s\n", prog, arg, see);
    }
    return '?';
}
