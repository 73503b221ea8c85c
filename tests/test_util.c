#include "test_util.h"

#include <stdlib.h>

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
