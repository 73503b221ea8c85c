/* SPDX-License-Identifier: MIT */
/* cli_method.h — the library's method registry as the CLI ports parse and
 * show it: method names, each method's parameters with their ranges and the
 * defaults the library resolves (no copies of either kept here). */
#ifndef SNELL_CLI_METHOD_H
#define SNELL_CLI_METHOD_H

#include "snell/snell.h"

#include <stdio.h>

/* "auto" or a registry name -> *out, 1. Else prints "PROG: unknown method 'x';
 * methods: auto, single, ..." to stderr and returns 0. */
int cli_method_parse(const char *prog, const char *name, snell_method *out);

/* The registry entry that has a parameter called name, searching methods in
 * registry order from index *start (updated past the match); NULL when none. */
const snell_method_info *cli_param_owner(const char *name, int *start);

/* Sets parameter name = value (a number or, for enums, a value name) on every
 * method of the registry that has it (snell_glass_set_param). 1 on success;
 * else prints "PROG: <library message> (value names)" and returns 0 (also
 * when no method has the parameter). */
int cli_param_set(const char *prog, snell_glass_material *m, const char *name, const char *value);
/* The same for one method's parameter only. */
int cli_param_set_one(const char *prog, snell_glass_material *m, snell_method method, const char *name,
                      const char *value);

/* Writes every method of the registry: "method NAME: summary", what it needs,
 * and each parameter as "<indent><prefix>NAME<suffix>  help, range (default D)"
 * with the registry's resolved default. */
void cli_method_help(FILE *f, const char *indent, const char *prefix, const char *suffix);

/* A parameter value as text: its value name for enums, else the number (in buf). */
const char *cli_param_value_str(const snell_param_info *p, int value, char *buf, size_t n);

#endif
