/* link.c - link specs, the TCP transport, and reading and writing any link (link.h). */
#include "link.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define WHY(...) snprintf(why, HL_LINK_WHY_LEN, __VA_ARGS__)

/* getaddrinfo's hints for the robot's address. AI_NUMERICHOST: the daemon has one thread,
 * and a host name would be looked up at every reconnection, which blocks on a name server
 * that does not answer (10.1 s were seen, past the service's 10 s watchdog); a numeric
 * address is only parsed, never looked up. */
static const struct addrinfo numeric_hints = {
    .ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM,
    .ai_flags = AI_NUMERICHOST | AI_NUMERICSERV,
};

/* Writes the robot's address into out->host: an IPv4 or IPv6 address (bare or in
 * brackets, [::1]), or localhost, taken as 127.0.0.1 without a lookup (the loopback
 * houghloc-sim listens on; it serves IPv4 only). */
static bool parse_host(const char *rest, const char *host, size_t len, hl_link_spec_t *out,
                       char *why)
{
    if (len >= 2 && host[0] == '[' && host[len - 1] == ']') {
        host++;
        len -= 2;
    }
    if (len == 0 || len >= sizeof out->host)
        return WHY("robot link 'tcp:%.200s': want tcp:HOST:PORT", rest), false;
    memcpy(out->host, host, len);
    out->host[len] = '\0';
    if (strcmp(out->host, "localhost") == 0)
        snprintf(out->host, sizeof out->host, "127.0.0.1");
    struct addrinfo *ai = NULL;
    if (getaddrinfo(out->host, NULL, &numeric_hints, &ai) != 0)
        return WHY("robot link 'tcp:%.60s': HOST must be a numeric IPv4/IPv6 address (name "
                   "resolution would block the daemon)", rest), false;
    freeaddrinfo(ai);
    return true;
}

static bool parse_tcp(const char *rest, hl_link_spec_t *out, char *why)
{
    const char *colon = strrchr(rest, ':');
    if (!colon || colon == rest)
        return WHY("robot link 'tcp:%.200s': want tcp:HOST:PORT", rest), false;
    char *end = NULL;
    errno = 0;
    long port = strtol(colon + 1, &end, 10);
    if (errno || end == colon + 1 || *end || port < 1 || port > 65535)
        return WHY("robot link 'tcp:%s': port must be a number 1..65535", rest), false;
    if (!parse_host(rest, rest, (size_t)(colon - rest), out, why))
        return false;
    out->kind = HL_LINK_TCP;
    snprintf(out->port, sizeof out->port, "%ld", port);
    return true;
}

static bool parse_serial(const char *rest, hl_link_spec_t *out, char *why)
{
    const char *comma = strchr(rest, ',');
    size_t dev_len = comma ? (size_t)(comma - rest) : strlen(rest);
    if (dev_len == 0 || dev_len >= sizeof out->device)
        return WHY("robot link 'serial:%s': want serial:DEVICE[,BAUD]", rest), false;
    out->kind = HL_LINK_SERIAL;
    memcpy(out->device, rest, dev_len);
    out->device[dev_len] = '\0';
    out->baud = 9600;   /* ARCOS starts at 9600 baud */
    if (!comma)
        return true;
    static const int rates[] = { 9600, 19200, 38400, 57600, 115200 };
    char *end = NULL;
    errno = 0;
    long baud = strtol(comma + 1, &end, 10);
    for (size_t i = 0; !errno && end != comma + 1 && !*end && i < sizeof rates / sizeof rates[0]; i++)
        if (baud == rates[i]) {
            out->baud = rates[i];
            return true;
        }
    return WHY("robot link 'serial:%s': baud rate '%s' is not one ARCOS speaks (9600, 19200, "
               "38400, 57600 or 115200)", rest, comma + 1), false;
}

static bool parse_file(const char *rest, hl_link_spec_t *out, char *why)
{
    size_t len = strlen(rest);
    if (len == 0)
        return WHY("robot link 'file:': want file:CAPTURE, a robot's captured bytes"), false;
    if (len >= sizeof out->path)
        return WHY("robot link 'file:%.100s...': the file name is longer than %d characters",
                   rest, HL_LINK_SPEC_MAX - 1), false;
    out->kind = HL_LINK_FILE;
    memcpy(out->path, rest, len + 1);
    return true;
}

bool hl_link_spec_parse(const char *text, hl_link_spec_t *out, char *why)
{
    memset(out, 0, sizeof *out);
    if (strncmp(text, "tcp:", 4) == 0)
        return parse_tcp(text + 4, out, why);
    if (strncmp(text, "serial:", 7) == 0)
        return parse_serial(text + 7, out, why);
    if (strncmp(text, "file:", 5) == 0)
        return parse_file(text + 5, out, why);
    return WHY("robot link '%.200s': want tcp:HOST:PORT, serial:DEVICE[,BAUD] or "
               "file:CAPTURE", text), false;
}

static bool open_tcp(hl_link_t *l, const hl_link_spec_t *spec, char *why)
{
    /* numeric: parsed, never looked up (the spec was checked so by parse_host); the
     * socket is non-blocking, so connect returns at once (EINPROGRESS) and the loop waits
     * for it to turn writable (hl_link_connected) */
    struct addrinfo *ai = NULL;
    int rc = getaddrinfo(spec->host, spec->port, &numeric_hints, &ai);
    if (rc != 0)
        return WHY("%.200s: %s", l->name, gai_strerror(rc)), false;
    l->fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (l->fd < 0) {
        WHY("%.200s: socket: %s", l->name, strerror(errno));
        freeaddrinfo(ai);
        return false;
    }
    rc = connect(l->fd, ai->ai_addr, ai->ai_addrlen);
    freeaddrinfo(ai);
    if (rc == 0)
        return true;
    if (errno == EINPROGRESS) {
        l->connecting = true;
        return true;
    }
    return WHY("%.200s: %s", l->name, strerror(errno)), false;
}

hl_link_t *hl_link_open(const hl_link_spec_t *spec, char *why)
{
    hl_link_t *l = calloc(1, sizeof *l);
    if (!l)
        return WHY("out of memory"), NULL;
    l->kind = spec->kind;
    l->fd = -1;
    bool ok;
    if (spec->kind == HL_LINK_TCP) {
        snprintf(l->name, sizeof l->name, "tcp:%s:%s", spec->host, spec->port);
        ok = open_tcp(l, spec, why);
    } else if (spec->kind == HL_LINK_SERIAL) {
        snprintf(l->name, sizeof l->name, "serial:%s", spec->device);
        ok = hl_link_open_serial(l, spec, why);
    } else {
        snprintf(l->name, sizeof l->name, "file:%s", spec->path);
        ok = hl_link_open_file(l, spec, why);
    }
    if (!ok) {
        hl_link_close(l);
        return NULL;
    }
    return l;
}

void hl_link_close(hl_link_t *l)
{
    if (!l)
        return;
    if (l->kind == HL_LINK_SERIAL)
        hl_link_close_serial(l);
    else if (l->fd >= 0)
        close(l->fd);
    free(l);
}

int hl_link_fd(const hl_link_t *l)
{
    return l->fd;
}

bool hl_link_connecting(const hl_link_t *l)
{
    return l->connecting;
}

bool hl_link_connected(hl_link_t *l, char *why)
{
    int err = 0;
    socklen_t len = sizeof err;
    if (getsockopt(l->fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0)
        err = errno;
    l->connecting = false;
    if (err)
        return WHY("%.200s: %s", l->name, strerror(err)), false;
    return true;
}

ssize_t hl_link_read(hl_link_t *l, void *buf, size_t n, char *why)
{
    if (l->kind == HL_LINK_FILE)
        return hl_link_read_file(l, buf, n, why);
    ssize_t got = read(l->fd, buf, n);
    if (got > 0)
        return got;
    if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return 0;
    if (got == 0 && l->kind == HL_LINK_SERIAL)
        return 0;   /* a tty with nothing to read, not an end */
    if (got == 0)
        return WHY("%.200s: the robot closed the connection", l->name), -1;
    return WHY("%.200s: read: %s", l->name, strerror(errno)), -1;
}

ssize_t hl_link_write(hl_link_t *l, const void *buf, size_t n, char *why)
{
    if (l->kind == HL_LINK_FILE)
        return (ssize_t)n;  /* the captured robot already answered what it was sent */
    ssize_t put = write(l->fd, buf, n);
    if (put >= 0)
        return put;
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
        return 0;
    return WHY("%.200s: write: %s", l->name, strerror(errno)), -1;
}

bool hl_link_ended(const hl_link_t *l)
{
    return l->ended;
}
