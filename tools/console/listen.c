/* listen.c - the console's listening socket (listen.h). */
#include "listen.h"

#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "access.h"

/* Non-blocking and close-on-exec: accept4 and SOCK_CLOEXEC are not POSIX. */
static int set_flags(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0)
        return -1;
    int fdf = fcntl(fd, F_GETFD);
    return fdf < 0 || fcntl(fd, F_SETFD, fdf | FD_CLOEXEC) != 0 ? -1 : 0;
}

int listen_open(const struct sockaddr *addr, socklen_t len, const char *host, unsigned port,
                char *why)
{
    int fd = socket(addr->sa_family, SOCK_STREAM, 0);
    int one = 1;
    const char *step = "socket";
    if (fd >= 0) {
        step = "bind";
        setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        if (addr->sa_family == AF_INET6)
            setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &one, sizeof one);
        if (bind(fd, addr, len) == 0 && (step = "listen", listen(fd, SOMAXCONN) == 0) &&
            (step = "fcntl", set_flags(fd) == 0))
            return fd;
    }
    int err = errno;
    if (fd >= 0)
        close(fd);
    snprintf(why, ACCESS_WHY_LEN, "cannot serve on %s:%u: %s: %s", host, port, step,
             strerror(err));
    return -1;
}

int listen_accept(int fd, struct sockaddr_storage *peer, socklen_t *peer_len)
{
    for (;;) {
        int c = accept(fd, (struct sockaddr *)peer, peer_len);
        if (c < 0 && errno == EINTR)
            continue;
        if (c >= 0 && set_flags(c) != 0) {
            close(c);
            errno = EAGAIN; /* not expected: drop it and go on */
            return -1;
        }
        return c;
    }
}
