/* SPDX-License-Identifier: MIT */
/* gl.h — the one place GLES headers are included. The library targets
 * OpenGL ES 3.0 core; everything newer is an extension probed by name. */
#ifndef SNELL_GL_H
#define SNELL_GL_H

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>

#endif
