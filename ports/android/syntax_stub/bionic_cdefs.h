/* SPDX-License-Identifier: MIT */
/* SYNTAX-CHECK STUB, not part of any build. Debian has no NDK: the syntax
 * check (ports/android/syntax_check.sh) compiles the port against Debian's
 * Android headers with aarch64 glibc standing in for bionic's C headers.
 * These are the bionic <sys/cdefs.h> macros those Android headers use and
 * glibc lacks, with bionic's meaning for a build at the minimum API level:
 * nothing. Force-included (-include) before every file. */
#ifndef SNELL_SYNTAX_STUB_BIONIC_CDEFS_H
#define SNELL_SYNTAX_STUB_BIONIC_CDEFS_H
#define __INTRODUCED_IN(api_level)
#define __RENAME_IF_FILE_OFFSET64(func)
#endif
