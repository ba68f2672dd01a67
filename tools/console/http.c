/* http.c - the console's web server on libmicrohttpd (http.h). */
#include "http.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <microhttpd.h>

#include "page.h"

#define STREAM_BLOCK (64 * 1024)

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
    if (s->dead)
        return MHD_CONTENT_READER_END_WITH_ERROR;
    size_t n = hub_stream_read(s, buf, max);
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

void http_wake(void *user, hub_stream_t *s)
{
    (void)user;
    MHD_resume_connection(s->conn);
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

/* The first call for a request: access, route and method; the page, the stream and a
 * stop are answered at once, a destination goes on to read its body. */
static enum MHD_Result first_call(http_t *h, struct MHD_Connection *c, const char *url,
                                  const char *method, request_t *q)
{
    const bool get = strcmp(method, MHD_HTTP_METHOD_GET) == 0 ||
                     strcmp(method, MHD_HTTP_METHOD_HEAD) == 0;
    const bool post = strcmp(method, MHD_HTTP_METHOD_POST) == 0;
    const access_request_t ar = {
        .changes_state = !get,
        .host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_HOST),
        .header_token = MHD_lookup_connection_value(c, MHD_HEADER_KIND, ACCESS_HEADER),
        .query_token = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "token"),
    };
    switch (access_decide(h->policy, &ar)) {
    case ACCESS_BAD_HOST:
        return refuse(h, c, MHD_HTTP_FORBIDDEN,
                      "the Host header does not name this console's address");
    case ACCESS_NEED_TOKEN:
        return refuse(h, c, MHD_HTTP_UNAUTHORIZED,
                      get ? "a token is required: open the address printed at start"
                          : "the X-Houghloc-Token header is missing or wrong");
    case ACCESS_ALLOW:
        break;
    }
    const bool page = strcmp(url, "/") == 0, events = strcmp(url, "/events") == 0;
    const bool dest = strcmp(url, "/destination") == 0, stop = strcmp(url, "/stop") == 0;
    if (!page && !events && !dest && !stop)
        return refuse(h, c, MHD_HTTP_NOT_FOUND, "no such page");
    if (((dest || stop) && !post) || (!dest && !stop && !get))
        return refuse(h, c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed here");
    if (stop)
        return stop_robot(h, c);
    if (page)
        return respond(c, MHD_HTTP_OK, "text/html; charset=utf-8", h->page, h->page_len,
                       MHD_RESPMEM_PERSISTENT);
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

static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    (void)cls, (void)c, (void)toe;
    free(*con_cls);
    *con_cls = NULL;
}

static void on_log(void *cls, const char *fmt, va_list ap)
{
    const http_t *h = cls;
    if (h->stopping || !h->daemon)
        return; /* the streams it ends on purpose; a start that fails says why itself */
    char line[256];
    vsnprintf(line, sizeof line, fmt, ap);
    line[strcspn(line, "\n")] = '\0';
    fprintf(stderr, "houghloc-console: http: %s\n", line);
}

/* The page with the token where the placeholder stands (page.html says where). */
static bool build_page(http_t *h, const char *token, char *why)
{
    static const char mark[] = "%%HOUGHLOC_TOKEN%%";
    const char *at = strstr(hl_console_page, mark); /* the array ends in a NUL */
    if (!at) {
        snprintf(why, ACCESS_WHY_LEN, "the embedded page has no token placeholder");
        return false;
    }
    size_t before = (size_t)(at - hl_console_page), tl = strlen(token);
    size_t after = hl_console_page_len - before - (sizeof mark - 1);
    h->page_len = before + tl + after;
    h->page = malloc(h->page_len);
    if (!h->page) {
        snprintf(why, ACCESS_WHY_LEN, "out of memory");
        return false;
    }
    memcpy(h->page, hl_console_page, before);
    memcpy(h->page + before, token, tl);
    memcpy(h->page + before + tl, at + sizeof mark - 1, after);
    return true;
}

bool http_start(http_t *h, const struct sockaddr *addr, hub_t *hub,
                const access_policy_t *policy, http_destination_fn dest,
                http_stop_robot_fn stop, void *user, char *why)
{
    *h = (http_t){ .hub = hub, .policy = policy, .on_destination = dest,
                   .on_stop_robot = stop, .user = user };
    if (!build_page(h, policy->token, why))
        return false;
    unsigned flags = MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    if (addr->sa_family == AF_INET6)
        flags |= MHD_USE_IPv6;
    h->daemon = MHD_start_daemon(
        flags, 0, NULL, NULL, on_request, h, MHD_OPTION_EXTERNAL_LOGGER, on_log, h,
        MHD_OPTION_SOCK_ADDR, addr,
        MHD_OPTION_CONNECTION_LIMIT, (unsigned)HTTP_MAX_CONNECTIONS,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)HTTP_IDLE_TIMEOUT_S,
        MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)(128 * 1024),
        MHD_OPTION_NOTIFY_COMPLETED, on_completed, h, MHD_OPTION_END);
    if (!h->daemon) {
        snprintf(why, ACCESS_WHY_LEN, "cannot serve on %s:%u: %s", policy->bound_host,
                 (unsigned)policy->port, strerror(errno));
        free(h->page);
        h->page = NULL;
        return false;
    }
    return true;
}

bool http_fdset(http_t *h, fd_set *rs, fd_set *ws, fd_set *es, int *max_fd)
{
    MHD_socket m = -1;
    if (MHD_get_fdset2(h->daemon, rs, ws, es, &m, FD_SETSIZE) != MHD_YES)
        return false;
    if (m > *max_fd)
        *max_fd = m;
    return true;
}

long http_timeout_ms(http_t *h)
{
    MHD_UNSIGNED_LONG_LONG ms;
    if (MHD_get_timeout(h->daemon, &ms) != MHD_YES)
        return -1;
    return ms > 3600000ULL ? 3600000L : (long)ms;
}

void http_run(http_t *h, fd_set *rs, fd_set *ws, fd_set *es)
{
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
    free(h->page);
    h->page = NULL;
}
