/*
 * request.c - the part of houghloc-goto and houghloc-ctl that talks to houghlocd: the
 * common options, one signed request on LCM, and the wait for its REPLY (request.h).
 */
#include "request.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>
#include <sodium.h>

#include "houghloc/auth.h"
#include "houghloc/fixed.h"
#include "houghloc/version.h"
#include "keyfile.h"

#define COORD_MAX_M (HL_COORD_MAX_MM / 1000.0)

/* ---- the command line ---------------------------------------------------------------- */

int req_usage_error(const char *prog, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", prog);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "; try %s --help\n", prog);
    va_end(ap);
    return EXIT_USAGE;
}

bool req_parse_number(const char *s, double *out)
{
    /* no leading spaces and no hexadecimal, which strtod would also take */
    if (isspace((unsigned char)*s) || strpbrk(s, "xX"))
        return false;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0')
        return false;
    *out = v;
    return true;
}

int req_parse_value(const char *prog, const char *name, const char *arg, bool coordinate,
                    double *out)
{
    double v;
    if (!req_parse_number(arg, &v))
        return req_usage_error(prog, "%s \"%s\" is not a number", name, arg);
    if (!isfinite(v))
        return req_usage_error(prog, "%s \"%s\" is not a finite number", name, arg);
    if (coordinate && fabs(round(v * 1000.0)) > HL_COORD_MAX_MM)
        return req_usage_error(prog, "%s %s m is outside +-%.3f m", name, arg, COORD_MAX_M);
    *out = v;
    return WAITING;
}

int req_parse_option(const char *prog, int argc, char **argv, int *i, req_options_t *o)
{
    static const char *const names[] = { "--lcm-url", "--prefix", "--key", "--timeout" };
    const char *a = argv[*i];
    const char *eq = strchr(a, '=');
    size_t n = eq ? (size_t)(eq - a) : strlen(a);
    int which = -1;
    for (int k = 0; k < 4; k++)
        if (strlen(names[k]) == n && strncmp(a, names[k], n) == 0)
            which = k;
    if (which < 0)
        return REQ_NOT_MINE;
    const char *v = eq ? eq + 1 : *i + 1 < argc ? argv[++*i] : NULL;
    if (!v)
        return req_usage_error(prog, "%s needs a value", names[which]);
    if (which == 0) {
        if (!*v)
            return req_usage_error(prog, "--lcm-url is empty");
        o->url = v;
    } else if (which == 1) {
        /* The prefix alone decides: DESTINATION is the longest name a client uses. */
        char channel[HL_BUS_CHANNEL_MAX];
        if (!hl_bus_channel(v, HL_CHANNEL_DESTINATION, channel))
            return req_usage_error(prog,
                                   "--prefix \"%s\": at most %d letters, digits, "
                                   "'_', '-', '.' or '/'",
                                   v, HL_BUS_PREFIX_MAX);
        o->prefix = v;
    } else if (which == 2) {
        if (!*v)
            return req_usage_error(prog, "--key is empty");
        o->key_file = v;
    } else {
        double t;
        if (!req_parse_number(v, &t) || !(t >= 0.1 && t <= 3600.0))
            return req_usage_error(prog, "--timeout \"%s\": give seconds from 0.1 to 3600", v);
        o->timeout_s = t;
    }
    return WAITING;
}

int req_walk_args(const req_args_t *a, int argc, char **argv, req_options_t *o)
{
    bool options_done = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        double ignored;
        int rc;
        if (options_done || arg[0] != '-' || arg[1] == '\0' ||
            (arg[1] != '-' && req_parse_number(arg, &ignored))) {
            rc = a->positional(a->user, arg);
        } else if (strcmp(arg, "--") == 0) {
            options_done = true;
            continue;
        } else if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            fputs(a->usage, stdout);
            return EXIT_DONE;
        } else if (strcmp(arg, "--version") == 0) {
            printf("%s %s\n", a->prog, HL_VERSION);
            return EXIT_DONE;
        } else {
            rc = a->option ? a->option(a->user, arg) : REQ_NOT_MINE;
            if (rc == REQ_NOT_MINE)
                rc = req_parse_option(a->prog, argc, argv, &i, o);
            if (rc == REQ_NOT_MINE)
                return req_usage_error(a->prog, "unknown option \"%s\"", arg);
        }
        if (rc != WAITING)
            return rc;
    }
    return WAITING;
}

/* ---- waiting for the answers --------------------------------------------------------- */

typedef struct waiter {
    const char *prog;
    int64_t seq;
    req_request_t *r;
    int undecodable;    /* REPLY messages that did not decode */
    int result;         /* WAITING, or the exit code */
} waiter_t;

/* What to print when the daemon's message is empty (ACCEPTED: the request's text). */
static const char *const default_message[] = {
    [HL_BUS_REPLY_ACCEPTED] = "",
    [HL_BUS_REPLY_ARRIVED] = "the robot reached the destination",
    [HL_BUS_REPLY_REJECTED_FENCE] = "the destination is outside the geofence",
    [HL_BUS_REPLY_REJECTED_AUTH] = "missing or wrong MAC (see --key)",
    [HL_BUS_REPLY_REJECTED_REPLAY] = "seq not above the last accepted one",
    [HL_BUS_REPLY_NO_ROBOT] = "",
    [HL_BUS_REPLY_FAILED] = "the daemon could not do it",
    [HL_BUS_REPLY_REJECTED_INVALID] = "a field is out of range",
};

static int exit_code(int8_t result, bool accepted_ends)
{
    switch (result) {
    case HL_BUS_REPLY_ACCEPTED: return accepted_ends ? EXIT_DONE : WAITING;
    case HL_BUS_REPLY_ARRIVED: return EXIT_DONE;
    case HL_BUS_REPLY_REJECTED_FENCE:
    case HL_BUS_REPLY_REJECTED_AUTH:
    case HL_BUS_REPLY_REJECTED_REPLAY:
    case HL_BUS_REPLY_REJECTED_INVALID: return EXIT_REJECTED;
    case HL_BUS_REPLY_NO_ROBOT: return EXIT_NO_ROBOT;
    case HL_BUS_REPLY_FAILED: return EXIT_FAILED;
    default: return EXIT_ERROR;
    }
}

static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    waiter_t *w = user;
    hl_bus_reply_t r;
    if (hl_bus_decode_reply(rbuf->data, rbuf->data_size, &r, NULL) != HL_OK) {
        w->undecodable++;
        return;
    }
    if (r.seq != w->seq || w->result != WAITING)
        return; /* another client's request */
    if (r.result == HL_BUS_REPLY_ACCEPTED && w->r->accepted)
        return; /* a repeated answer */
    /* The text came over the network: print it as one line of plain characters. */
    for (char *c = r.message; *c; c++)
        if (iscntrl((unsigned char)*c))
            *c = '?';
    const char *text = r.message;
    if (!text[0] && r.result == HL_BUS_REPLY_ACCEPTED && w->r->accepted_text)
        text = w->r->accepted_text;
    else if (!text[0] && r.result >= 0 && r.result <= HL_BUS_REPLY_REJECTED_INVALID)
        text = default_message[r.result];
    bool good = r.result == HL_BUS_REPLY_ACCEPTED || r.result == HL_BUS_REPLY_ARRIVED;
    FILE *out = good ? stdout : stderr;
    if (r.result == HL_BUS_REPLY_NO_ROBOT)
        fprintf(out, "%s: NO_ROBOT: no robot is connected to the daemon%s%s\n", w->prog,
                r.message[0] ? ": " : "", r.message);
    else
        fprintf(out, "%s: %s: %s\n", w->prog, hl_bus_reply_name(r.result), text);
    fflush(out);
    w->r->accepted = w->r->accepted || r.result == HL_BUS_REPLY_ACCEPTED;
    w->result = exit_code(r.result, w->r->accepted_ends);
}

static int64_t clock_us(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* Handles REPLY until an answer ends the wait or the timeout runs out. */
static int wait_for_answer(lcm_t *lcm, waiter_t *w, double timeout_s)
{
    const int64_t deadline = clock_us(CLOCK_MONOTONIC) + (int64_t)llround(timeout_s * 1e6);
    const int fd = lcm_get_fileno(lcm);
    while (w->result == WAITING) {
        int64_t left = deadline - clock_us(CLOCK_MONOTONIC);
        if (left <= 0)
            return EXIT_TIMEOUT;
        struct pollfd p = { .fd = fd, .events = POLLIN };
        int n = poll(&p, 1, (int)((left + 999) / 1000));
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            fprintf(stderr, "%s: poll: %s\n", w->prog, strerror(errno));
            return EXIT_ERROR;
        }
        if (n > 0 && lcm_handle(lcm) != 0) {
            fprintf(stderr, "%s: LCM stopped receiving\n", w->prog);
            return EXIT_ERROR;
        }
    }
    return w->result;
}

/* ---- sending ------------------------------------------------------------------------- */

/* Stamps the request with the clock and signs it when a key file is given, then encodes
 * it into buf (cap bytes). @return the length, or -1 after the message (exit 1). */
static int stamp_sign_encode(const char *prog, const req_options_t *o, req_request_t *r,
                             uint8_t *buf, size_t cap)
{
    const bool is_cmd = r->kind == REQ_COMMAND;
    const char *noun = is_cmd ? "command" : "destination";
    const int64_t now = clock_us(CLOCK_REALTIME);
    /* The seq is the wall clock in microseconds: strictly increasing across calls. */
    if (is_cmd) {
        r->msg.command.utime = r->msg.command.seq = now;
        memset(r->msg.command.mac, 0, sizeof r->msg.command.mac);
    } else {
        r->msg.destination.utime = r->msg.destination.seq = now;
        memset(r->msg.destination.mac, 0, sizeof r->msg.destination.mac);
    }
    if (o->key_file) {
        if (!hl_auth_init()) {
            fprintf(stderr, "%s: libsodium does not initialize\n", prog);
            return -1;
        }
        hl_auth_key_t key;
        char why[HL_KEYFILE_WHY_LEN];
        if (hl_keyfile_load(o->key_file, &key, why) != HL_OK) {
            fprintf(stderr, "%s: %s\n", prog, why);
            return -1;
        }
        bool ok = is_cmd ? hl_auth_sign_command(&key, &r->msg.command)
                         : hl_auth_sign_destination(&key, &r->msg.destination);
        sodium_memzero(&key, sizeof key);
        if (!ok) {
            fprintf(stderr, "%s: the %s does not encode\n", prog, noun);
            return -1;
        }
    }
    int len = is_cmd ? hl_bus_encode_command(&r->msg.command, buf, cap)
                     : hl_bus_encode_destination(&r->msg.destination, buf, cap);
    if (len < 0)
        fprintf(stderr, "%s: the %s does not encode\n", prog, noun);
    return len;
}

int req_run(const char *prog, const req_options_t *o, req_request_t *r)
{
    const char *url = o->url;
    if (!url) {
        const char *env = getenv("LCM_DEFAULT_URL");
        url = env && *env ? env : REQ_DEFAULT_URL;
    }
    const bool is_cmd = r->kind == REQ_COMMAND;
    char req_channel[HL_BUS_CHANNEL_MAX], reply_channel[HL_BUS_CHANNEL_MAX];
    if (!hl_bus_channel(o->prefix, is_cmd ? HL_CHANNEL_COMMAND : HL_CHANNEL_DESTINATION,
                        req_channel) ||
        !hl_bus_channel(o->prefix, HL_CHANNEL_REPLY, reply_channel))
        return req_usage_error(prog, "--prefix \"%s\" is too long", o->prefix);

    r->accepted = false;
    _Static_assert(HL_BUS_COMMAND_BYTES <= HL_BUS_DESTINATION_BYTES, "buffer size");
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = stamp_sign_encode(prog, o, r, buf, sizeof buf);
    if (len < 0)
        return EXIT_ERROR;

    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        fprintf(stderr, "%s: cannot start LCM with URL \"%s\"\n", prog, url);
        return EXIT_ERROR;
    }
    /* Subscribe before publishing, so that no answer can come before we listen. */
    waiter_t w = { .prog = prog, .seq = is_cmd ? r->msg.command.seq : r->msg.destination.seq,
                   .r = r, .result = WAITING };
    if (!lcm_subscribe(lcm, reply_channel, on_reply, &w)) {
        fprintf(stderr, "%s: cannot subscribe to %s\n", prog, reply_channel);
        lcm_destroy(lcm);
        return EXIT_ERROR;
    }
    if (lcm_publish(lcm, req_channel, buf, (unsigned int)len) != 0) {
        fprintf(stderr, "%s: cannot publish on %s with LCM URL \"%s\"\n", prog, req_channel,
                url);
        lcm_destroy(lcm);
        return EXIT_ERROR;
    }
    int rc = wait_for_answer(lcm, &w, o->timeout_s);
    lcm_destroy(lcm);
    if (rc == EXIT_TIMEOUT && !r->accepted)
        fprintf(stderr,
                "%s: no reply from houghlocd within %g s on channel %s: is it running, "
                "with the same --lcm-url and prefix?%s\n",
                prog, o->timeout_s, reply_channel,
                w.undecodable ? " (some REPLY messages did not decode: another version?)"
                              : "");
    return rc;
}
