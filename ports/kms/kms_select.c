/* SPDX-License-Identifier: MIT */
/* kms_select.c — which card, connector, mode, CRTC and format snell-kiosk
 * drives (kms_select.h); no libdrm here, the kiosk fills the structs. */
#include "kms_select.h"

#include <errno.h>
#include <stdlib.h>

int kms_pick_card(const kms_card_probe *cards, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (cards[i].opened && cards[i].has_resources && cards[i].usable_connectors > 0) return i;
    return -1;
}

int kms_connector_usable(const kms_connector_info *c)
{
    return (c->connection == KMS_CONNECTED || c->connection == KMS_UNKNOWN) && c->mode_count > 0;
}

int kms_display_gone(int err, const kms_connector_info *now)
{
    return err == -ENODEV || !now || !kms_connector_usable(now);
}

int kms_pick_connector(const kms_resources_info *r, uint32_t want_id)
{
    int i, pass;
    if (want_id) {
        for (i = 0; i < r->connector_count; i++)
            if (r->connectors[i].id == want_id) return kms_connector_usable(&r->connectors[i]) ? i : -1;
        return -1;
    }
    /* Connected ones first: an unknown connector is only a guess. */
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < r->connector_count; i++) {
            const kms_connector_info *c = &r->connectors[i];
            if (c->connection == (pass ? KMS_UNKNOWN : KMS_CONNECTED) && c->mode_count > 0) return i;
        }
    return -1;
}

/* A positive decimal integer at *s, *s moved past it; 0 if there is none. */
static int parse_positive(const char **s)
{
    char *end;
    long v;
    if (**s < '0' || **s > '9') return 0;
    errno = 0;
    v = strtol(*s, &end, 10);
    if (errno || v <= 0 || v > 100000) return 0;
    *s = end;
    return (int)v;
}

int kms_parse_mode(const char *s, kms_mode_request *out)
{
    kms_mode_request m = {0, 0, 0};
    if (!s || !(m.width = parse_positive(&s)) || *s++ != 'x' || !(m.height = parse_positive(&s))) return 0;
    if (*s == '@') {
        s++;
        if (!(m.refresh = parse_positive(&s))) return 0;
    }
    if (*s) return 0;
    *out = m;
    return 1;
}

int kms_pick_mode(const kms_connector_info *c, const kms_mode_request *req)
{
    int i, best = -1;
    if (req && req->width && req->height) {
        for (i = 0; i < c->mode_count; i++) {
            const kms_mode_info *m = &c->modes[i];
            if (m->width != req->width || m->height != req->height) continue;
            if (req->refresh) {
                if (m->refresh == req->refresh) return i;
            } else if (best < 0 || m->refresh > c->modes[best].refresh) {
                best = i;
            }
        }
        return best;
    }
    for (i = 0; i < c->mode_count; i++)
        if (c->modes[i].preferred) return i;
    for (i = 0; i < c->mode_count; i++) {
        const kms_mode_info *m = &c->modes[i];
        long area = (long)m->width * m->height, best_area;
        if (best < 0) {
            best = i;
            continue;
        }
        best_area = (long)c->modes[best].width * c->modes[best].height;
        if (area > best_area || (area == best_area && m->refresh > c->modes[best].refresh)) best = i;
    }
    return best;
}

static const kms_encoder_info *find_encoder(const kms_resources_info *r, uint32_t id)
{
    int i;
    for (i = 0; i < r->encoder_count; i++)
        if (r->encoders[i].id == id) return &r->encoders[i];
    return NULL;
}

uint32_t kms_pick_crtc(const kms_resources_info *r, const kms_connector_info *c, int *index)
{
    const kms_encoder_info *e = c->encoder_id ? find_encoder(r, c->encoder_id) : NULL;
    int i, k;
    *index = -1;
    if (e && e->crtc_id)
        for (i = 0; i < r->crtc_count; i++)
            if (r->crtcs[i] == e->crtc_id) return *index = i, e->crtc_id;
    for (k = 0; k < c->encoder_count; k++) {
        e = find_encoder(r, c->encoders[k]);
        if (!e) continue;
        for (i = 0; i < r->crtc_count && i < 32; i++)
            if (e->possible_crtcs & (1u << i)) return *index = i, r->crtcs[i];
    }
    return 0;
}

int kms_pick_config(const int32_t *visual_ids, int nc, const uint32_t *formats, int nf, int *format)
{
    int f, i;
    for (f = 0; f < nf; f++)
        for (i = 0; i < nc; i++)
            if ((uint32_t)visual_ids[i] == formats[f]) return *format = f, i;
    *format = -1;
    return -1;
}
