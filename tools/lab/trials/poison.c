/*
 * poison.c - hl-poison: the sensor-stream poisons of the Poison trial
 * (tools/lab/trials/poison.sh), written into a copy of a recorded log.
 *
 *   hl-poison make IN OUT     copies the LCM log IN to OUT with, among its real scans:
 *                             after the 10th SONAR, a well-formed scan with seq 2^31 - 6
 *                             and utime 2^62 (a forged or corrupt value far ahead);
 *                             after the 20th, an ODOMETRY with utime 2^63 - 1;
 *                             from the 40th on, the publisher restarted: every scan's seq
 *                             counted again from 0, and every SONAR and ODOMETRY time
 *                             stepped 2 h back (a clock stepped back).
 *                             Prints "real_scans=N poisons=2 restart_at=40".
 *   hl-poison count LOG CH    prints how many events LOG holds on channel CH.
 *
 * A daemon that cannot be poisoned answers every real scan but the few a restart costs
 * (stream.h: HL_STREAM_CONFIRM - 1); the trial counts the POSE it published.
 */
#include <inttypes.h>
#include <lcm/eventlog.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/version.h"

#define PROG "hl-poison"
#define FAR_SEQ_AFTER 10
#define FAR_ODOMETRY_AFTER 20
#define RESTART_AT 40
#define CLOCK_STEP_US (2LL * 3600 * 1000000)

static const char usage[] =
    "Usage: hl-poison make IN OUT | hl-poison count LOG CHANNEL\n"
    "  make   copy the LCM log IN to OUT with a far-ahead scan, a far-ahead odometry and,\n"
    "         from the 40th scan on, a restarted publisher (seq from 0, clock 2 h back)\n"
    "  count  the number of events on CHANNEL in LOG\n"
    "Exit status: 0 done, 1 a log that cannot be read or written, 2 bad arguments.\n";

static bool is_channel(const lcm_eventlog_event_t *ev, const char *name)
{
    return ev->channellen == (int32_t)strlen(name) && memcmp(ev->channel, name, strlen(name)) == 0;
}

static bool write_event(lcm_eventlog_t *out, const char *channel, int64_t timestamp,
                        void *data, int len)
{
    lcm_eventlog_event_t ev = { .timestamp = timestamp, .channellen = (int32_t)strlen(channel),
                                .datalen = len, .channel = (char *)channel, .data = data };
    return len > 0 && lcm_eventlog_write_event(out, &ev) == 0;
}

/* The scan of @p ev, decoded into storage of its own (12 KiB: off the stack); NULL after a
 * one-line message when it does not decode. */
static hl_bus_scan_t *read_scan(const lcm_eventlog_event_t *ev)
{
    static hl_bus_scan_t s;
    char why[HL_BUS_WHY_LEN];
    if (hl_bus_decode_scan(ev->data, (size_t)ev->datalen, &s, why) == HL_OK)
        return &s;
    fprintf(stderr, PROG ": a SONAR in the log does not decode: %s\n", why);
    return NULL;
}

static bool read_odometry(const lcm_eventlog_event_t *ev, hl_bus_odometry_t *o)
{
    char why[HL_BUS_WHY_LEN];
    if (hl_bus_decode_odometry(ev->data, (size_t)ev->datalen, o, why) == HL_OK)
        return true;
    fprintf(stderr, PROG ": an ODOMETRY in the log does not decode: %s\n", why);
    return false;
}

typedef struct copy {
    lcm_eventlog_t *out;
    int scans;                  /* real scans copied */
    int32_t restart_seq;        /* the seq of the scan the publisher restarted at */
    hl_bus_odometry_t last_odometry;
    bool have_odometry;
    uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
} copy_t;

/* One event of the input, moved to the restarted publisher's numbers once it restarted. */
static bool copy_event(copy_t *c, const lcm_eventlog_event_t *ev)
{
    bool sonar = is_channel(ev, "SONAR"), odometry = is_channel(ev, "ODOMETRY");
    char channel[256];
    snprintf(channel, sizeof channel, "%.*s", (int)ev->channellen, ev->channel);
    bool restarted = c->scans >= RESTART_AT || (sonar && c->scans + 1 == RESTART_AT);
    if (!restarted || !(sonar || odometry))
        return write_event(c->out, channel, ev->timestamp, ev->data, ev->datalen);
    int len;
    if (sonar) {
        hl_bus_scan_t *s = read_scan(ev);
        if (!s)
            return false;
        if (c->scans + 1 == RESTART_AT)
            c->restart_seq = s->seq;
        s->seq -= c->restart_seq;
        s->utime -= CLOCK_STEP_US;
        len = hl_bus_encode_scan(s, c->buf, sizeof c->buf);
    } else {
        hl_bus_odometry_t o;
        if (!read_odometry(ev, &o))
            return false;
        o.utime -= CLOCK_STEP_US;
        len = hl_bus_encode_odometry(&o, c->buf, sizeof c->buf);
    }
    return write_event(c->out, channel, ev->timestamp, c->buf, len);
}

/* The poisons, each after the real scan it follows. */
static bool poison_after(copy_t *c, const lcm_eventlog_event_t *scan)
{
    if (c->scans == FAR_SEQ_AFTER) {
        hl_bus_scan_t *s = read_scan(scan);
        if (!s)
            return false;
        s->seq = INT32_MAX - 6;
        s->utime = INT64_C(1) << 62;
        int len = hl_bus_encode_scan(s, c->buf, sizeof c->buf);
        if (!write_event(c->out, "SONAR", scan->timestamp + 1, c->buf, len))
            return false;
    }
    if (c->scans == FAR_ODOMETRY_AFTER && c->have_odometry) {
        hl_bus_odometry_t o = c->last_odometry;
        o.utime = INT64_MAX;
        int len = hl_bus_encode_odometry(&o, c->buf, sizeof c->buf);
        if (!write_event(c->out, "ODOMETRY", scan->timestamp + 1, c->buf, len))
            return false;
    }
    return true;
}

static int make(const char *in_path, const char *out_path)
{
    lcm_eventlog_t *in = lcm_eventlog_create(in_path, "r");
    if (!in)
        return fprintf(stderr, PROG ": cannot read %s\n", in_path), 1;
    copy_t *c = calloc(1, sizeof *c);
    c->out = lcm_eventlog_create(out_path, "w");
    if (!c->out) {
        lcm_eventlog_destroy(in);
        free(c);
        return fprintf(stderr, PROG ": cannot write %s\n", out_path), 1;
    }
    bool ok = true;
    lcm_eventlog_event_t *ev;
    while (ok && (ev = lcm_eventlog_read_next_event(in)) != NULL) {
        if (is_channel(ev, "ODOMETRY"))
            ok = c->have_odometry = read_odometry(ev, &c->last_odometry);
        if (!ok)
            break;
        ok = copy_event(c, ev);
        if (ok && is_channel(ev, "SONAR")) {
            c->scans++;
            ok = poison_after(c, ev);
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(in);
    lcm_eventlog_destroy(c->out);
    if (ok && c->scans <= RESTART_AT)
        ok = fprintf(stderr, PROG ": %s has %d scans; the poisons need more than %d\n", in_path,
                     c->scans, RESTART_AT) < 0;
    if (ok)
        printf("real_scans=%d poisons=2 restart_at=%d\n", c->scans, RESTART_AT);
    free(c);
    return ok ? 0 : 1;
}

static int count(const char *path, const char *channel)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log)
        return fprintf(stderr, PROG ": cannot read %s\n", path), 1;
    long n = 0;
    lcm_eventlog_event_t *ev;
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
        n += is_channel(ev, channel);
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    printf("%ld\n", n);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return fputs(usage, stdout), 0;
    if (argc == 2 && strcmp(argv[1], "--version") == 0)
        return printf(PROG " %s\n", HL_VERSION), 0;
    if (argc == 4 && strcmp(argv[1], "make") == 0)
        return make(argv[2], argv[3]);
    if (argc == 4 && strcmp(argv[1], "count") == 0)
        return count(argv[2], argv[3]);
    fprintf(stderr, PROG ": expected 'make IN OUT' or 'count LOG CHANNEL'; try " PROG
            " --help\n");
    return 2;
}
