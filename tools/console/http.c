/* http.c - the console's web server on libmicrohttpd (http.h). */
#include "http.h"

#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <microhttpd.h>

#include "listen.h"
#include "page.h"

/* Small blocks: each stream's response holds one, and a page that stops reading keeps
 * its own; the hub's queue is where the rest waits. */
#define STREAM_BLOCK (16 * 1024)
/* Connections accepted per round: the ones accepted before are read in between, so a
 * newcomer's request is read before many more can displace it. */
#define ACCEPT_BATCH 16
/* Room for a request's header (the cookie, the token) and a response's. */
#define CONNECTION_MEMORY (64 * 1024)
#define HTTP_LOG_BURST 10

/* One request's state between libmicrohttpd's calls of the handler. */
typedef struct request {
    bool receiving;             /* POST /destination admitted: reading its body */
    bool too_large;
    size_t len;
    char body[DESTREQ_MAX_BYTES];
} request_t;

static const char page_csp[] =
    "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
    "connect-src 'self'; img-src data:; frame-ancestors 'none'; form-action 'none'";

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* The gate's slot of connection @p c (kept as its socket context, plus one), or -1. */
static int slot_of(struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *ci =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    return ci ? (int)(intptr_t)ci->socket_context - 1 : -1;
}

/* Makes the server close the connection on slot @p slot at its next look at it. The
 * socket stays open (the server closes it), so no other connection can take its number. */
static void shut(http_t *h, int slot)
{
    if (slot >= 0 && slot < GATE_SLOTS && h->gate.conn[slot].fd >= 0)
        shutdown(h->gate.conn[slot].fd, SHUT_RDWR);
}

static void add_common_headers(struct MHD_Response *r)
{
    MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    MHD_add_response_header(r, "X-Frame-Options", "DENY");
}

static enum MHD_Result respond(struct MHD_Connection *c, unsigned status, const char *type,
                               const char *body, size_t len, enum MHD_ResponseMemoryMode mode)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(len, (void *)body, mode);
    if (!r)
        return MHD_NO;
    add_common_headers(r);
    /* a refused client gets no second try on the same connection: it holds no place */
    if (status == MHD_HTTP_UNAUTHORIZED || status == MHD_HTTP_FORBIDDEN)
        MHD_add_response_header(r, MHD_HTTP_HEADER_CONNECTION, "close");
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, type);
    if (strncmp(type, "text/html", 9) == 0)
        MHD_add_response_header(r, "Content-Security-Policy", page_csp);
    if (status == MHD_HTTP_METHOD_NOT_ALLOWED)
        MHD_add_response_header(r, MHD_HTTP_HEADER_ALLOW, "GET, HEAD, POST");
    enum MHD_Result rc = MHD_queue_response(c, status, r);
    MHD_destroy_response(r);
    return rc;
}

/* {"error": "..."} with the status. */
static enum MHD_Result refuse(http_t *h, struct MHD_Connection *c, unsigned status,
                              const char *why)
{
    h->refused++;
    jbuf_t b;
    jbuf_init(&b, 4096);
    jbuf_puts(&b, "{\"error\":");
    jbuf_str(&b, why);
    jbuf_puts(&b, "}\n");
    if (b.failed) {
        jbuf_free(&b);
        return MHD_NO;
    }
    enum MHD_Result rc = respond(c, status, "application/json", b.data, b.len,
                                 MHD_RESPMEM_MUST_COPY);
    jbuf_free(&b);
    return rc;
}

static ssize_t stream_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    hub_stream_t *s = cls;
    size_t n = hub_stream_read(s, buf, max);
    if (s->dead)
        return MHD_CONTENT_READER_END_WITH_ERROR;
    if (n == 0) {
        /* nothing to send: wait for the hub's wake (http_wake) without polling */
        MHD_suspend_connection(s->conn);
        return 0;
    }
    return (ssize_t)n;
}

static void stream_free(void *cls)
{
    hub_stream_close(cls);
}

void http_wake(void *user, hub_stream_t *s, bool suspended)
{
    http_t *h = user;
    if (suspended)
        MHD_resume_connection(s->conn);
    if (s->dead && !h->stopping)
        shut(h, slot_of(s->conn)); /* cut off: its page reconnects */
}

static enum MHD_Result open_stream(http_t *h, struct MHD_Connection *c)
{
    hub_stream_t *s = hub_stream_open(h->hub, c);
    if (!s)
        return MHD_NO;
    struct MHD_Response *r =
        MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, STREAM_BLOCK, stream_read, s,
                                          stream_free);
    if (!r) {
        hub_stream_close(s);
        return MHD_NO;
    }
    add_common_headers(r);
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, "text/event-stream");
    enum MHD_Result rc = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return rc;
}

/* A callback's answer with its status (a 4xx or 5xx counts as refused). */
static enum MHD_Result answer(http_t *h, struct MHD_Connection *c, unsigned status, jbuf_t *a)
{
    if (a->failed) {
        jbuf_free(a);
        return MHD_NO;
    }
    if (status >= 400)
        h->refused++;
    jbuf_putc(a, '\n');
    enum MHD_Result rc = respond(c, status, "application/json", a->data, a->len,
                                 MHD_RESPMEM_MUST_COPY);
    jbuf_free(a);
    return rc;
}

static enum MHD_Result finish_destination(http_t *h, struct MHD_Connection *c, request_t *q)
{
    if (q->too_large)
        return refuse(h, c, MHD_HTTP_BAD_REQUEST, "the body is longer than 1024 bytes");
    destreq_t d;
    char why[DESTREQ_WHY_LEN];
    if (destreq_parse(q->body, q->len, &d, why) != HL_OK)
        return refuse(h, c, MHD_HTTP_BAD_REQUEST, why);
    jbuf_t a;
    jbuf_init(&a, 4096);
    unsigned status = h->on_destination(h->user, &d, &a);
    return answer(h, c, status, &a);
}

/* POST /stop: published at once, without waiting for a body (any body is dropped). */
static enum MHD_Result stop_robot(http_t *h, struct MHD_Connection *c)
{
    jbuf_t a;
    jbuf_init(&a, 4096);
    unsigned status = h->on_stop_robot(h->user, &a);
    return answer(h, c, status, &a);
}

/* GET /?token=TOKEN: the session cookie, and the page again without the token. */
static enum MHD_Result exchange(http_t *h, struct MHD_Connection *c)
{
    static const char body[] = "signed in: the page is at /\n";
    struct MHD_Response *r = MHD_create_response_from_buffer(sizeof body - 1, (void *)body,
                                                             MHD_RESPMEM_PERSISTENT);
    if (!r)
        return MHD_NO;
    char cookie[ACCESS_SET_COOKIE_LEN];
    access_set_cookie(h->policy, cookie);
    add_common_headers(r);
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, "text/plain; charset=utf-8");
    MHD_add_response_header(r, MHD_HTTP_HEADER_SET_COOKIE, cookie);
    MHD_add_response_header(r, MHD_HTTP_HEADER_LOCATION, "/");
    enum MHD_Result rc = MHD_queue_response(c, MHD_HTTP_SEE_OTHER, r);
    MHD_destroy_response(r);
    return rc;
}

/* The first call for a request: access, route and method; the page, the stream and a
 * stop are answered at once, a destination goes on to read its body. */
static enum MHD_Result first_call(http_t *h, struct MHD_Connection *c, const char *url,
                                  const char *method, request_t *q)
{
    const bool get = strcmp(method, MHD_HTTP_METHOD_GET) == 0 ||
                     strcmp(method, MHD_HTTP_METHOD_HEAD) == 0;
    const bool post = strcmp(method, MHD_HTTP_METHOD_POST) == 0;
    const bool page = strcmp(url, "/") == 0, events = strcmp(url, "/events") == 0;
    const bool dest = strcmp(url, "/destination") == 0, stop = strcmp(url, "/stop") == 0;
    const access_request_t ar = {
        .changes_state = !get,
        .page = get && page,
        .host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_HOST),
        .origin = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Origin"),
        .authorization = MHD_lookup_connection_value(c, MHD_HEADER_KIND,
                                                     MHD_HTTP_HEADER_AUTHORIZATION),
        .header_token = MHD_lookup_connection_value(c, MHD_HEADER_KIND, ACCESS_HEADER),
        .cookie = MHD_lookup_connection_value(c, MHD_COOKIE_KIND, h->policy->cookie_name),
        .query_token = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "token"),
    };
    access_verdict_t v = access_decide(h->policy, &ar);
    if (v == ACCESS_EXCHANGE)
        return exchange(h, c);
    if (v != ACCESS_ALLOW)
        return refuse(h, c, access_status(v), access_reason(v));
    gate_serving(&h->gate, slot_of(c)); /* proven: not displaced while this request lasts */
    if (!page && !events && !dest && !stop)
        return refuse(h, c, MHD_HTTP_NOT_FOUND, "no such page");
    if (((dest || stop) && !post) || (!dest && !stop && !get))
        return refuse(h, c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed here");
    if (stop)
        return stop_robot(h, c);
    if (page)
        return respond(c, MHD_HTTP_OK, "text/html; charset=utf-8", hl_console_page,
                       hl_console_page_len, MHD_RESPMEM_PERSISTENT);
    if (events)
        return open_stream(h, c);
    const char *type = MHD_lookup_connection_value(c, MHD_HEADER_KIND,
                                                   MHD_HTTP_HEADER_CONTENT_TYPE);
    if (!type || strncmp(type, "application/json", 16) != 0 ||
        (type[16] != '\0' && type[16] != ';'))
        return refuse(h, c, MHD_HTTP_BAD_REQUEST, "Content-Type must be application/json");
    q->receiving = true;
    return MHD_YES;
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url,
                                  const char *method, const char *version,
                                  const char *upload, size_t *upload_size, void **con_cls)
{
    (void)version;
    http_t *h = cls;
    request_t *q = *con_cls;
    if (!q) {
        q = calloc(1, sizeof *q);
        if (!q)
            return MHD_NO;
        *con_cls = q;
        h->requests++;
        return first_call(h, c, url, method, q);
    }
    if (!q->receiving)
        return MHD_NO; /* answered on the first call; nothing more to read */
    if (*upload_size > 0) {
        if (*upload_size > sizeof q->body - q->len)
            q->too_large = true; /* read on and drop, to answer 400 at the end */
        else
            memcpy(q->body + q->len, upload, *upload_size);
        if (!q->too_large)
            q->len += *upload_size;
        *upload_size = 0;
        return MHD_YES;
    }
    q->receiving = false;
    return finish_destination(h, c, q);
}

/* A request ended: the connection, if it stays, waits for the next one. */
static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    (void)toe;
    http_t *h = cls;
    gate_waiting(&h->gate, slot_of(c), now_ms());
    free(*con_cls);
    *con_cls = NULL;
}

/* A connection handed over (http_run) gets its gate slot; a closed one gives it back. */
static void on_connection(void *cls, struct MHD_Connection *c, void **socket_context,
                          enum MHD_ConnectionNotificationCode toe)
{
    (void)c;
    http_t *h = cls;
    if (toe == MHD_CONNECTION_NOTIFY_STARTED) {
        *socket_context = (void *)(intptr_t)(h->adding + 1);
        h->adding = -1;
    } else {
        gate_closed(&h->gate, (int)(intptr_t)*socket_context - 1);
    }
}

/* The server's messages, at most HTTP_LOG_BURST a minute: under a flood of connections
 * (each one the gate closes is "closed ... with incomplete request") the log would
 * otherwise grow by thousands of lines a second. What is held back is counted. */
static void on_log(void *cls, const char *fmt, va_list ap)
{
    http_t *h = cls;
    if (h->stopping || !h->daemon)
        return; /* the streams it ends on purpose; a start that fails says why itself */
    int64_t now = now_ms();
    if (now - h->log_since >= 60000) {
        if (h->log_held)
            fprintf(stderr, "houghloc-console: http: %lu more messages in the last minute "
                            "not shown\n", h->log_held);
        h->log_since = now;
        h->log_shown = h->log_held = 0;
    }
    if (h->log_shown >= HTTP_LOG_BURST) {
        h->log_held++;
        return;
    }
    h->log_shown++;
    char line[256];
    vsnprintf(line, sizeof line, fmt, ap);
    line[strcspn(line, "\n")] = '\0';
    fprintf(stderr, "houghloc-console: http: %s\n", line);
}

bool http_start(http_t *h, const struct sockaddr *addr, socklen_t addrlen, hub_t *hub,
                const access_policy_t *policy, http_destination_fn dest,
                http_stop_robot_fn stop, void *user, char *why)
{
    *h = (http_t){ .hub = hub, .policy = policy, .on_destination = dest,
                   .on_stop_robot = stop, .user = user, .adding = -1 };
    gate_init(&h->gate);
    h->listen_fd = listen_open(addr, addrlen, policy->bound_host, policy->port, why);
    if (h->listen_fd < 0)
        return false;
    unsigned flags = MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG | MHD_USE_NO_LISTEN_SOCKET;
    if (addr->sa_family == AF_INET6)
        flags |= MHD_USE_IPv6;
    /* The gate keeps the count; the server's own limit is the gate's table, which also
     * holds the connections told to close that the server has not closed yet. */
    h->daemon = MHD_start_daemon(
        flags, 0, NULL, NULL, on_request, h, MHD_OPTION_EXTERNAL_LOGGER, on_log, h,
        MHD_OPTION_CONNECTION_LIMIT, (unsigned)GATE_SLOTS,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)HTTP_IDLE_TIMEOUT_S,
        MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)CONNECTION_MEMORY,
        MHD_OPTION_NOTIFY_COMPLETED, on_completed, h,
        MHD_OPTION_NOTIFY_CONNECTION, on_connection, h, MHD_OPTION_END);
    if (!h->daemon) {
        snprintf(why, ACCESS_WHY_LEN, "cannot start the web server on %s:%u: %s",
                 policy->bound_host, (unsigned)policy->port, strerror(errno));
        close(h->listen_fd);
        h->listen_fd = -1;
        return false;
    }
    return true;
}

bool http_fdset(http_t *h, fd_set *rs, fd_set *ws, fd_set *es, int *max_fd)
{
    MHD_socket m = -1;
    if (MHD_get_fdset2(h->daemon, rs, ws, es, &m, FD_SETSIZE) != MHD_YES ||
        h->listen_fd >= FD_SETSIZE)
        return false;
    FD_SET(h->listen_fd, rs);
    if (h->listen_fd > m)
        m = h->listen_fd;
    if (m > *max_fd)
        *max_fd = m;
    return true;
}

long http_timeout_ms(http_t *h)
{
    MHD_UNSIGNED_LONG_LONG ms;
    long t = MHD_get_timeout(h->daemon, &ms) != MHD_YES ? -1
             : ms > 3600000ULL                          ? 3600000L
                                                        : (long)ms;
    long g = gate_timeout_ms(&h->gate, now_ms());
    return g >= 0 && (t < 0 || g < t) ? g : t;
}

/* Accepts up to ACCEPT_BATCH connections: each one the gate admits goes to the server
 * (after the one it displaces, if any, is told to close); the others are closed. */
static void accept_some(http_t *h)
{
    for (int i = 0; i < ACCEPT_BATCH; i++) {
        struct sockaddr_storage peer;
        socklen_t len = sizeof peer;
        int fd = listen_accept(h->listen_fd, &peer, &len);
        if (fd < 0)
            return; /* none waiting (or out of descriptors: the gate keeps far below) */
        if (fd >= FD_SETSIZE) {
            close(fd);
            continue;
        }
        gate_addr_t a = gate_addr_of((const struct sockaddr *)&peer);
        int victim;
        int slot = gate_open(&h->gate, &a, fd, now_ms(), &victim);
        shut(h, victim);
        if (slot < 0) {
            close(fd);
            continue;
        }
        h->adding = slot;
        if (MHD_add_connection(h->daemon, fd, (const struct sockaddr *)&peer, len) != MHD_YES &&
            h->adding == slot)
            gate_closed(&h->gate, slot); /* the server closed it without taking it */
        h->adding = -1;
    }
}

void http_run(http_t *h, fd_set *rs, fd_set *ws, fd_set *es)
{
    if (FD_ISSET(h->listen_fd, rs))
        accept_some(h);
    for (int slot; (slot = gate_expire(&h->gate, now_ms())) >= 0;)
        shut(h, slot);
    MHD_run_from_select(h->daemon, rs, ws, es);
}

void http_stop(http_t *h)
{
    if (h->daemon) {
        /* libmicrohttpd must not be stopped with a suspended connection: end them all */
        h->stopping = true;
        for (hub_stream_t *s = h->hub->streams; s; s = s->next) {
            s->dead = true;
            if (s->idle) {
                s->idle = false;
                MHD_resume_connection(s->conn);
            }
        }
        MHD_run(h->daemon);
        MHD_stop_daemon(h->daemon);
        h->daemon = NULL;
    }
    if (h->hub && h->listen_fd >= 0) /* started (a zeroed http_t's 0 is not ours) */
        close(h->listen_fd);
    h->listen_fd = -1;
}
