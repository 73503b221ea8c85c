/* SPDX-License-Identifier: MIT */
/* test_kms.c — snell-kiosk's choices and page-flip state machine on made-up
 * DRM resources (ports/kms/kms_select.c, kms_flip.c; no DRM device needed):
 * a Pi 4 with a render-only card before the display card, connectors in
 * every state, preferred and requested modes, CRTCs in use or free, EGL
 * configs matched by native visual id, and the flip sequence with the calls
 * it must refuse. */
#include "kms_flip.h"
#include "kms_select.h"
#include "test_util.h"

#include <errno.h>
#include <string.h>

#define XR24 0x34325258u /* DRM_FORMAT_XRGB8888 'XR24' */
#define AR24 0x34325241u /* DRM_FORMAT_ARGB8888 'AR24' */
#define RG16 0x36314752u /* DRM_FORMAT_RGB565 'RG16' */

static void test_cards(void)
{
    /* Pi 4: card0 = v3d (render only), card1 = vc4 (KMS, HDMI connected). */
    kms_card_probe pi4[2] = {{1, 0, 0}, {1, 1, 1}};
    kms_card_probe none_open[2] = {{0, 0, 0}, {0, 0, 0}};
    kms_card_probe no_display[2] = {{1, 1, 0}, {1, 0, 0}};
    kms_card_probe second_opens[3] = {{0, 0, 0}, {1, 1, 2}, {1, 1, 1}};
    CHECK(kms_pick_card(pi4, 2) == 1, "the render-only card is skipped: %d", kms_pick_card(pi4, 2));
    CHECK(kms_pick_card(none_open, 2) == -1, "no card opens");
    CHECK(kms_pick_card(no_display, 2) == -1, "KMS but nothing connected");
    CHECK(kms_pick_card(second_opens, 3) == 1, "the first usable card: %d", kms_pick_card(second_opens, 3));
    CHECK(kms_pick_card(pi4, 0) == -1, "no cards at all");
}

static const kms_mode_info g_modes_hdmi[] = {
    {1920, 1080, 60, 0}, {3840, 2160, 30, 0}, {1920, 1080, 50, 0}, {1280, 720, 60, 1}, {1920, 1080, 75, 0},
};
static const kms_mode_info g_modes_dsi[] = {{800, 480, 60, 0}};
static const uint32_t g_enc_hdmi[] = {40}, g_enc_dsi[] = {41, 42};

static void test_connectors(void)
{
    kms_connector_info c[4];
    kms_resources_info r;
    memset(c, 0, sizeof c);
    memset(&r, 0, sizeof r);
    c[0] = (kms_connector_info){30, KMS_DISCONNECTED, 0, g_enc_hdmi, 1, g_modes_hdmi, 5};
    c[1] = (kms_connector_info){31, KMS_UNKNOWN, 0, g_enc_dsi, 2, g_modes_dsi, 1};
    c[2] = (kms_connector_info){32, KMS_CONNECTED, 0, g_enc_hdmi, 1, NULL, 0}; /* connected, no modes */
    c[3] = (kms_connector_info){33, KMS_CONNECTED, 0, g_enc_hdmi, 1, g_modes_hdmi, 5};
    r.connectors = c;
    r.connector_count = 4;
    CHECK(kms_pick_connector(&r, 0) == 3, "connected with modes first: %d", kms_pick_connector(&r, 0));
    r.connector_count = 3;
    CHECK(kms_pick_connector(&r, 0) == 1, "then unknown with modes: %d", kms_pick_connector(&r, 0));
    r.connector_count = 1;
    CHECK(kms_pick_connector(&r, 0) == -1, "a disconnected one is never used");
    r.connector_count = 4;
    CHECK(kms_pick_connector(&r, 31) == 1, "asked for by id");
    CHECK(kms_pick_connector(&r, 30) == -1, "asked for, but disconnected");
    CHECK(kms_pick_connector(&r, 32) == -1, "asked for, but no modes");
    CHECK(kms_pick_connector(&r, 99) == -1, "asked for, not there");
    CHECK(kms_connector_usable(&c[1]) && !kms_connector_usable(&c[2]) && !kms_connector_usable(&c[0]),
          "usable: connected or unknown, with modes");
    /* display loss after a failed frame: the card gone, the connector unplugged,
     * unreadable or without modes; a timeout or EBUSY on a display still there is not */
    CHECK(kms_display_gone(-ENODEV, &c[3]), "gone: the card (ENODEV)");
    CHECK(kms_display_gone(-EINVAL, &c[0]), "gone: unplugged");
    CHECK(kms_display_gone(0, NULL), "gone: connector unreadable");
    CHECK(kms_display_gone(-EINVAL, &c[2]), "gone: no modes left");
    CHECK(!kms_display_gone(0, &c[3]) && !kms_display_gone(-EBUSY, &c[3]) && !kms_display_gone(-EACCES, &c[1]),
          "not gone: the display is still there");
}

static void test_modes(void)
{
    kms_connector_info c = {33, KMS_CONNECTED, 0, g_enc_hdmi, 1, g_modes_hdmi, 5};
    kms_mode_info no_pref[3] = {{1280, 720, 60, 0}, {1920, 1080, 50, 0}, {1920, 1080, 60, 0}};
    kms_mode_request q;
    CHECK(kms_pick_mode(&c, NULL) == 3, "preferred mode (not the largest): %d", kms_pick_mode(&c, NULL));
    memset(&q, 0, sizeof q);
    CHECK(kms_pick_mode(&c, &q) == 3, "an empty request is the preferred mode");
    CHECK(kms_parse_mode("1920x1080", &q) && q.width == 1920 && q.height == 1080 && q.refresh == 0, "parse WxH");
    CHECK(kms_pick_mode(&c, &q) == 4, "WxH: the highest refresh of that size: %d", kms_pick_mode(&c, &q));
    CHECK(kms_parse_mode("1920x1080@50", &q) && q.refresh == 50, "parse WxH@R");
    CHECK(kms_pick_mode(&c, &q) == 2, "WxH@R: that refresh: %d", kms_pick_mode(&c, &q));
    CHECK(kms_parse_mode("1920x1080@24", &q) && kms_pick_mode(&c, &q) == -1, "no such refresh");
    CHECK(kms_parse_mode("1024x768", &q) && kms_pick_mode(&c, &q) == -1, "no such size");
    c.modes = no_pref;
    c.mode_count = 3;
    CHECK(kms_pick_mode(&c, NULL) == 2, "no preferred mode: the largest, highest refresh: %d", kms_pick_mode(&c, NULL));
    c.mode_count = 0;
    CHECK(kms_pick_mode(&c, NULL) == -1, "no modes");
    {
        static const char *const bad[] = {
            "",       "1920",       "1920x",      "x1080",       "1920x1080@", "1920x1080@60Hz", "0x1080",
            "1920x0", "-1920x1080", "1920 x1080", "1920x1080@0", "99999999x1", "1920X1080"};
        size_t i;
        for (i = 0; i < sizeof bad / sizeof *bad; i++) CHECK(!kms_parse_mode(bad[i], &q), "'%s' is not a mode", bad[i]);
        CHECK(!kms_parse_mode(NULL, &q), "NULL is not a mode");
    }
}

static void test_crtcs(void)
{
    static const uint32_t crtcs[3] = {50, 51, 52};
    kms_encoder_info enc[3] = {{40, 0, 0x6}, {41, 0, 0x4}, {42, 0, 0x1}};
    kms_connector_info c = {33, KMS_CONNECTED, 0, g_enc_hdmi, 1, g_modes_hdmi, 5};
    kms_resources_info r = {&c, 1, enc, 3, crtcs, 3};
    int index;
    CHECK(kms_pick_crtc(&r, &c, &index) == 51 && index == 1, "the first CRTC the encoder can use (bit 1): %d", index);
    c.encoder_id = 40;
    enc[0].crtc_id = 52;
    CHECK(kms_pick_crtc(&r, &c, &index) == 52 && index == 2, "the CRTC the current encoder feeds (the console's)");
    enc[0].crtc_id = 77; /* not among the resources' CRTCs: fall back to possible_crtcs */
    CHECK(kms_pick_crtc(&r, &c, &index) == 51 && index == 1, "a stale current CRTC is not used");
    c.encoders = g_enc_dsi; /* 41 (bit 2) then 42 (bit 0): the first encoder decides */
    c.encoder_count = 2;
    c.encoder_id = 0;
    CHECK(kms_pick_crtc(&r, &c, &index) == 52 && index == 2, "encoders in the connector's order");
    enc[1].possible_crtcs = 0;
    CHECK(kms_pick_crtc(&r, &c, &index) == 50 && index == 0, "an encoder with no CRTC is passed over");
    enc[2].possible_crtcs = 0;
    CHECK(kms_pick_crtc(&r, &c, &index) == 0 && index == -1, "no CRTC at all");
    enc[2].possible_crtcs = 0x8; /* bit 3: beyond the 3 CRTCs */
    CHECK(kms_pick_crtc(&r, &c, &index) == 0, "possible_crtcs beyond the CRTC list");
}

static void test_configs(void)
{
    static const uint32_t formats[2] = {XR24, AR24};
    int32_t visuals[4] = {(int32_t)RG16, (int32_t)AR24, (int32_t)XR24, 0};
    int f;
    CHECK(kms_pick_config(visuals, 4, formats, 2, &f) == 2 && f == 0, "XRGB8888 preferred over ARGB8888");
    CHECK(kms_pick_config(visuals, 2, formats, 2, &f) == 1 && f == 1, "ARGB8888 when no XRGB8888 config");
    CHECK(kms_pick_config(visuals, 1, formats, 2, &f) == -1 && f == -1, "RGB565 only: no match");
    CHECK(kms_pick_config(visuals, 4, formats + 1, 1, &f) == 1 && f == 0, "a plane that takes ARGB8888 only");
    CHECK(kms_pick_config(visuals, 4, formats, 0, &f) == -1, "a plane that takes neither");
}

static void test_flips(void)
{
    kms_flip f;
    int a, b, c, ok;
    void *old;
    kms_flip_init(&f);
    CHECK(kms_flip_next(&f) == KMS_STEP_MODESET, "the first frame is a modeset");
    CHECK(!kms_flip_queued(&f, &a), "no page flip before the modeset");
    old = kms_flip_complete(&f, &ok);
    CHECK(!ok && old == NULL, "a flip event with nothing queued is refused");
    CHECK(!kms_flip_modeset_done(&f, NULL), "a modeset needs a buffer");
    CHECK(kms_flip_modeset_done(&f, &a) && f.shown == &a && f.frames == 1 && f.flips == 0, "modeset shows a");
    CHECK(!kms_flip_modeset_done(&f, &b), "only one modeset");
    CHECK(kms_flip_next(&f) == KMS_STEP_PAGE_FLIP, "then page flips");
    CHECK(!kms_flip_queued(&f, &a), "no flip to the buffer on screen");
    CHECK(kms_flip_queued(&f, &b) && kms_flip_pending(&f), "flip to b queued");
    CHECK(kms_flip_next(&f) == KMS_STEP_WAIT, "wait while a flip is queued");
    CHECK(!kms_flip_queued(&f, &c), "a second queued flip is refused");
    CHECK(f.frames == 1, "a queued flip is not a frame shown yet");
    old = kms_flip_complete(&f, &ok);
    CHECK(ok && old == &a && f.shown == &b && !kms_flip_pending(&f), "the event shows b and frees a");
    CHECK(f.frames == 2 && f.flips == 1, "frames %ld flips %ld", f.frames, f.flips);
    CHECK(kms_flip_queued(&f, &a), "a is free again: flip to it");
    old = kms_flip_complete(&f, &ok);
    CHECK(ok && old == &b, "b freed");
    old = kms_flip_complete(&f, &ok);
    CHECK(!ok && old == NULL && f.shown == &a, "a stray second event changes nothing");
    CHECK(kms_flip_queued(&f, &c) && (old = kms_flip_complete(&f, &ok)) == &a && ok, "three buffers in turn");
    CHECK(f.frames == 4 && f.flips == 3, "N frames = 1 modeset + N-1 flips: %ld, %ld", f.frames, f.flips);
    CHECK(f.refused == 7, "every refused call counted: %ld", f.refused);
}

int main(void)
{
    test_cards();
    test_connectors();
    test_modes();
    test_crtcs();
    test_configs();
    test_flips();
    return test_finish();
}
