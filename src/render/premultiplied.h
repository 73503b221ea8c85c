/* premultiplied.h — premultiplied alpha output: the kernel hook
 * SNELL_PREMULTIPLIED (common/output.glsl), an entry of the stage table that
 * draws nothing of its own. */
#ifndef SNELL_PREMULTIPLIED_H
#define SNELL_PREMULTIPLIED_H

#include "frame/stage.h"

int snell__premultiplied_wanted(const snell__frame *f);
unsigned snell__premultiplied_variant(const snell__frame *f, const snell__object *o);
extern const snell__kernel_hook snell__premultiplied_hook;

#endif
