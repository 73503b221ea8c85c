/* SPDX-License-Identifier: MIT */
/* planted.h — a public header's comment is checked too: this was issue-free. */
