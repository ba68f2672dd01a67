/*
 * args.h - houghloc-console's command line (private to tools/console). The options it
 * shares with houghloc-goto (--lcm-url, --prefix, --key) are parsed by tools/goto's
 * request.c, so that they mean exactly the same in both.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_ARGS_H
#define HOUGHLOC_TOOLS_CONSOLE_ARGS_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/socket.h>

#include "request.h"

#define PROG "houghloc-console"
#define CONSOLE_DEFAULT_PORT 8047

typedef struct console_options {
    req_options_t req;              /* --lcm-url, --prefix, --key (--timeout refused) */
    const char *listen;             /* as given; NULL: 127.0.0.1:8047 */
    struct sockaddr_storage addr;   /* the address to bind, parsed */
    socklen_t addrlen;
    bool loopback;                  /* 127.0.0.0/8 or ::1 */
    uint16_t port;
    char host[64];                  /* the address as a Host header names it */
    const char *token_file;         /* NULL: a token generated at start */
    const char *token_out;          /* where to write the generated token (0600), instead
                                       of printing it; NULL: printed on stderr */
    bool ground_truth;
    hl_pose_t start;                /* the daemon's start pose (--start): where the
                                       truth's first pose is drawn */
    const char *pending;            /* internal: an option waiting for its value */
} console_options_t;

/**
 * Parses "ADDR:PORT" ("127.0.0.1:8047", "0.0.0.0:80", "[::1]:8047", "localhost:8047")
 * into @p o's addr, addrlen, loopback, port and host. @return false when it is not one.
 */
bool console_parse_listen(const char *s, console_options_t *o);

/**
 * Parses the command line into @p o (which holds the defaults on entry).
 * @return WAITING when the program should go on; otherwise the exit code, after --help
 *         or --version printed on stdout, or a usage error printed on stderr as one line.
 */
int console_parse_args(int argc, char **argv, console_options_t *o);

#endif
