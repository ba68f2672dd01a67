/*
 * http.h - the console's web server (private to tools/console): libmicrohttpd in
 * external-select mode, so that one thread polls LCM and HTTP together, with
 * suspend/resume for the event streams (a stream with nothing to send is suspended, and
 * resumed by the hub's wake when a message arrives: no busy loop).
 *
 * The console accepts connections itself and hands them to libmicrohttpd, so that the
 * gate (gate.h) decides who holds them: at most GATE_MAX_LIVE, GATE_PER_ADDR from one
 * address, a request header within GATE_HEADER_MS, and a newcomer displaces the oldest
 * connection that has not proven the token. A connection with no activity for
 * HTTP_IDLE_TIMEOUT_S is closed too (an event stream that is read gets a keepalive every
 * 15 s and never idles that long; one whose page stopped reading does).
 *
 * Routes: GET / the page (HEAD too), GET /events the Server-Sent Events stream,
 * POST /destination {x_m, y_m, heading_deg?}, POST /stop (no body needed; any body is
 * ignored). Every request passes access_decide first (403 bad Host or Origin, 401 no
 * token or a wrong one, each with a one-line reason and the connection closed; 303 with
 * the session cookie for the page's ?token=); then 404 for another path, 405 for another
 * method (OPTIONS included: no CORS preflight is ever granted); for /destination 400 for
 * a body that is not Content-Type application/json or does not parse (destreq.h) or is
 * longer than DESTREQ_MAX_BYTES. A refused request changes nothing. A stop is carried
 * out on the request's first call, before any body is read, and nothing else limits it:
 * no rate limit applies.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_HTTP_H
#define HOUGHLOC_TOOLS_CONSOLE_HTTP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/select.h>
#include <sys/socket.h>

#include "access.h"
#include "destreq.h"
#include "gate.h"
#include "hub.h"
#include "jbuf.h"

#define HTTP_IDLE_TIMEOUT_S 30

/**
 * Carries out a parsed destination request. Writes the JSON answer into @p answer.
 * @return 202 when published, or another HTTP status (the answer then has "error").
 */
typedef unsigned (*http_destination_fn)(void *user, const destreq_t *r, jbuf_t *answer);

/**
 * Carries out POST /stop. Writes the JSON answer into @p answer.
 * @return 202 when published, or another HTTP status (the answer then has "error").
 */
typedef unsigned (*http_stop_robot_fn)(void *user, jbuf_t *answer);

typedef struct http {
    struct MHD_Daemon *daemon;
    int listen_fd;
    gate_t gate;
    int adding;                 /* the gate's slot of the connection being handed over */
    hub_t *hub;
    const access_policy_t *policy;
    http_destination_fn on_destination;
    http_stop_robot_fn on_stop_robot;
    void *user;
    bool stopping;
    unsigned long requests, refused;    /* refused: any 4xx */
    int64_t log_since;                  /* the server's log: this minute's start, */
    unsigned long log_shown, log_held;  /* the lines shown in it and those held back */
} http_t;

/**
 * Starts serving on @p addr (@p addrlen bytes). @p hub's wake must be http_wake with
 * @p h as its user. @p dest and @p stop are called with @p user.
 * @return false with one line in @p why (ACCESS_WHY_LEN bytes) when it cannot.
 */
bool http_start(http_t *h, const struct sockaddr *addr, socklen_t addrlen, hub_t *hub,
                const access_policy_t *policy, http_destination_fn dest,
                http_stop_robot_fn stop, void *user, char *why);

/** The hub's wake callback: resumes the suspended stream @p s, and ends it when it was
 *  cut off. @p user is the http_t. */
void http_wake(void *user, hub_stream_t *s, bool suspended);

/** Adds the server's sockets to the sets; raises *max_fd. @return false on error. */
bool http_fdset(http_t *h, fd_set *rs, fd_set *ws, fd_set *es, int *max_fd);
/** Milliseconds until the server needs to run again, or -1 for no deadline. */
long http_timeout_ms(http_t *h);
/** Accepts new connections, closes those past their deadline, and runs the server on
 *  what select() found. */
void http_run(http_t *h, fd_set *rs, fd_set *ws, fd_set *es);
/** Ends every stream and stops the server. Accepts a stopped one. */
void http_stop(http_t *h);

#endif
