#include "test_util.h"

#include <stdlib.h>
#include <string.h>

int test_passed, test_failed;

int test_finish(void)
{
    printf("%d passed, %d failed\n", test_passed, test_failed);
    return test_failed ? 1 : 0;
}

const char *test_data(const char *name)
{
    static char buf[1024];
    const char *dir = getenv("SNELL_TEST_DATA");
    snprintf(buf, sizeof buf, "%s/%s", dir ? dir : "data", name);
    return buf;
}

const char *test_out(const char *name)
{
    static char buf[1024];
    const char *dir = getenv("SNELL_TEST_OUT");
    snprintf(buf, sizeof buf, "%s/%s", dir ? dir : ".", name);
    return buf;
}

snell_ctx *test_ctx(void)
{
    snell_ctx *ctx = NULL;
    snell_ctx_desc d = {0};
    if (snell_ctx_create(&d, &ctx) != SNELL_OK) {
        fprintf(stderr, "no headless GL context: %s\n", snell_last_error(NULL));
        return NULL;
    }
    return ctx;
}

void test_ref_params(const snell_frame_desc *fd, int w, int h, int max_interfaces, snell_ref_params *p)
{
    memset(p, 0, sizeof *p);
    p->mode = SNELL_REF_MATCHED;
    p->max_interfaces = max_interfaces;
    p->glass = fd->glass;
    p->env = fd->env;
    p->camera = fd->camera;
    p->width = w;
    p->height = h;
}

snell_status test_ref_render(const snell_ref *ref, const snell_ref_params *p, float *rgb, float *exit_dir,
                             uint8_t *hit)
{
    snell_ref_output o;
    memset(&o, 0, sizeof o);
    o.rgb = rgb;
    o.exit_dir = exit_dir;
    o.hit = hit;
    return snell_ref_render(ref, p, &o);
}
