/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* fdopen, O_CLOEXEC */
/* file.c — opening an input file for a loader: regular files only, and never
 * blocking in open() on a FIFO or a device. */
#include "core/core.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int open_regular(const char *path, int extra_flags, int *opened, const char **why)
{
    struct stat sb;
    int fd, flags;
    *opened = 0;
    *why = "";
    /* open() of a FIFO without a writer blocks forever; O_NONBLOCK returns at
     * once, and fstat then refuses it like any other non-regular file */
    fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | extra_flags);
    if (fd < 0) {
        *why = strerror(errno);
        return -1;
    }
    *opened = 1;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        *why = S_ISDIR(sb.st_mode) ? "a directory" : "not a regular file";
        close(fd);
        return -1;
    }
    flags = fcntl(fd, F_GETFL);
    if (flags != -1) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

int snell__open_regular(const char *path, int *opened, const char **why)
{
    return open_regular(path, 0, opened, why);
}

int snell__open_regular_nofollow(const char *path, int *opened, const char **why)
{
    return open_regular(path, O_NOFOLLOW, opened, why);
}

FILE *snell__fopen_regular(const char *path, int *opened, const char **why)
{
    int fd = snell__open_regular(path, opened, why);
    FILE *f;
    if (fd < 0) return NULL;
    f = fdopen(fd, "rb");
    if (!f) {
        *why = strerror(errno);
        close(fd);
    }
    return f;
}
