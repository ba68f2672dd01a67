/* link_file.c - a captured stream of a robot's bytes as the robot link (link.h): the
 * replay of houghloc-sim --capture, for the ARCOS golden (tests/golden). */
#include "link.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define WHY(...) snprintf(why, HL_LINK_WHY_LEN, __VA_ARGS__)

bool hl_link_open_file(hl_link_t *l, const hl_link_spec_t *spec, char *why)
{
    l->fd = open(spec->path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (l->fd < 0)
        return WHY("%.200s: %s", l->name, strerror(errno)), false;
    /* A regular file is always readable, so poll() never waits on it and the capture
     * replays at once; anything else (a pipe, a tty) would pace it by the wall clock. */
    struct stat st;
    if (fstat(l->fd, &st) != 0 || !S_ISREG(st.st_mode))
        return WHY("%.200s: not a regular file (a capture, from houghloc-sim --capture)",
                   l->name), false;
    return true;
}

ssize_t hl_link_read_file(hl_link_t *l, void *buf, size_t n, char *why)
{
    if (l->ended)
        return WHY("%.200s: the end of the capture", l->name), -1;
    ssize_t got = read(l->fd, buf, n);
    if (got > 0)
        return got;
    if (got < 0 && errno == EINTR)
        return 0;
    if (got < 0)
        return WHY("%.200s: read: %s", l->name, strerror(errno)), -1;
    l->ended = true;
    return WHY("%.200s: the end of the capture", l->name), -1;
}
