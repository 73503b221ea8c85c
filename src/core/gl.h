/* SPDX-License-Identifier: MIT */
/* gl.h — the one place GLES headers are included. The library targets
 * OpenGL ES 3.0 core; everything newer is an extension probed by name. */
#ifndef SNELL_GL_H
#define SNELL_GL_H

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>

/* Every texture unit snell selects or binds on goes through these
 * (core/glstate.c), so that a frame saves, resets and restores only the
 * units it uses. */
void snell__active_texture(GLenum unit);
void snell__bind_texture(GLenum target, GLuint texture);
void snell__bind_sampler(GLuint unit, GLuint sampler);
#ifndef SNELL_GL_UNTRACKED
#define glActiveTexture snell__active_texture
#define glBindTexture snell__bind_texture
#define glBindSampler snell__bind_sampler
#endif

/* The bound texture of target samples its nearest texel (texelFetch or exact
 * look-ups), clamped at its edges where clamp is nonzero. */
void snell__texture_nearest(GLenum target, int clamp);

#endif
