/*
 * listen.h - the console's listening socket (private to tools/console): bound and
 * listened on here, accepted from by http.c, which asks the gate (gate.h) about each
 * connection before libmicrohttpd gets it.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_LISTEN_H
#define HOUGHLOC_TOOLS_CONSOLE_LISTEN_H

#include <sys/socket.h>

/**
 * A non-blocking, close-on-exec TCP socket listening on @p addr (@p len bytes; IPv6 only
 * for an IPv6 address), with SO_REUSEADDR so that a restart does not wait for the last
 * run's closed connections.
 * @param[out] why  on failure one line: "cannot serve on HOST:PORT: REASON"
 *                  (ACCESS_WHY_LEN bytes), @p host and @p port as the operator gave them.
 * @return the socket, or -1.
 */
int listen_open(const struct sockaddr *addr, socklen_t len, const char *host, unsigned port,
                char *why);

/**
 * Accepts one connection from @p fd: non-blocking and close-on-exec, its peer's address
 * in @p peer (@p peer_len in: its size; out: the address's).
 * @return the connection's socket, or -1 (errno: EAGAIN when none is waiting).
 */
int listen_accept(int fd, struct sockaddr_storage *peer, socklen_t *peer_len);

#endif
