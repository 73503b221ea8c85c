/* SPDX-License-Identifier: MIT */
/* cli_input.h — what the tools read from a user and echo back: a whole input
 * file (regular files only, opened without blocking on a FIFO, bounded in
 * size), and text made safe to print on a terminal. */
#ifndef SNELL_CLI_INPUT_H
#define SNELL_CLI_INPUT_H

#include <stddef.h>

/* A read-only descriptor of the regular file at path, -1 with *why ("a
 * directory", "not a regular file" or the system's reason) for anything else. */
int cli_open_input(const char *path, char *why, size_t why_size);
/* The file at path, NUL-terminated (its length in *len), malloc'd; NULL with
 * *why ("a directory", "not a regular file", "larger than N bytes", or the
 * system's reason) when it is not a regular file of at most max bytes. */
char *cli_read_input(const char *path, size_t max, size_t *len, char *why, size_t why_size);
/* Control characters (C0 but tab, DEL, UTF-8 C1) in s become '?', in place. */
void cli_scrub(char *s);
/* 1 if s holds a control character (a CR at its end aside). */
int cli_has_control(const char *s);
/* 0 with one message naming prog if an argument holds a control character:
 * the tools echo their arguments, and a terminal acts on those. */
int cli_args_clean(const char *prog, int argc, char **argv);
/* s scrubbed, and cut with "..." past n - 4 bytes, into buf of n bytes; returns buf. */
const char *cli_safe(const char *s, char *buf, size_t n);

#endif
