/* SPDX-License-Identifier: MIT */
/* lifecycle — the Android port's create/destroy rules (lifecycle.h). */
#include "lifecycle.h"

#include <string.h>

void lifecycle_init(lifecycle_state *s) { memset(s, 0, sizeof *s); }

/* What is missing for drawing, given that a window exists: the context (and
 * with it the GL objects, made once the surface is current), the surface. */
static unsigned create_what_is_missing(lifecycle_state *s)
{
    unsigned act = 0;
    if (!s->context) {
        act |= LIFECYCLE_CREATE_CONTEXT;
        s->context = 1;
        s->generation++;
    }
    if (!s->surface) {
        act |= LIFECYCLE_CREATE_SURFACE;
        s->surface = 1;
    }
    if (!s->gl_objects) {
        act |= LIFECYCLE_CREATE_GL_OBJECTS;
        s->gl_objects = 1;
    }
    return act;
}

static unsigned destroy_all(lifecycle_state *s)
{
    unsigned act = 0;
    if (s->surface) act |= LIFECYCLE_DESTROY_SURFACE;
    if (s->gl_objects) act |= LIFECYCLE_DESTROY_GL_OBJECTS;
    if (s->context) act |= LIFECYCLE_DESTROY_CONTEXT;
    s->surface = s->gl_objects = s->context = 0;
    return act;
}

unsigned lifecycle_step(lifecycle_state *s, lifecycle_event ev)
{
    unsigned act = 0;
    if (s->destroyed) return 0;
    switch (ev) {
    case LIFECYCLE_START:
    case LIFECYCLE_STOP: break; /* a stopped app keeps its context, as a paused one */
    case LIFECYCLE_RESUME: s->resumed = 1; break;
    case LIFECYCLE_PAUSE: s->resumed = 0; break;
    case LIFECYCLE_WINDOW_CREATED:
        if (s->surface) { /* a new window without the old one's destroy: its surface goes */
            act = LIFECYCLE_DESTROY_SURFACE;
            s->surface = 0;
        }
        s->window = 1;
        act |= create_what_is_missing(s);
        break;
    case LIFECYCLE_WINDOW_DESTROYED:
        /* The surface must be gone before onNativeWindowDestroyed returns. */
        if (s->surface) act = LIFECYCLE_DESTROY_SURFACE;
        s->window = s->surface = 0;
        break;
    case LIFECYCLE_CONTEXT_LOST:
        if (!s->context) break;
        act = destroy_all(s);
        if (s->window) act |= create_what_is_missing(s);
        break;
    case LIFECYCLE_DESTROY:
        act = destroy_all(s);
        s->window = s->resumed = 0;
        s->destroyed = 1;
        break;
    default: break;
    }
    return act;
}

int lifecycle_should_render(const lifecycle_state *s)
{
    return s->resumed && s->surface && s->gl_objects && !s->destroyed;
}

const char *lifecycle_event_str(lifecycle_event ev)
{
    static const char *const names[LIFECYCLE_EVENT_COUNT] = {
        "start", "resume", "pause", "stop", "window-created", "window-destroyed", "context-lost", "destroy"};
    return (unsigned)ev < LIFECYCLE_EVENT_COUNT ? names[ev] : "unknown";
}
