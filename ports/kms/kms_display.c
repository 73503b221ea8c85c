/* SPDX-License-Identifier: MIT */
/* kms_display.c — the DRM card, connector, mode and CRTC snell-kiosk drives,
 * framebuffers, modeset, legacy page flips, restore (kms_display.h). What is
 * chosen is decided by kms_select.c; this file only reads the card into its
 * structs and does what was chosen. */
#define _POSIX_C_SOURCE 200809L
#include "kms_display.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_CARDS 16

/* A card's resources as libdrm returns them and as kms_select.c reads them. */
typedef struct card_scan {
    drmModeRes *res;
    drmModeConnector **conn;
    kms_connector_info *ci;
    kms_encoder_info *ei;
    kms_mode_info **modes;
    kms_resources_info info;
} card_scan;

static void free_scan(card_scan *s)
{
    int i;
    if (s->res) {
        for (i = 0; i < s->res->count_connectors; i++) {
            if (s->conn) drmModeFreeConnector(s->conn[i]);
            if (s->modes) free(s->modes[i]);
        }
        drmModeFreeResources(s->res);
    }
    free(s->conn);
    free(s->ci);
    free(s->ei);
    free(s->modes);
    memset(s, 0, sizeof *s);
}

/* 1 if fd has KMS resources (read into s), else 0. */
static int scan_card(int fd, card_scan *s)
{
    int i, k, nc, ne;
    memset(s, 0, sizeof *s);
    if (!(s->res = drmModeGetResources(fd))) return 0;
    nc = s->res->count_connectors;
    ne = s->res->count_encoders;
    s->conn = (drmModeConnector **)calloc((size_t)nc + 1, sizeof *s->conn);
    s->ci = (kms_connector_info *)calloc((size_t)nc + 1, sizeof *s->ci);
    s->modes = (kms_mode_info **)calloc((size_t)nc + 1, sizeof *s->modes);
    s->ei = (kms_encoder_info *)calloc((size_t)ne + 1, sizeof *s->ei);
    if (!s->conn || !s->ci || !s->modes || !s->ei) return 1; /* counts stay 0: nothing usable */
    for (i = 0; i < nc; i++) {
        drmModeConnector *c = s->conn[i] = drmModeGetConnector(fd, s->res->connectors[i]);
        kms_connector_info *ci = &s->ci[s->info.connector_count];
        if (!c) continue;
        ci->id = c->connector_id;
        ci->connection = (int)c->connection;
        ci->encoder_id = c->encoder_id;
        ci->encoders = c->encoders;
        ci->encoder_count = c->count_encoders;
        s->modes[i] = (kms_mode_info *)calloc((size_t)c->count_modes + 1, sizeof **s->modes);
        if (s->modes[i])
            for (k = 0; k < c->count_modes; k++) {
                s->modes[i][k].width = c->modes[k].hdisplay;
                s->modes[i][k].height = c->modes[k].vdisplay;
                s->modes[i][k].refresh = (int)c->modes[k].vrefresh;
                s->modes[i][k].preferred = (c->modes[k].type & DRM_MODE_TYPE_PREFERRED) != 0;
            }
        ci->modes = s->modes[i];
        ci->mode_count = s->modes[i] ? c->count_modes : 0;
        s->info.connector_count++;
    }
    for (i = 0; i < ne; i++) {
        drmModeEncoder *e = drmModeGetEncoder(fd, s->res->encoders[i]);
        if (!e) continue;
        s->ei[s->info.encoder_count].id = e->encoder_id;
        s->ei[s->info.encoder_count].crtc_id = e->crtc_id;
        s->ei[s->info.encoder_count].possible_crtcs = e->possible_crtcs;
        s->info.encoder_count++;
        drmModeFreeEncoder(e);
    }
    s->info.connectors = s->ci;
    s->info.encoders = s->ei;
    s->info.crtcs = s->res->crtcs;
    s->info.crtc_count = s->res->count_crtcs;
    return 1;
}

/* The drmModeConnector behind kms connector info index i (connectors that
 * could not be read are left out of ci, so indices differ). */
static drmModeConnector *connector_of(const card_scan *s, uint32_t id)
{
    int i;
    for (i = 0; i < s->res->count_connectors; i++)
        if (s->conn[i] && s->conn[i]->connector_id == id) return s->conn[i];
    return NULL;
}

static int card_number(const char *name)
{
    int n;
    char tail;
    return sscanf(name, "card%d%c", &n, &tail) == 1 && n >= 0 ? n : -1;
}

static int by_number(const void *a, const void *b)
{
    return card_number((const char *)a) - card_number((const char *)b);
}

/* card* under dir, in number order, as full paths. */
static int list_cards(const char *dir, char paths[][256], int max)
{
    char names[MAX_CARDS][64];
    int i, n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    if (!d) return 0;
    while ((e = readdir(d)) && n < max)
        if (card_number(e->d_name) >= 0) snprintf(names[n++], sizeof names[0], "%.32s", e->d_name); /* "cardN" */
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], by_number);
    for (i = 0; i < n; i++) snprintf(paths[i], 256, "%.200s/%.32s", dir, names[i]);
    return n;
}

static const char *connection_str(int c)
{
    return c == KMS_CONNECTED ? "connected" : c == KMS_DISCONNECTED ? "disconnected" : "unknown";
}

/* The primary plane of the chosen CRTC: its formats and IN_FORMATS blob. */
static void find_primary_plane(kms_display *d)
{
    drmModePlaneRes *pr;
    uint32_t i, k;
    drmSetClientCap(d->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
    if (!(pr = drmModeGetPlaneResources(d->fd))) return;
    for (i = 0; i < pr->count_planes && !d->plane_id; i++) {
        drmModePlane *p = drmModeGetPlane(d->fd, pr->planes[i]);
        drmModeObjectProperties *props;
        int primary = 0;
        uint32_t blob = 0;
        if (!p) continue;
        props = (p->possible_crtcs & (1u << d->crtc_index))
                    ? drmModeObjectGetProperties(d->fd, p->plane_id, DRM_MODE_OBJECT_PLANE)
                    : NULL;
        for (k = 0; props && k < props->count_props; k++) {
            drmModePropertyRes *pp = drmModeGetProperty(d->fd, props->props[k]);
            if (!pp) continue;
            if (!strcmp(pp->name, "type")) primary = props->prop_values[k] == DRM_PLANE_TYPE_PRIMARY;
            if (!strcmp(pp->name, "IN_FORMATS")) blob = (uint32_t)props->prop_values[k];
            drmModeFreeProperty(pp);
        }
        if (primary) {
            d->plane_id = p->plane_id;
            d->in_formats_blob = blob;
            for (k = 0; k < p->count_formats && k < KMS_MAX_FORMATS; k++) d->formats[k] = p->formats[k];
            d->format_count = (int)k;
        }
        drmModeFreeObjectProperties(props);
        drmModeFreePlane(p);
    }
    drmModeFreePlaneResources(pr);
}

/* Why no card was chosen, card by card. */
static void explain_cards(char paths[][256], const kms_card_probe *probe, const int *open_errno, int n, char *msg,
                          size_t size)
{
    size_t len = 0;
    int i;
    for (i = 0; i < n && len < size; i++) {
        const char *why = !probe[i].opened          ? strerror(open_errno[i])
                          : !probe[i].has_resources ? "no KMS resources (a render-only GPU, or not a DRM card)"
                                                    : "no connected display";
        len += (size_t)snprintf(msg + len, size - len, "%s%s: %s", i ? "; " : "", paths[i], why);
    }
}

/* Id of the property called name of object obj (0 if it has none). */
static uint32_t prop_id(int fd, uint32_t obj, uint32_t type, const char *name)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint32_t i, id = 0;
    for (i = 0; props && i < props->count_props && !id; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && !strcmp(p->name, name)) id = p->prop_id;
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

/* Atomic commits asked for: the cap (left on) and the properties they set. */
static int atomic_setup(kms_display *d, char *msg, size_t n)
{
    static const char *const plane_names[10] = {"FB_ID", "CRTC_ID", "SRC_X",  "SRC_Y",  "SRC_W",
                                                "SRC_H", "CRTC_X",  "CRTC_Y", "CRTC_W", "CRTC_H"};
    uint32_t *plane_ids[10] = {&d->prop.fb_id, &d->prop.crtc_id, &d->prop.src_x,  &d->prop.src_y,  &d->prop.src_w,
                               &d->prop.src_h, &d->prop.crtc_x,  &d->prop.crtc_y, &d->prop.crtc_w, &d->prop.crtc_h};
    int i;
    if (!d->atomic) return snprintf(msg, n, "%s: --atomic, but the kernel has no atomic modesetting here", d->path), 0;
    if (!d->plane_id) return snprintf(msg, n, "%s: --atomic, but no primary plane for CRTC %u", d->path, d->crtc_id), 0;
    d->prop.conn_crtc_id = prop_id(d->fd, d->connector_id, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
    d->prop.crtc_mode_id = prop_id(d->fd, d->crtc_id, DRM_MODE_OBJECT_CRTC, "MODE_ID");
    d->prop.crtc_active = prop_id(d->fd, d->crtc_id, DRM_MODE_OBJECT_CRTC, "ACTIVE");
    if (!d->prop.conn_crtc_id || !d->prop.crtc_mode_id || !d->prop.crtc_active)
        return snprintf(msg, n, "%s: --atomic, but the connector or CRTC lacks CRTC_ID, MODE_ID or ACTIVE", d->path), 0;
    for (i = 0; i < 10; i++)
        if (!(*plane_ids[i] = prop_id(d->fd, d->plane_id, DRM_MODE_OBJECT_PLANE, plane_names[i])))
            return snprintf(msg, n, "%s: --atomic, but plane %u has no %s", d->path, d->plane_id, plane_names[i]), 0;
    d->use_atomic = 1;
    return 1;
}

static kms_open_result choose(kms_display *d, const kms_display_request *req, card_scan *s, char *msg, size_t n)
{
    int ci, mi, i;
    uint64_t cap = 0;
    const kms_connector_info *c;
    drmModeConnector *dc;
    if ((ci = kms_pick_connector(&s->info, req->connector_id)) < 0) {
        if (req->connector_id)
            snprintf(msg, n, "%s: connector %u is not there or not connected", d->path, req->connector_id);
        else
            snprintf(msg, n, "%s: no connected connector with modes", d->path);
        return KMS_OPEN_FAILED;
    }
    c = &s->info.connectors[ci];
    dc = connector_of(s, c->id);
    d->connector_id = c->id;
    snprintf(d->connector_name, sizeof d->connector_name, "%s-%u",
             drmModeGetConnectorTypeName(dc->connector_type) ? drmModeGetConnectorTypeName(dc->connector_type)
                                                             : "unknown",
             dc->connector_type_id);
    for (i = 0; i < c->mode_count && i < 64; i++) d->modes[i] = c->modes[i];
    d->mode_count = i;
    if ((mi = kms_pick_mode(c, &req->mode)) < 0) {
        char list[512];
        kms_display_mode_list(d, list, sizeof list);
        if (req->mode.refresh)
            snprintf(msg, n, "%s: %s has no mode %dx%d@%d; its modes: %s", d->path, d->connector_name, req->mode.width,
                     req->mode.height, req->mode.refresh, list);
        else
            snprintf(msg, n, "%s: %s has no mode %dx%d; its modes: %s", d->path, d->connector_name, req->mode.width,
                     req->mode.height, list);
        return KMS_OPEN_FAILED;
    }
    d->mode = dc->modes[mi];
    if (!(d->crtc_id = kms_pick_crtc(&s->info, c, &d->crtc_index))) {
        snprintf(msg, n, "%s: no CRTC can drive %s", d->path, d->connector_name);
        return KMS_OPEN_FAILED;
    }
    d->saved = drmModeGetCrtc(d->fd, d->crtc_id);
    d->monotonic_events = drmGetCap(d->fd, DRM_CAP_TIMESTAMP_MONOTONIC, &cap) == 0 && cap == 1;
    find_primary_plane(d);
    /* Atomic modesetting is probed and reported; used when asked for. Legacy
     * flips work on every KMS driver (on atomic ones through their helpers). */
    d->atomic = drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 1) == 0;
    if (d->atomic && !req->atomic) drmSetClientCap(d->fd, DRM_CLIENT_CAP_ATOMIC, 0);
    if (req->atomic && !atomic_setup(d, msg, n)) return KMS_OPEN_FAILED;
    snprintf(msg, n,
             "%s, %s (%s), mode %dx%d@%d%s, CRTC %u, primary plane %u (%d formats, IN_FORMATS %s), "
             "atomic %s (%s used)",
             d->path, d->connector_name, connection_str(c->connection), d->mode.hdisplay, d->mode.vdisplay,
             (int)d->mode.vrefresh, (d->mode.type & DRM_MODE_TYPE_PREFERRED) ? " (preferred)" : "", d->crtc_id,
             d->plane_id, d->format_count, d->in_formats_blob ? "yes" : "no", d->atomic ? "available" : "not available",
             d->use_atomic ? "atomic commits" : "legacy page flips");
    return KMS_OPEN_OK;
}

kms_open_result kms_display_open(kms_display *d, const kms_display_request *req, char *msg, size_t n)
{
    char paths[MAX_CARDS][256];
    kms_card_probe probe[MAX_CARDS];
    card_scan scans[MAX_CARDS];
    int fds[MAX_CARDS], open_errno[MAX_CARDS];
    int count, i, pick, opened = 0;
    const char *dir = req->dri_dir ? req->dri_dir : "/dev/dri";
    kms_open_result result;

    memset(d, 0, sizeof *d);
    d->fd = -1;
    if (req->device) {
        snprintf(paths[0], sizeof paths[0], "%s", req->device);
        count = 1;
    } else if (!(count = list_cards(dir, paths, MAX_CARDS))) {
        snprintf(msg, n, "no DRM device: no card* in %s (no KMS driver loaded?)", dir);
        return KMS_OPEN_NO_DISPLAY;
    }
    memset(probe, 0, sizeof probe);
    memset(scans, 0, sizeof scans);
    for (i = 0; i < count; i++) {
        open_errno[i] = 0;
        fds[i] = open(paths[i], O_RDWR | O_CLOEXEC);
        if (fds[i] < 0) {
            open_errno[i] = errno;
            continue;
        }
        opened++;
        probe[i].opened = 1;
        probe[i].has_resources = scan_card(fds[i], &scans[i]);
        for (int k = 0; k < scans[i].info.connector_count; k++)
            probe[i].usable_connectors += kms_connector_usable(&scans[i].info.connectors[k]);
    }
    pick = kms_pick_card(probe, count);
    if (pick < 0) {
        char why[1024];
        explain_cards(paths, probe, open_errno, count, why, sizeof why);
        /* A card that exists but cannot be opened is a setup problem (the
         * video group, a path typo), not the absence of a display. */
        result = opened == count ? KMS_OPEN_NO_DISPLAY : KMS_OPEN_FAILED;
        snprintf(msg, n, "%s: %s", result == KMS_OPEN_NO_DISPLAY ? "no DRM/KMS display" : "cannot use a DRM device",
                 why);
    } else {
        d->fd = fds[pick];
        fds[pick] = -1;
        snprintf(d->path, sizeof d->path, "%s", paths[pick]);
        result = choose(d, req, &scans[pick], msg, n);
    }
    for (i = 0; i < count; i++) {
        free_scan(&scans[i]);
        if (fds[i] >= 0) close(fds[i]);
    }
    return result;
}

int kms_display_modifiers(const kms_display *d, uint32_t format, uint64_t *out, int max)
{
    drmModePropertyBlobRes *blob;
    drmModeFormatModifierIterator it;
    int n = 0;
    if (!d->in_formats_blob || !(blob = drmModeGetPropertyBlob(d->fd, d->in_formats_blob))) return 0;
    memset(&it, 0, sizeof it);
    while (n < max && drmModeFormatModifierBlobIterNext(blob, &it))
        if (it.fmt == format) out[n++] = it.mod;
    drmModeFreePropertyBlob(blob);
    return n;
}

void kms_display_mode_list(const kms_display *d, char *out, size_t n)
{
    size_t len = 0;
    int i;
    out[0] = '\0';
    for (i = 0; i < d->mode_count && len < n; i++)
        len += (size_t)snprintf(out + len, n - len, "%s%dx%d@%d%s", i ? " " : "", d->modes[i].width, d->modes[i].height,
                                d->modes[i].refresh, d->modes[i].preferred ? "*" : "");
}

uint32_t kms_display_add_fb(const kms_display *d, int width, int height, uint32_t format, int planes,
                            const uint32_t handles[4], const uint32_t strides[4], const uint32_t offsets[4],
                            uint64_t modifier)
{
    uint32_t fb = 0;
    uint64_t mods[4] = {modifier, modifier, modifier, modifier};
    int i;
    uint32_t h[4] = {0}, s[4] = {0}, o[4] = {0};
    for (i = 0; i < planes && i < 4; i++) h[i] = handles[i], s[i] = strides[i], o[i] = offsets[i];
    if (modifier != DRM_FORMAT_MOD_INVALID &&
        drmModeAddFB2WithModifiers(d->fd, (uint32_t)width, (uint32_t)height, format, h, s, o, mods, &fb,
                                   DRM_MODE_FB_MODIFIERS) == 0)
        return fb;
    if (drmModeAddFB2(d->fd, (uint32_t)width, (uint32_t)height, format, h, s, o, &fb, 0) == 0) return fb;
    if (drmModeAddFB(d->fd, (uint32_t)width, (uint32_t)height, 24, 32, s[0], h[0], &fb) == 0) return fb;
    return 0;
}

/* An atomic commit of framebuffer fb on the primary plane: with the mode,
 * the connector and the whole plane for the modeset (blocking), the
 * framebuffer alone for a flip (nonblocking, with an event). */
static int atomic_commit(kms_display *d, uint32_t fb, int modeset)
{
    drmModeAtomicReq *req;
    uint32_t flags = modeset ? DRM_MODE_ATOMIC_ALLOW_MODESET : DRM_MODE_PAGE_FLIP_EVENT | DRM_MODE_ATOMIC_NONBLOCK;
    uint64_t w = d->mode.hdisplay, h = d->mode.vdisplay;
    int r;
    if (modeset && !d->mode_blob && drmModeCreatePropertyBlob(d->fd, &d->mode, sizeof d->mode, &d->mode_blob))
        return -errno;
    if (!(req = drmModeAtomicAlloc())) return -ENOMEM;
    if (modeset) {
        drmModeAtomicAddProperty(req, d->connector_id, d->prop.conn_crtc_id, d->crtc_id);
        drmModeAtomicAddProperty(req, d->crtc_id, d->prop.crtc_mode_id, d->mode_blob);
        drmModeAtomicAddProperty(req, d->crtc_id, d->prop.crtc_active, 1);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.crtc_id, d->crtc_id);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.src_x, 0);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.src_y, 0);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.src_w, w << 16); /* 16.16 fixed point */
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.src_h, h << 16);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.crtc_x, 0);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.crtc_y, 0);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.crtc_w, w);
        drmModeAtomicAddProperty(req, d->plane_id, d->prop.crtc_h, h);
    }
    drmModeAtomicAddProperty(req, d->plane_id, d->prop.fb_id, fb);
    r = drmModeAtomicCommit(d->fd, req, flags, d) ? -errno : 0;
    drmModeAtomicFree(req);
    return r;
}

int kms_display_modeset(kms_display *d, uint32_t fb)
{
    if (d->use_atomic) return atomic_commit(d, fb, 1);
    return drmModeSetCrtc(d->fd, d->crtc_id, fb, 0, 0, &d->connector_id, 1, &d->mode) ? -errno : 0;
}

int kms_display_page_flip(kms_display *d, uint32_t fb)
{
    if (d->use_atomic) return atomic_commit(d, fb, 0);
    return drmModePageFlip(d->fd, d->crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, d) ? -errno : 0;
}

static void flip_handler(int fd, unsigned int sequence, unsigned int sec, unsigned int usec, void *data)
{
    kms_display *d = (kms_display *)data;
    (void)fd;
    (void)sequence;
    if (d->on_flip) d->on_flip(d->on_flip_user, (double)sec + 1e-6 * (double)usec);
}

int kms_display_wait(kms_display *d, int timeout_ms, void (*on_flip)(void *user, double t_s), void *user)
{
    struct pollfd p = {d->fd, POLLIN, 0};
    drmEventContext ev;
    int r = poll(&p, 1, timeout_ms);
    if (r < 0) return errno == EINTR ? -2 : -1;
    if (r == 0) return 0;
    memset(&ev, 0, sizeof ev);
    ev.version = 2;
    ev.page_flip_handler = flip_handler;
    d->on_flip = on_flip;
    d->on_flip_user = user;
    r = drmHandleEvent(d->fd, &ev);
    d->on_flip = NULL;
    return r == 0 ? 1 : -1;
}

int kms_display_restore(kms_display *d, char *msg, size_t n)
{
    drmModeCrtc *now;
    int r, ok;
    if (!d->saved) {
        snprintf(msg, n, "CRTC %u: nothing saved to restore", d->crtc_id);
        return 0;
    }
    if (d->saved->mode_valid)
        r = drmModeSetCrtc(d->fd, d->crtc_id, d->saved->buffer_id, d->saved->x, d->saved->y, &d->connector_id, 1,
                           &d->saved->mode);
    else
        r = drmModeSetCrtc(d->fd, d->crtc_id, 0, 0, 0, NULL, 0, NULL); /* it was off: switch it off again */
    if (r) {
        snprintf(msg, n, "CRTC %u: restoring framebuffer %u failed: %s", d->crtc_id, d->saved->buffer_id,
                 strerror(errno));
        return 0;
    }
    now = drmModeGetCrtc(d->fd, d->crtc_id);
    ok = now && now->buffer_id == d->saved->buffer_id;
    snprintf(msg, n, "restored CRTC %u: framebuffer %u%s, mode %s", d->crtc_id, now ? now->buffer_id : 0,
             ok ? " (the one before the kiosk)" : " (NOT the one before the kiosk)",
             d->saved->mode_valid ? d->saved->mode.name : "off");
    drmModeFreeCrtc(now);
    return ok;
}

int kms_display_recheck(const kms_display *d, int *connection, int *mode_count)
{
    drmModeConnector *c = d->fd >= 0 ? drmModeGetConnector(d->fd, d->connector_id) : NULL;
    if (!c) return 0;
    *connection = (int)c->connection;
    *mode_count = c->count_modes;
    drmModeFreeConnector(c);
    return 1;
}

void kms_display_close(kms_display *d)
{
    if (d->mode_blob) drmModeDestroyPropertyBlob(d->fd, d->mode_blob);
    d->mode_blob = 0;
    drmModeFreeCrtc(d->saved);
    d->saved = NULL;
    if (d->fd >= 0) close(d->fd);
    d->fd = -1;
}
