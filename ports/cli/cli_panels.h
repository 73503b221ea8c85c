/* SPDX-License-Identifier: MIT */
/* cli_panels.h — the ports' panels file (docs/panels.md "snell-render"): one
 * glass panel a line, key=value fields named as snell_panel's, '#' comments.
 * Read by snell-render --panels and the kiosk's --panels. */
#ifndef SNELL_CLI_PANELS_H
#define SNELL_CLI_PANELS_H

#include "snell/snell.h"

#include <stddef.h>

#define CLI_PANELS_MAX_BYTES (1 << 20) /* a file of SNELL_MAX_PANELS full lines fits */

/* A panels file read: the panels and the line each came from. */
typedef struct cli_panels {
    snell_panel *panels;
    int *lines; /* lines[i]: panels[i]'s line in the file (1-based) */
    int count;
} cli_panels;

/* Parses text (NUL-terminated) into *out (malloc'd; free with
 * cli_panels_free). 0 with "NAME line N: why" in why for a bad line. Values
 * are checked for form (numbers, counts) here and for range by snell_render,
 * whose message cli_panels_where maps back to the line. */
int cli_panels_parse(const char *text, const char *name, cli_panels *out, char *why, size_t why_size);
/* The same from the file at path (regular, at most CLI_PANELS_MAX_BYTES). */
int cli_panels_read(const char *path, cli_panels *out, char *why, size_t why_size);
/* " (line N of NAME)" for a library message naming "panels[i]", else "". */
const char *cli_panels_where(const cli_panels *p, const char *name, const char *msg, char *buf, size_t n);
void cli_panels_free(cli_panels *p);

#endif
