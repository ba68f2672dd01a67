/*
 * console_load.c - hl-console-load: the load of the Console trial
 * (tools/lab/trials/console.sh) on houghloc-console, one kind per run:
 *
 *   --mode maps       publishes MAP messages of --vectors vectors (up to the largest the
 *                     wire allows, 2^20) at --rate a second, each a new version, the
 *                     vectors spread over the whole coordinate range so that their JSON
 *                     is as long as it gets;
 *   --mode stall      opens --count event streams (GET /events with the token), reads
 *                     each one's response header, then never reads again: the pages
 *                     that stopped reading; their receive buffers are made small, so the
 *                     console feels the stall at once;
 *   --mode slowloris  keeps --count connections that send a request header one line a
 *                     second and never finish it; each one the console closes is opened
 *                     again at once.
 *
 * Loopback only (127.0.0.1, and udpm:// with ttl=0). The last stdout line says what was
 * done; progress goes to stderr.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <lcm/lcm.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "houghloc/bus.h"
#include "houghloc/map.h"
#include "houghloc/rng.h"
#include "houghloc/version.h"
#include "trial_args.h"

#define PROG "hl-console-load"
#define MAX_CONNS 2000
#define STALL_RCVBUF 4096

static const char usage[] =
    "Usage: hl-console-load --mode maps --lcm-url URL [--vectors N] [--rate R] [--seconds S]\n"
    "       hl-console-load --mode stall --port P --token T [--count N] [--seconds S]\n"
    "       hl-console-load --mode slowloris --port P [--count N] [--seconds S]\n"
    "The load of the Console trial on houghloc-console (loopback only):\n"
    "  maps       MAP messages of N vectors (default 1500; at most 1048576, the largest the\n"
    "             wire allows) at R a second (default 20), on udpm:// with ttl=0\n"
    "  stall      N event streams (default 64) with the token, their header read, then\n"
    "             never read again\n"
    "  slowloris  N connections (default 500) that never finish a request header, each\n"
    "             opened again as soon as the console closes it\n"
    "  --prefix P   the channel prefix (maps)\n"
    "  --seconds S  how long, 0.1..3600 (default 10); SIGINT or SIGTERM stops sooner\n"
    "The last stdout line:\n"
    "  maps sent=<n> bytes=<b> vectors=<n> publish_errors=<n>\n"
    "  stall opened=<n> ok=<n> (ok: answered 200)\n"
    "  slowloris held=<n> opened=<n> closed_by_console=<n>\n"
    "Exit status: 0 done, 1 a failure, 2 bad usage.\n";

typedef struct options {
    const char *mode, *url, *prefix, *token;
    long vectors, rate, count, port;
    double seconds;
} options_t;

static volatile sig_atomic_t stop_requested;

static void on_stop(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static int64_t mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static bool whole(const char *v, double lo, double hi, long *out)
{
    double d;
    if (!trial_parse_double(v, lo, hi, &d) || d != (double)(long)d)
        return false;
    *out = (long)d;
    return true;
}

/* @return -1 to go on, else an exit status (after --help or an error message). */
static int parse_args(int argc, char **argv, options_t *o)
{
    static const char *const names[] = { "--mode", "--lcm-url", "--vectors", "--rate",
                                          "--seconds", "--port", "--count", "--token",
                                          "--prefix" };
    const trial_cli_t cli = { PROG, usage, HL_VERSION, names, 9, false };
    for (int i = 1; i < argc; i++) {
        const char *v;
        int status;
        int k = trial_next_option(&cli, argc, argv, &i, &v, &status);
        if (k < 0)
            return status;
        bool ok = true;
        switch (k) {
        case 0: o->mode = v; break;
        case 1: o->url = v; break;
        case 2: ok = whole(v, 0, HL_MAP_MAX_CAPACITY, &o->vectors); break;
        case 3: ok = whole(v, 1, 1000, &o->rate); break;
        case 4: ok = trial_parse_double(v, 0.1, 3600.0, &o->seconds); break;
        case 5: ok = whole(v, 1, 65535, &o->port); break;
        case 6: ok = whole(v, 1, MAX_CONNS, &o->count); break;
        case 7: o->token = v; break;
        default: o->prefix = v; break;
        }
        if (!ok)
            return trial_usage_error(PROG, "a value out of range:", v);
    }
    if (!o->mode || (strcmp(o->mode, "maps") != 0 && strcmp(o->mode, "stall") != 0 &&
                     strcmp(o->mode, "slowloris") != 0))
        return trial_usage_error(PROG, "--mode: give maps, stall or slowloris, not",
                                 o->mode ? o->mode : "");
    if (strcmp(o->mode, "maps") == 0 &&
        (!o->url || strncmp(o->url, "udpm://", 7) != 0 || !strstr(o->url, "ttl=0")))
        return trial_usage_error(PROG, "--lcm-url: give a udpm:// URL with ttl=0, not",
                                 o->url ? o->url : "");
    if (strcmp(o->mode, "maps") != 0 && !o->port)
        return trial_usage_error(PROG, "--port is required for", o->mode);
    if (strcmp(o->mode, "stall") == 0 && !o->token)
        return trial_usage_error(PROG, "--token is required for", o->mode);
    return -1;
}

/* ---- maps ------------------------------------------------------------------------------ */

static int run_maps(const options_t *o)
{
    lcm_t *lcm = lcm_create(o->url);
    if (!lcm)
        return fprintf(stderr, "%s: cannot open LCM at %s\n", PROG, o->url), 1;
    char channel[HL_BUS_CHANNEL_MAX];
    if (!hl_bus_channel(o->prefix, HL_CHANNEL_MAP, channel))
        return fprintf(stderr, "%s: bad --prefix\n", PROG), 1;
    uint32_t n = (uint32_t)o->vectors;
    hl_vector_t *v = calloc(n ? n : 1, sizeof *v);
    size_t cap = hl_bus_map_bytes(n);
    uint8_t *buf = malloc(cap);
    if (!v || !buf)
        return fprintf(stderr, "%s: out of memory\n", PROG), 1;
    hl_rng_t rng;
    hl_rng_seed(&rng, 1);
    /* the whole coordinate range, so that each vector's JSON is as long as it gets */
    for (uint32_t i = 0; i < n; i++) {
        v[i].x_mm = (hl_mm_t)((int32_t)(hl_rng_next(&rng) % (2u * HL_COORD_MAX_MM + 1)) -
                              HL_COORD_MAX_MM);
        v[i].y_mm = (hl_mm_t)((int32_t)(hl_rng_next(&rng) % (2u * HL_COORD_MAX_MM + 1)) -
                              HL_COORD_MAX_MM);
        v[i].normal = (hl_bam_t)hl_rng_next(&rng);
        v[i].range_mm = (uint16_t)(hl_rng_next(&rng) % (HL_RANGE_MAX_MM + 1));
    }
    hl_bus_map_t m = { .capacity = n ? (int32_t)n : 1, .count = n, .vectors = v };
    long long sent = 0, errors = 0, bytes = 0;
    const int64_t start = mono_ms(), end = start + (int64_t)(o->seconds * 1000);
    for (int64_t now = start; now < end && !stop_requested; now = mono_ms()) {
        long long due = (now - start) * o->rate / 1000 + 1;
        if (sent < due) {
            m.version = sent;
            m.utime = now * 1000;
            int len = hl_bus_encode_map(&m, buf, cap);
            if (len < 0)
                return fprintf(stderr, "%s: the map does not encode (a bug)\n", PROG), 1;
            if (lcm_publish(lcm, channel, buf, (unsigned)len) != 0)
                errors++;
            sent++;
            bytes += len;
            continue;
        }
        struct timespec pause = { 0, 2000000 };
        nanosleep(&pause, NULL);
    }
    lcm_destroy(lcm);
    free(v);
    free(buf);
    printf("maps sent=%lld bytes=%lld vectors=%u publish_errors=%lld\n", sent, bytes, n,
           errors);
    return 0;
}

/* ---- connections ----------------------------------------------------------------------- */

/* A non-blocking TCP connection to 127.0.0.1:port under way; -1 on failure. */
static int connect_local(long port, int rcvbuf)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        return -1;
    if (rcvbuf > 0)
        setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons((uint16_t)port) };
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) != 0 && errno != EINPROGRESS) {
        close(fd);
        return -1;
    }
    return fd;
}

/* Writes all of @p s on a non-blocking socket within @p ms. */
static bool send_all(int fd, const char *s, int ms)
{
    size_t n = strlen(s), done = 0;
    int64_t end = mono_ms() + ms;
    while (done < n) {
        ssize_t w = send(fd, s + done, n - done, MSG_NOSIGNAL);
        if (w > 0) {
            done += (size_t)w;
            continue;
        }
        if (w < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != ENOTCONN)
            return false;
        struct pollfd p = { .fd = fd, .events = POLLOUT };
        int left = (int)(end - mono_ms());
        if (left <= 0 || poll(&p, 1, left) < 0)
            return false;
    }
    return true;
}

/* Reads the response's header (up to the blank line) within @p ms: @return the status,
 * or 0. Not a byte of the body is read on purpose beyond what came with the header. */
static int read_status(int fd, int ms)
{
    char buf[2048];
    size_t n = 0;
    int64_t end = mono_ms() + ms;
    while (n < sizeof buf - 1) {
        ssize_t r = recv(fd, buf + n, 1, 0); /* one byte at a time: stop at the header's end */
        if (r > 0) {
            n++;
            buf[n] = '\0';
            if (n >= 4 && memcmp(buf + n - 4, "\r\n\r\n", 4) == 0)
                break;
            continue;
        }
        if (r == 0 || (errno != EAGAIN && errno != EWOULDBLOCK))
            return 0;
        struct pollfd p = { .fd = fd, .events = POLLIN };
        int left = (int)(end - mono_ms());
        if (left <= 0 || poll(&p, 1, left) <= 0)
            return 0;
    }
    int status = 0;
    return sscanf(buf, "HTTP/1.%*d %d", &status) == 1 ? status : 0;
}

static int run_stall(const options_t *o)
{
    static int fds[MAX_CONNS];
    char req[512];
    snprintf(req, sizeof req,
             "GET /events HTTP/1.1\r\nHost: 127.0.0.1:%ld\r\nAuthorization: Bearer %s\r\n"
             "Accept: text/event-stream\r\n\r\n",
             o->port, o->token);
    long opened = 0, ok = 0;
    for (long i = 0; i < o->count && !stop_requested; i++) {
        fds[i] = connect_local(o->port, STALL_RCVBUF);
        if (fds[i] < 0)
            continue;
        opened++;
        if (send_all(fds[i], req, 3000) && read_status(fds[i], 3000) == 200)
            ok++;
    }
    fprintf(stderr, "%s: %ld streams open, %ld answered 200; not reading for %.1f s\n", PROG,
            opened, ok, o->seconds);
    const int64_t end = mono_ms() + (int64_t)(o->seconds * 1000);
    while (!stop_requested && mono_ms() < end) {
        struct timespec pause = { 0, 50000000 };
        nanosleep(&pause, NULL);
    }
    for (long i = 0; i < o->count; i++)
        if (fds[i] >= 0)
            close(fds[i]);
    printf("stall opened=%ld ok=%ld\n", opened, ok);
    return 0;
}

typedef struct loris {
    int fd;
    unsigned lines;             /* header lines sent: the request line first */
    int64_t next_at;            /* when the next one is due */
} loris_t;

/* Sends @p l's next header line when it is due. @return false when the console closed
 * the connection. */
static bool loris_step(loris_t *l, long port, int64_t now)
{
    if (now < l->next_at)
        return true;
    char line[128];
    if (l->lines == 0)
        snprintf(line, sizeof line, "GET / HTTP/1.1\r\nHost: 127.0.0.1:%ld\r\n", port);
    else
        snprintf(line, sizeof line, "X-Slow-%u: 1\r\n", l->lines);
    ssize_t w = send(l->fd, line, strlen(line), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (w < 0)
        return errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOTCONN; /* later */
    l->lines++;
    l->next_at = now + 1000;
    return true;
}

static int run_slowloris(const options_t *o)
{
    static loris_t c[MAX_CONNS];
    static struct pollfd p[MAX_CONNS];
    long long opened = 0, closed = 0;
    long held = 0;
    for (long i = 0; i < o->count; i++)
        c[i].fd = -1;
    const int64_t end = mono_ms() + (int64_t)(o->seconds * 1000);
    while (!stop_requested && mono_ms() < end) {
        int64_t now = mono_ms();
        held = 0;
        for (long i = 0; i < o->count; i++) {
            if (c[i].fd < 0) {
                c[i] = (loris_t){ .fd = connect_local(o->port, 0), .next_at = now };
                opened += c[i].fd >= 0;
            }
            if (c[i].fd >= 0 && !loris_step(&c[i], o->port, now)) {
                close(c[i].fd);
                c[i].fd = -1;
                closed++;
            }
            p[i] = (struct pollfd){ .fd = c[i].fd, .events = POLLIN };
            held += c[i].fd >= 0;
        }
        poll(p, (nfds_t)o->count, 50);
        for (long i = 0; i < o->count; i++) {
            if (c[i].fd < 0 || !(p[i].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            char junk[4096];
            ssize_t r = recv(c[i].fd, junk, sizeof junk, MSG_DONTWAIT);
            if (r <= 0 && !(r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))) {
                close(c[i].fd); /* the console closed it: another at once, next round */
                c[i].fd = -1;
                closed++;
            }
        }
    }
    for (long i = 0; i < o->count; i++)
        if (c[i].fd >= 0)
            close(c[i].fd);
    printf("slowloris held=%ld opened=%lld closed_by_console=%lld\n", held, opened, closed);
    return 0;
}

int main(int argc, char **argv)
{
    options_t o = { .prefix = "", .vectors = 1500, .rate = 20, .seconds = 10.0 };
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if (strcmp(o.mode, "stall") == 0 && !o.count)
        o.count = 64;
    if (strcmp(o.mode, "slowloris") == 0 && !o.count)
        o.count = 500;
    struct sigaction sa = { .sa_handler = on_stop };
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    if (strcmp(o.mode, "maps") == 0)
        return run_maps(&o);
    if (strcmp(o.mode, "stall") == 0)
        return run_stall(&o);
    return run_slowloris(&o);
}
