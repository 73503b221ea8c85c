/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* uname */
/* cli_system.c — the build, GL driver, kernel and board of a benchmark run.
 * The board model is read where Linux publishes it: the device tree's model
 * (ARM boards: "Raspberry Pi 4 Model B Rev 1.4"), else DMI's vendor and
 * product (PCs, servers, VMs). */
#include "cli_system.h"
#include "snell_build_info.h"

#include <GLES3/gl3.h>
#include <string.h>
#include <sys/utsname.h>

/* The first line of a small text file, NUL bytes (device-tree strings) ended; 1 if non-empty. */
static int read_line(const char *path, char *out, size_t n)
{
    FILE *f = fopen(path, "rb");
    size_t len, i;
    if (!f) return 0;
    len = fread(out, 1, n - 1, f);
    fclose(f);
    out[len] = '\0';
    for (i = 0; i < len; i++)
        if (out[i] == '\n' || out[i] == '\0') break;
    out[i] = '\0';
    while (i > 0 && (out[i - 1] == ' ' || out[i - 1] == '\t' || out[i - 1] == '\r')) out[--i] = '\0';
    return i > 0;
}

static void gl_string(GLenum name, char *out, size_t n)
{
    const char *s = (const char *)glGetString(name);
    snprintf(out, n, "%s", s ? s : "unknown");
}

static void board(cli_system *s)
{
    static const char *const dt[] = {"/proc/device-tree/model", "/sys/firmware/devicetree/base/model"};
    char vendor[128], product[128];
    size_t k;
    for (k = 0; k < sizeof dt / sizeof *dt; k++)
        if (read_line(dt[k], s->board, sizeof s->board)) {
            snprintf(s->board_from, sizeof s->board_from, "%s", dt[k]);
            return;
        }
    if (read_line("/sys/class/dmi/id/product_name", product, sizeof product)) {
        if (read_line("/sys/class/dmi/id/sys_vendor", vendor, sizeof vendor))
            snprintf(s->board, sizeof s->board, "%s %s", vendor, product);
        else
            snprintf(s->board, sizeof s->board, "%s", product);
        snprintf(s->board_from, sizeof s->board_from, "/sys/class/dmi/id/product_name");
        return;
    }
    s->board[0] = s->board_from[0] = '\0';
}

void cli_system_read(cli_system *s)
{
    struct utsname u;
    memset(s, 0, sizeof *s);
    s->version = SNELL_TOOL_VERSION;
    s->commit = SNELL_TOOL_COMMIT;
    gl_string(GL_VENDOR, s->gl_vendor, sizeof s->gl_vendor);
    gl_string(GL_RENDERER, s->gl_renderer, sizeof s->gl_renderer);
    gl_string(GL_VERSION, s->gl_version, sizeof s->gl_version);
    if (uname(&u) == 0) snprintf(s->kernel, sizeof s->kernel, "%s %s %s %s", u.sysname, u.release, u.version, u.machine);
    else snprintf(s->kernel, sizeof s->kernel, "unknown");
    board(s);
}

int cli_print_version(const char *prog)
{
    printf("%s %s (commit %s)\n", prog, SNELL_TOOL_VERSION, SNELL_TOOL_COMMIT);
    return 0;
}
