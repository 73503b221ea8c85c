/* SPDX-License-Identifier: MIT */
/* background_stage.c — the background goes last, where the depth buffer is
 * still clear, so pixels covered by glass or opaque objects are never
 * shaded twice. Exit-direction output always needs it (misses = the view
 * ray). */
#include "render/stages.h"
#include "core/gl.h"
#include "frame/env.h"

#include <string.h>

static int wanted(const snell__frame *f, const void *state)
{
    (void)state;
    return f->fd->draw_background >= 0 || f->sv->out != SNELL__OUT_COLOR;
}

static snell_status run(snell__frame *f, void *state)
{
    const snell__services *sv = f->sv;
    snell_status st = SNELL_OK;
    mat4 rot, vp, inv; /* inv: a pixel's far-plane point to the direction it sees */
    int paraboloid = snell__env_lookup_paraboloid(sv->env_lookup, 0);
    unsigned tex = f->fd->env->texture;
    (void)state;
    if (f->sc->view.view_axis[3] > 0.5f) {
        /* orthographic: every view ray, so every background pixel, looks
         * along the axis (as the reference's rays do) */
        glm_mat4_zero(inv);
        memcpy(inv[3], f->sc->view.view_axis, 3 * sizeof(float));
        inv[3][3] = 1.0f;
    } else {
        glm_mat4_copy(f->sc->view.view, rot);
        rot[3][0] = rot[3][1] = rot[3][2] = 0.0f;
        snell__mat4_mul((const float *)f->sc->view.proj, (const float *)rot, (float *)vp);
        snell__mat4_inv((const float *)vp, (float *)inv);
    }
    if (paraboloid) st = snell__env_paraboloid(sv->ctx, sv->dp, f->fd->env, &tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(paraboloid ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_CUBE_MAP, tex);
    if (st == SNELL_OK)
        st = snell__composite_background_lookup(sv->ctx, sv->comp, sv->out, paraboloid, (const float *)inv);
    f->s->background_drawn = 1;
    f->s->background_paraboloid = paraboloid;
    return st;
}

const snell__stage snell__stage_background = {
    .name = "background",
    .wanted = wanted,
    .run = run,
};
