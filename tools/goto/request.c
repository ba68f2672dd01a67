/*
 * request.c - the part of houghloc-goto and houghloc-ctl that talks to houghlocd: the
 * common options, one signed request on LCM, and the wait for its REPLY (request.h).
 */
#include "request.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
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
#include "houghloc/keyfile.h"

#define COORD_MAX_M (HL_COORD_MAX_MM / 1000.0)

/* wait_for_robot: how soon a destination is sent again after NO_ROBOT (the link comes
 * up within a second or two of the daemon's start), and after no answer at all (the
 * daemon may not be listening yet). */
#define NO_ROBOT_AGAIN_US 250000
#define SILENCE_AGAIN_US 1000000
/* stop_on_signal: the longest wait for the STOP's answer. */
#define STOP_WAIT_S 2.0

/* Not exit codes: why wait_for_answer returned early. */
enum { REQ_AGAIN = -3, REQ_INTERRUPTED = -4 };

/* The signal that interrupts a wait (stop_on_signal): noted here, acted on by the loop. */
static volatile sig_atomic_t interrupted;

static void note_signal(int sig)
{
    interrupted = sig;
}

static int64_t clock_us(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

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
    static const char *const names[] = { "--lcm-url", "--prefix", "--key", "--timeout",
                                         "--deadline" };
    const char *a = argv[*i];
    const char *eq = strchr(a, '=');
    size_t n = eq ? (size_t)(eq - a) : strlen(a);
    int which = -1;
    for (int k = 0; k < 5; k++)
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
    } else if (which == 3) {
        double t;
        if (!req_parse_number(v, &t) || !(t >= 0.1 && t <= 3600.0))
            return req_usage_error(prog, "--timeout \"%s\": give seconds from 0.1 to 3600", v);
        o->timeout_s = t;
    } else {
        double t;
        if (!req_parse_number(v, &t) || !(t >= 0.1 && t <= 86400.0))
            return req_usage_error(prog, "--deadline \"%s\": give seconds from 0.1 to 86400",
                                   v);
        o->deadline_s = t;
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
    bool answered;              /* a REPLY to seq came (other than a waited-out NO_ROBOT) */
    bool no_robot;              /* a NO_ROBOT was waited out */
    int64_t again_us;           /* wait_for_robot: monotonic time to send again */
    int undecodable;    /* REPLY messages that did not decode */
    const hl_auth_key_t *key;   /* --key: only REPLY messages with its MAC count; NULL none */
    const char *prefix;         /* the channel prefix the MACs cover */
    int forged;                 /* REPLY messages to seq whose MAC was missing or wrong */
    bool unverified_auth;       /* one of them was REJECTED_AUTH: what the daemon answers
                                   a client whose key is not its own, which that client
                                   cannot verify */
    int result;         /* WAITING, or the exit code */
    int64_t progress_us;        /* monotonic time of the last sign of progress (or of
                                   sending): the silence is measured from it */
    bool under_way;             /* a STATUS showed this destination under way */
    bool seen_status;           /* a STATUS showed this request worked on (on_our_trip) */
    hl_bus_status_t last;       /* the newest such STATUS */
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
    /* With a key, the daemon signs its answers: one without the MAC is not the daemon's
     * (a forged ARRIVED must not end the wait with success), so wait on for the real one. */
    if (w->key && !hl_auth_check_reply(w->key, w->prefix, &r)) {
        /* the one answer a client with another key cannot verify: said once the wait is
         * over (exchange), not here */
        if (r.result == HL_BUS_REPLY_REJECTED_AUTH) {
            w->unverified_auth = true;
            return;
        }
        if (w->forged++ == 0)
            fprintf(stderr, "%s: ignoring a REPLY (%s) to seq %lld without a valid MAC "
                    "(forged, or from a daemon without this key); waiting for the daemon's "
                    "own\n", w->prog, hl_bus_reply_name(r.result), (long long)w->seq);
        return;
    }
    if (r.result == HL_BUS_REPLY_ACCEPTED && w->r->accepted)
        return; /* a repeated answer */
    /* a daemon with no link configured will never have one: that NO_ROBOT is final */
    if (r.result == HL_BUS_REPLY_NO_ROBOT && w->r->wait_for_robot &&
        strncmp(r.message, HL_BUS_NO_ROBOT_UNCONFIGURED, sizeof r.message) != 0) {
        if (!w->no_robot)
            fprintf(stderr, "%s: waiting for the robot link (NO_ROBOT%s%.100s)\n", w->prog,
                    r.message[0] ? ": " : "", r.message);
        w->no_robot = true;
        w->again_us = clock_us(CLOCK_MONOTONIC) + NO_ROBOT_AGAIN_US;
        return;
    }
    w->answered = true;
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
    w->progress_us = clock_us(CLOCK_MONOTONIC);     /* ACCEPTED: the trip has begun */
}

/* The states of a destination under way: driving, sounding, localizing a scan, or lost
 * and sounding to find itself (IDLE, FAULT, STOPPING end it or hold it up). */
static bool working(int8_t state)
{
    return state == HL_BUS_STATE_MOVING || state == HL_BUS_STATE_SOUNDING ||
           state == HL_BUS_STATE_LOCALIZING || state == HL_BUS_STATE_LOST;
}

/* Whether STATUS @p s shows this request being worked on: its destination under way, or,
 * once ACCEPTED and before it starts, the sounding it waits behind (a destination that
 * comes during a sounding begins when the sounding ends; STATUS names no destination
 * until then). */
static bool on_our_trip(const waiter_t *w, const hl_bus_status_t *s)
{
    if (s->destination_seq == w->seq)
        return working(s->state);
    return s->destination_seq < 0 && w->r->accepted && !w->under_way &&
           (s->state == HL_BUS_STATE_SOUNDING || s->state == HL_BUS_STATE_LOCALIZING);
}

/* STATUS, once a second and on every change of state: a sign of progress when it shows
 * this request being worked on and something moved on since the last one: the state,
 * the scans made, the estimate, or the time of the newest input (the robot's packets
 * flow). A daemon that stops, a link that goes quiet, or a destination the daemon has
 * left give no sign, and the wait runs out after --timeout. */
static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    waiter_t *w = user;
    hl_bus_status_t s;
    if (hl_bus_decode_status(rbuf->data, rbuf->data_size, &s, NULL) != HL_OK ||
        !on_our_trip(w, &s))
        return;
    const hl_bus_status_t *p = &w->last;
    bool changed = !w->seen_status || s.utime != p->utime || s.state != p->state ||
                   s.scans != p->scans || s.pose.x_mm != p->pose.x_mm ||
                   s.pose.y_mm != p->pose.y_mm || s.pose.theta != p->pose.theta;
    w->seen_status = true;
    w->under_way = w->under_way || s.destination_seq == w->seq;
    w->last = s;
    if (changed)
        w->progress_us = clock_us(CLOCK_MONOTONIC);
}

/* Why a wait ended without an answer. */
typedef enum { ENDED_SILENCE, ENDED_DEADLINE } ended_t;

/* Handles REPLY (and STATUS) until an answer ends the wait, o->timeout_s passes since the
 * last sign of progress, or the deadline since @p sent_us. */
static int wait_for_answer(lcm_t *lcm, waiter_t *w, const req_options_t *o, int64_t sent_us,
                           ended_t *ended)
{
    const int64_t silence_us = (int64_t)llround(o->timeout_s * 1e6);
    const int64_t deadline = o->deadline_s > 0 ? sent_us + (int64_t)llround(o->deadline_s * 1e6)
                                               : INT64_MAX;
    const int fd = lcm_get_fileno(lcm);
    while (w->result == WAITING) {
        if (interrupted)
            return REQ_INTERRUPTED;
        const int64_t now = clock_us(CLOCK_MONOTONIC);
        int64_t left = w->progress_us + silence_us - now;
        *ended = ENDED_SILENCE;
        if (deadline - now < left) {
            left = deadline - now;
            *ended = ENDED_DEADLINE;
        }
        if (left <= 0)
            return w->no_robot && !w->answered ? EXIT_NO_ROBOT : EXIT_TIMEOUT;
        if (w->r->wait_for_robot && !w->answered) {
            if (now >= w->again_us)
                return REQ_AGAIN;
            if (w->again_us - now < left)
                left = w->again_us - now;
        }
        if (left > 1000000)
            left = 1000000;     /* progress moves the end: look again at least each second */
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

/* A timeout after the daemon took the request: which limit ran out, and what STATUS said
 * last, so that the operator can tell a slow trip from a stuck one. */
static void report_stalled(const waiter_t *w, const req_options_t *o, ended_t ended)
{
    static const char *const states[] = { "STARTING", "SOUNDING", "LOCALIZING", "MOVING",
                                          "IDLE", "FAULT", "STOPPING", "LOST" };
    char last[96] = "no STATUS showed it under way";
    if (w->seen_status)
        snprintf(last, sizeof last, "last STATUS: %s at (%.3f, %.3f) m after %lld scans",
                 states[w->last.state], w->last.pose.x_mm / 1000.0, w->last.pose.y_mm / 1000.0,
                 (long long)w->last.scans);
    if (ended == ENDED_DEADLINE)
        fprintf(stderr, "%s: accepted, but no ARRIVED within the --deadline of %g s (%s); "
                "the robot may still be on its way\n", w->prog, o->deadline_s, last);
    else if (w->r->follow_progress)
        fprintf(stderr, "%s: accepted, but no sign of progress for %g s (%s): is the robot "
                "stuck, or the daemon's STATUS not reaching this host? (raise --timeout)\n",
                w->prog, o->timeout_s, last);
    else
        fprintf(stderr, "%s: accepted, but no final answer within %g s (raise --timeout)\n",
                w->prog, o->timeout_s);
}

/* ---- sending ------------------------------------------------------------------------- */

/* Stamps the request with the clock and signs it with @p key (NULL: unsigned) for the
 * channels of @p prefix, then encodes it into buf (cap bytes). @return the length, or -1
 * after the message (exit 1). */
static int stamp_sign_encode(const char *prog, const hl_auth_key_t *key, const char *prefix,
                             req_request_t *r, uint8_t *buf, size_t cap)
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
    if (key && !(is_cmd ? hl_auth_sign_command(key, prefix, &r->msg.command)
                        : hl_auth_sign_destination(key, prefix, &r->msg.destination))) {
        fprintf(stderr, "%s: the %s does not encode\n", prog, noun);
        return -1;
    }
    int len = is_cmd ? hl_bus_encode_command(&r->msg.command, buf, cap)
                     : hl_bus_encode_destination(&r->msg.destination, buf, cap);
    if (len < 0)
        fprintf(stderr, "%s: the %s does not encode\n", prog, noun);
    return len;
}

/* The key of --key (when given) into @p key. @return false after the message. */
static bool load_key(const char *prog, const req_options_t *o, hl_auth_key_t *key)
{
    if (!hl_auth_init()) {
        fprintf(stderr, "%s: libsodium does not initialize\n", prog);
        return false;
    }
    char why[HL_KEYFILE_WHY_LEN];
    if (hl_keyfile_load(o->key_file, key, why) != HL_OK) {
        fprintf(stderr, "%s: %s\n", prog, why);
        return false;
    }
    return true;
}

/* Stamps, signs, encodes and publishes @p r on @p channel; the waiter then waits for
 * its seq. @return false after a one-line message. */
static bool send_request(lcm_t *lcm, const char *prog, req_request_t *r, const char *channel,
                         waiter_t *w)
{
    _Static_assert(HL_BUS_COMMAND_BYTES <= HL_BUS_DESTINATION_BYTES, "buffer size");
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = stamp_sign_encode(prog, w->key, w->prefix, r, buf, sizeof buf);
    if (len < 0)
        return false;
    w->seq = r->kind == REQ_COMMAND ? r->msg.command.seq : r->msg.destination.seq;
    w->again_us = clock_us(CLOCK_MONOTONIC) + SILENCE_AGAIN_US;
    if (lcm_publish(lcm, channel, buf, (unsigned int)len) != 0) {
        fprintf(stderr, "%s: cannot publish on %s\n", prog, channel);
        return false;
    }
    return true;
}

/* Interrupted by @p sig while a request of ours may be under way: STOP, so that the robot
 * does not drive on without its operator, and a short wait for its answer. */
static int stop_after_signal(lcm_t *lcm, const char *prog, const req_options_t *o,
                             const char *command_channel, waiter_t *w, int sig)
{
    fprintf(stderr, "%s: %s: sending STOP\n", prog, sig == SIGTERM ? "SIGTERM" : "SIGINT");
    interrupted = 0;    /* a second signal interrupts the wait for STOP's answer */
    req_request_t stop = { .kind = REQ_COMMAND, .accepted_ends = true,
                           .accepted_text = "stopped" };
    stop.msg.command = (hl_bus_command_t){ .kind = HL_BUS_COMMAND_STOP };
    req_options_t quick = *o;
    quick.timeout_s = STOP_WAIT_S;
    quick.deadline_s = 0;
    *w = (waiter_t){ .prog = prog, .r = &stop, .result = WAITING, .key = w->key,
                     .prefix = w->prefix, .progress_us = clock_us(CLOCK_MONOTONIC) };
    ended_t ended;
    if (send_request(lcm, prog, &stop, command_channel, w) &&
        wait_for_answer(lcm, w, &quick, w->progress_us, &ended) == EXIT_TIMEOUT)
        fprintf(stderr, "%s: no answer to STOP within %g s: is the daemon running?\n", prog,
                STOP_WAIT_S);
    return EXIT_SIGNAL + sig;
}

static void catch_signals(void)
{
    struct sigaction sa = { .sa_handler = note_signal };
    sigemptyset(&sa.sa_mask);
    /* no SA_RESTART: poll returns EINTR and the wait sees the signal at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

/* req_run with LCM started: subscribes, sends, waits, and says why a wait failed. */
static int exchange(lcm_t *lcm, const char *prog, const req_options_t *o, req_request_t *r,
                    waiter_t *w)
{
    const bool is_cmd = r->kind == REQ_COMMAND;
    char req_channel[HL_BUS_CHANNEL_MAX], reply_channel[HL_BUS_CHANNEL_MAX];
    char command_channel[HL_BUS_CHANNEL_MAX], status_channel[HL_BUS_CHANNEL_MAX];
    /* req_run checked that the prefix fits every name */
    hl_bus_channel(o->prefix, is_cmd ? HL_CHANNEL_COMMAND : HL_CHANNEL_DESTINATION,
                   req_channel);
    hl_bus_channel(o->prefix, HL_CHANNEL_REPLY, reply_channel);
    hl_bus_channel(o->prefix, HL_CHANNEL_COMMAND, command_channel);
    hl_bus_channel(o->prefix, HL_CHANNEL_STATUS, status_channel);
    /* Subscribe before publishing, so that no answer can come before we listen. */
    if (!lcm_subscribe(lcm, reply_channel, on_reply, w)) {
        fprintf(stderr, "%s: cannot subscribe to %s\n", prog, reply_channel);
        return EXIT_ERROR;
    }
    if (r->follow_progress && !lcm_subscribe(lcm, status_channel, on_status, w)) {
        fprintf(stderr, "%s: cannot subscribe to STATUS\n", prog);
        return EXIT_ERROR;
    }
    if (r->stop_on_signal)
        catch_signals();
    const int64_t sent_us = clock_us(CLOCK_MONOTONIC);
    w->progress_us = sent_us;
    ended_t ended = ENDED_SILENCE;
    int rc;
    do {    /* wait_for_robot: again with a new seq until the robot link answers */
        if (!send_request(lcm, prog, r, req_channel, w))
            return EXIT_ERROR;
        rc = wait_for_answer(lcm, w, o, sent_us, &ended);
    } while (rc == REQ_AGAIN);
    if (rc == REQ_INTERRUPTED)
        return stop_after_signal(lcm, prog, o, command_channel, w, (int)interrupted);
    /* A refusal cannot be a false success: once the wait is over with nothing better, an
     * unverified REJECTED_AUTH is the likeliest truth (a key that is not the daemon's). It
     * never ends the wait early, where a forged one could hide the daemon's real ACCEPTED
     * of a trip the robot then makes. */
    if (rc == EXIT_TIMEOUT && w->unverified_auth && !w->answered) {
        fprintf(stderr, "%s: REJECTED_AUTH, unverified (that answer's MAC does not match "
                "--key either): is --key the daemon's key (auth.key_file), and --prefix its "
                "prefix?\n", prog);
        return EXIT_REJECTED;
    }
    char ignored[160] = "";
    if (w->forged)
        snprintf(ignored, sizeof ignored, " (%d REPLY message(s) without a valid MAC were "
                 "ignored: forged, or from a daemon without this key)", w->forged);
    if (rc == EXIT_NO_ROBOT && !w->answered)
        fprintf(stderr, "%s: NO_ROBOT: the daemon's robot link did not come up within %g s\n",
                prog, o->timeout_s);
    else if (rc == EXIT_TIMEOUT && (r->accepted || w->seen_status))
        report_stalled(w, o, ended);
    else if (rc == EXIT_TIMEOUT && ended == ENDED_DEADLINE)
        fprintf(stderr, "%s: no reply from houghlocd within the --deadline of %g s%s\n", prog,
                o->deadline_s, ignored);
    else if (rc == EXIT_TIMEOUT)
        fprintf(stderr,
                "%s: no reply from houghlocd within %g s on channel %s: is it running, "
                "with the same --lcm-url and prefix?%s%s\n",
                prog, o->timeout_s, reply_channel,
                w->undecodable ? " (some REPLY messages did not decode: another version?)"
                               : "", ignored);
    return rc;
}

int req_run(const char *prog, const req_options_t *o, req_request_t *r)
{
    const char *url = o->url;
    if (!url) {
        const char *env = getenv("LCM_DEFAULT_URL");
        url = env && *env ? env : REQ_DEFAULT_URL;
    }
    char channel[HL_BUS_CHANNEL_MAX];
    static const char *const names[] = { HL_CHANNEL_DESTINATION, HL_CHANNEL_COMMAND,
                                         HL_CHANNEL_REPLY, HL_CHANNEL_STATUS };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!hl_bus_channel(o->prefix, names[i], channel))
            return req_usage_error(prog, "--prefix \"%s\" is too long", o->prefix);

    r->accepted = false;
    hl_auth_key_t key;
    if (o->key_file && !load_key(prog, o, &key))
        return EXIT_ERROR;
    waiter_t w = { .prog = prog, .r = r, .result = WAITING, .key = o->key_file ? &key : NULL,
                   .prefix = o->prefix };
    int rc = EXIT_ERROR;
    lcm_t *lcm = lcm_create(url);
    if (lcm) {
        rc = exchange(lcm, prog, o, r, &w);
        lcm_destroy(lcm);
    } else {
        fprintf(stderr, "%s: cannot start LCM with URL \"%s\"\n", prog, url);
    }
    if (o->key_file)
        sodium_memzero(&key, sizeof key);
    return rc;
}
