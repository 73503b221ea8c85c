/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* O_CLOEXEC */
/* cli_input.c — reading a user's input file and echoing a user's text
 * (cli_input.h); the library's loaders keep the same rules (core/file.c). */
#include "cli_input.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_open_input(const char *path, char *why, size_t why_size)
{
    struct stat sb;
    int flags;
    /* open() of a FIFO without a writer blocks forever; O_NONBLOCK returns at
     * once, and fstat then refuses it like any other non-regular file */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, why_size, "%s", strerror(errno));
        return -1;
    }
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        snprintf(why, why_size, "%s", S_ISDIR(sb.st_mode) ? "a directory" : "not a regular file");
        close(fd);
        return -1;
    }
    if ((flags = fcntl(fd, F_GETFL)) != -1) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

char *cli_read_input(const char *path, size_t max, size_t *len, char *why, size_t why_size)
{
    struct stat sb;
    char *text = NULL;
    size_t got = 0;
    ssize_t n;
    int fd = cli_open_input(path, why, why_size);
    *len = 0;
    if (fd < 0) return NULL;
    if (fstat(fd, &sb) != 0) {
        snprintf(why, why_size, "%s", strerror(errno));
    } else if ((unsigned long long)sb.st_size > max) {
        snprintf(why, why_size, "larger than %zu bytes", max);
    } else if (!(text = (char *)malloc((size_t)sb.st_size + 1))) {
        snprintf(why, why_size, "out of memory for %lld bytes", (long long)sb.st_size);
    } else {
        /* up to the size it had: a file that grows meanwhile is cut there */
        while (got < (size_t)sb.st_size && (n = read(fd, text + got, (size_t)sb.st_size - got)) != 0) {
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                snprintf(why, why_size, "%s", strerror(errno));
                free(text);
                text = NULL;
                break;
            }
            got += (size_t)n;
        }
    }
    close(fd);
    if (text) {
        text[got] = '\0';
        *len = got;
    }
    return text;
}

/* The length of the control character at p (0: none). */
static int control_at(const unsigned char *p)
{
    if ((*p < 0x20 && *p != '\t') || *p == 0x7f) return 1;
    return *p == 0xc2 && p[1] >= 0x80 && p[1] <= 0x9f ? 2 : 0;
}

void cli_scrub(char *s)
{
    unsigned char *p = (unsigned char *)s;
    int k;
    for (; *p; p++)
        for (k = control_at(p); k > 0; k--) p[k - 1] = '?';
}

int cli_has_control(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    for (; *p; p++)
        if (control_at(p) && !(*p == '\r' && !p[1])) return 1;
    return 0;
}

int cli_args_clean(const char *prog, int argc, char **argv)
{
    char safe[256];
    int i;
    for (i = 1; i < argc; i++)
        if (cli_has_control(argv[i])) {
            fprintf(stderr, "%s: argument %d ('%s') holds a control character\n", prog, i,
                    cli_safe(argv[i], safe, sizeof safe));
            return 0;
        }
    return 1;
}

const char *cli_safe(const char *s, char *buf, size_t n)
{
    size_t len = strlen(s);
    if (len < n) {
        memcpy(buf, s, len + 1);
    } else {
        memcpy(buf, s, n - 4);
        memcpy(buf + n - 4, "...", 4);
    }
    cli_scrub(buf);
    return buf;
}
