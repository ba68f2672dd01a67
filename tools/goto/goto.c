/*
 * goto.c - houghloc-goto: sends the robot to a destination through houghlocd.
 *
 * One DESTINATION message (signed with --key), then the REPLY messages that carry its
 * seq: ACCEPTED, then ARRIVED or a refusal. Messages go through the bus codecs
 * (houghloc/bus.h) and lcm_publish, never the generated code. The command line is in
 * goto_args.c.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>
#include <sodium.h>

#include "goto_args.h"
#include "houghloc/auth.h"
#include "houghloc/bus.h"
#include "houghloc/fixed.h"
#include "keyfile.h"

/* ---- waiting for the answers --------------------------------------------------------- */

typedef struct waiter {
    int64_t seq;
    bool no_wait;
    bool accepted;
    int undecodable;    /* REPLY messages that did not decode */
    int result;         /* WAITING, or the exit code */
} waiter_t;

/* What to print when the daemon's message is empty. */
static const char *const default_message[] = {
    [HL_BUS_REPLY_ACCEPTED] = "the robot is on its way",
    [HL_BUS_REPLY_ARRIVED] = "the robot reached the destination",
    [HL_BUS_REPLY_REJECTED_FENCE] = "the destination is outside the geofence",
    [HL_BUS_REPLY_REJECTED_AUTH] = "missing or wrong MAC (see --key)",
    [HL_BUS_REPLY_REJECTED_REPLAY] = "seq not above the last accepted one",
    [HL_BUS_REPLY_NO_ROBOT] = "",
    [HL_BUS_REPLY_FAILED] = "the daemon could not do it",
    [HL_BUS_REPLY_REJECTED_INVALID] = "a field is out of range",
};

static int exit_code(int8_t result, bool no_wait)
{
    switch (result) {
    case HL_BUS_REPLY_ACCEPTED: return no_wait ? EXIT_ARRIVED : WAITING;
    case HL_BUS_REPLY_ARRIVED: return EXIT_ARRIVED;
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
    if (r.result == HL_BUS_REPLY_ACCEPTED && w->accepted)
        return; /* a repeated answer */
    /* The text came over the network: print it as one line of plain characters. */
    for (char *c = r.message; *c; c++)
        if (iscntrl((unsigned char)*c))
            *c = '?';
    const char *text = r.message;
    if (!text[0] && r.result >= 0 && r.result <= HL_BUS_REPLY_REJECTED_INVALID)
        text = default_message[r.result];
    bool good = r.result == HL_BUS_REPLY_ACCEPTED || r.result == HL_BUS_REPLY_ARRIVED;
    FILE *out = good ? stdout : stderr;
    if (r.result == HL_BUS_REPLY_NO_ROBOT)
        fprintf(out, "%s: NO_ROBOT: no robot is connected to the daemon%s%s\n", PROG,
                r.message[0] ? ": " : "", r.message);
    else
        fprintf(out, "%s: %s: %s\n", PROG, hl_bus_reply_name(r.result), text);
    fflush(out);
    w->accepted = w->accepted || r.result == HL_BUS_REPLY_ACCEPTED;
    w->result = exit_code(r.result, w->no_wait);
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
            fprintf(stderr, "%s: poll: %s\n", PROG, strerror(errno));
            return EXIT_ERROR;
        }
        if (n > 0 && lcm_handle(lcm) != 0) {
            fprintf(stderr, "%s: LCM stopped receiving\n", PROG);
            return EXIT_ERROR;
        }
    }
    return w->result;
}

/* ---- main ------------------------------------------------------------------------------ */

/* Fills the destination and signs it when a key file is given. @return an exit code. */
static int make_destination(const goto_options_t *o, hl_bus_destination_t *d)
{
    memset(d, 0, sizeof *d);
    d->utime = clock_us(CLOCK_REALTIME);
    d->seq = d->utime; /* strictly increasing across calls, as the daemon requires */
    d->x_mm = (int32_t)lround(o->pos[0] * 1000.0);
    d->y_mm = (int32_t)lround(o->pos[1] * 1000.0);
    d->has_heading = o->npos == 3;
    d->heading = d->has_heading ? hl_bam_from_deg(fmod(o->pos[2], 360.0)) : 0;
    if (!o->key_file)
        return EXIT_ARRIVED;
    if (!hl_auth_init()) {
        fprintf(stderr, "%s: libsodium does not initialize\n", PROG);
        return EXIT_ERROR;
    }
    hl_auth_key_t key;
    char why[HL_KEYFILE_WHY_LEN];
    if (hl_keyfile_load(o->key_file, &key, why) != HL_OK) {
        fprintf(stderr, "%s: %s\n", PROG, why);
        return EXIT_ERROR;
    }
    bool ok = hl_auth_sign_destination(&key, d);
    sodium_memzero(&key, sizeof key);
    if (!ok) {
        fprintf(stderr, "%s: the destination does not encode\n", PROG);
        return EXIT_ERROR;
    }
    return EXIT_ARRIVED;
}

int main(int argc, char **argv)
{
    goto_options_t o = { .prefix = "", .timeout_s = 10.0 };
    int rc = goto_parse_args(argc, argv, &o);
    if (rc != WAITING)
        return rc;
    if (!o.url) {
        const char *env = getenv("LCM_DEFAULT_URL");
        o.url = env && *env ? env : DEFAULT_URL;
    }
    char dest_channel[HL_BUS_CHANNEL_MAX], reply_channel[HL_BUS_CHANNEL_MAX];
    if (!hl_bus_channel(o.prefix, HL_CHANNEL_DESTINATION, dest_channel) ||
        !hl_bus_channel(o.prefix, HL_CHANNEL_REPLY, reply_channel))
        return goto_usage_error("--prefix \"%s\" is too long", o.prefix);

    hl_bus_destination_t d;
    if ((rc = make_destination(&o, &d)) != EXIT_ARRIVED)
        return rc;
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = hl_bus_encode_destination(&d, buf, sizeof buf);
    if (len < 0) {
        fprintf(stderr, "%s: the destination does not encode\n", PROG);
        return EXIT_ERROR;
    }

    lcm_t *lcm = lcm_create(o.url);
    if (!lcm) {
        fprintf(stderr, "%s: cannot start LCM with URL \"%s\"\n", PROG, o.url);
        return EXIT_ERROR;
    }
    /* Subscribe before publishing, so that no answer can come before we listen. */
    waiter_t w = { .seq = d.seq, .no_wait = o.no_wait, .result = WAITING };
    if (!lcm_subscribe(lcm, reply_channel, on_reply, &w)) {
        fprintf(stderr, "%s: cannot subscribe to %s\n", PROG, reply_channel);
        lcm_destroy(lcm);
        return EXIT_ERROR;
    }
    if (lcm_publish(lcm, dest_channel, buf, (unsigned int)len) != 0) {
        fprintf(stderr, "%s: cannot publish on %s with LCM URL \"%s\"\n", PROG, dest_channel,
                o.url);
        lcm_destroy(lcm);
        return EXIT_ERROR;
    }
    rc = wait_for_answer(lcm, &w, o.timeout_s);
    lcm_destroy(lcm);
    if (rc == EXIT_TIMEOUT && !w.accepted)
        fprintf(stderr,
                "%s: no reply from houghlocd within %g s on channel %s: is it running, "
                "with the same --lcm-url and prefix?%s\n",
                PROG, o.timeout_s, reply_channel,
                w.undecodable ? " (some REPLY messages did not decode: another version?)"
                              : "");
    else if (rc == EXIT_TIMEOUT)
        fprintf(stderr,
                "%s: accepted, but no ARRIVED within %g s: the robot may still be on its "
                "way (raise --timeout, or use --no-wait)\n",
                PROG, o.timeout_s);
    return rc;
}
