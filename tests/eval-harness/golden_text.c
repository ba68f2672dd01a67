/*
 * golden_text.c - hl-eval text: one channel of a log as text, one line per message, for
 * the goldens (tests/golden/check.sh; the format in tests/golden/README.md).
 *
 * Each message is decoded with its generated LCM decoder, so a line holds exactly the
 * wire's fields, in the order of the type's definition (lcmtypes/houghloc_*_t.lcm), as
 * NAME=VALUE separated by one space: integers in decimal; floats in fixed notation with
 * 9 decimals, more only for a value that 9 would not give back exactly (below 1/32), so
 * that two streams whose text is equal are equal byte for byte; a pose's status by its
 * constant's name. A message that does not decode, or leaves bytes over, is an error:
 * the text must stand for every byte.
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "golden_text.h"
#include "houghloc/bus.h"
#include "houghloc_odometry_t.h"
#include "houghloc_pose_t.h"
#include "houghloc_scan_t.h"
#include "runlog.h"

typedef bool (*line_fn)(FILE *out, const lcm_eventlog_event_t *ev, char *why);

typedef struct text {
    const char *channel;
    line_fn line;
    FILE *out;
} text_t;

static void put_float(FILE *out, const char *name, float v)
{
    char s[128];
    for (int decimals = 9;; decimals++) {
        snprintf(s, sizeof s, "%.*f", decimals, (double)v);
        float back = strtof(s, NULL);
        if (memcmp(&back, &v, sizeof v) == 0 || decimals == 60)
            break;      /* (60: a NaN, which no decimal gives back) */
    }
    fprintf(out, " %s=%s", name, s);
}

static const char *pose_status(int8_t status, char *buf, size_t len)
{
    static const char *const names[] = { "ACCEPTED", "REJECTED_WILD", "ODOMETRY_ONLY",
                                         "RELOCALIZED", "LOST" };
    if (status >= 0 && (size_t)status < sizeof names / sizeof names[0])
        return names[status];
    snprintf(buf, len, "%d", status);
    return buf;
}

/* A decoder's result: the whole message read, or a reason in @p why. */
static bool decoded(int n, const lcm_eventlog_event_t *ev, char *why)
{
    if (n < 0)
        return snprintf(why, HL_BUS_WHY_LEN, "does not decode"), false;
    if (n != ev->datalen)
        return snprintf(why, HL_BUS_WHY_LEN, "%d bytes after the message", ev->datalen - n),
               false;
    return true;
}

static bool pose_line(FILE *out, const lcm_eventlog_event_t *ev, char *why)
{
    houghloc_pose_t p;
    if (!decoded(houghloc_pose_t_decode(ev->data, 0, ev->datalen, &p), ev, why))
        return false;
    char status[8];
    fprintf(out, "utime=%" PRId64 " scan_seq=%" PRId32 " x_mm=%" PRId32 " y_mm=%" PRId32
            " heading_bam=%d status=%s", p.utime, p.scan_seq, p.x_mm, p.y_mm, p.heading_bam,
            pose_status(p.status, status, sizeof status));
    put_float(out, "confidence", p.confidence);
    fprintf(out, " peak=%" PRId32 " second_peak=%" PRId32 " votes=%" PRId32, p.peak,
            p.second_peak, p.votes);
    put_float(out, "search_score", p.search_score);
    fprintf(out, " runner_up_x_mm=%" PRId32 " runner_up_y_mm=%" PRId32
            " runner_up_heading_bam=%d", p.runner_up_x_mm, p.runner_up_y_mm,
            p.runner_up_heading_bam);
    put_float(out, "runner_up_score", p.runner_up_score);
    fputc('\n', out);
    houghloc_pose_t_decode_cleanup(&p);
    return true;
}

static void put_odometry(FILE *out, const char *prefix, const houghloc_odometry_t *o)
{
    fprintf(out, "%sutime=%" PRId64 " %sx_mm=%" PRId32 " %sy_mm=%" PRId32 " %sheading_bam=%d"
            " %svelocity_mm_s=%d %sstopped=%d", prefix, o->utime, prefix, o->x_mm, prefix,
            o->y_mm, prefix, o->heading_bam, prefix, o->velocity_mm_s, prefix, o->stopped);
}

static bool odometry_line(FILE *out, const lcm_eventlog_event_t *ev, char *why)
{
    houghloc_odometry_t o;
    if (!decoded(houghloc_odometry_t_decode(ev->data, 0, ev->datalen, &o), ev, why))
        return false;
    put_odometry(out, "", &o);
    fputc('\n', out);
    houghloc_odometry_t_decode_cleanup(&o);
    return true;
}

/* readings=T:B:R:V,... : each reading's transducer, bearing_bam, range_mm and valid. */
static bool scan_line(FILE *out, const lcm_eventlog_event_t *ev, char *why)
{
    houghloc_scan_t s;
    int n = houghloc_scan_t_decode(ev->data, 0, ev->datalen, &s);
    bool ok = decoded(n, ev, why);
    if (ok && s.nreadings < 0) {
        snprintf(why, HL_BUS_WHY_LEN, "nreadings %d", s.nreadings);
        ok = false;
    }
    if (ok) {
        fprintf(out, "utime=%" PRId64 " seq=%" PRId32 " ", s.utime, s.seq);
        put_odometry(out, "odometry.", &s.odometry);
        fprintf(out, " nreadings=%d readings=", s.nreadings);
        for (int i = 0; i < s.nreadings; i++)
            fprintf(out, "%s%d:%d:%" PRId32 ":%d", i ? "," : "", s.transducer[i],
                    s.bearing_bam[i], s.range_mm[i], s.valid[i]);
        fputc('\n', out);
    }
    if (n >= 0)
        houghloc_scan_t_decode_cleanup(&s);
    return ok;
}

static bool on_event(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    text_t *t = user;
    if (!hl_runlog_is_channel(ev, t->channel))
        return true;
    if (!t->line(t->out, ev, why))
        return false;
    if (ferror(t->out))
        return snprintf(why, HL_BUS_WHY_LEN, "write error: %s", strerror(errno)), false;
    return true;
}

int hl_eval_text(const char *prog, const char *log, const char *channel, const char *file)
{
    static const struct { const char *channel; line_fn line; } types[] = {
        { HL_CHANNEL_POSE, pose_line },
        { HL_CHANNEL_GROUND_TRUTH, pose_line },
        { HL_CHANNEL_SONAR, scan_line },
        { HL_CHANNEL_ODOMETRY, odometry_line },
    };
    text_t t = { channel, NULL, NULL };
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcmp(channel, types[i].channel) == 0)
            t.line = types[i].line;
    if (!t.line)
        return fprintf(stderr, "%s: text: no text form for channel '%s' (POSE, GROUND_TRUTH, "
                       "SONAR or ODOMETRY)\n", prog, channel), 2;
    t.out = fopen(file, "w");
    if (!t.out)
        return fprintf(stderr, "%s: %s: %s\n", prog, file, strerror(errno)), 1;
    int rc = hl_runlog_each_event(prog, log, on_event, &t);
    if (fclose(t.out) != 0 && rc == 0) {
        fprintf(stderr, "%s: %s: %s\n", prog, file, strerror(errno));
        rc = 1;
    }
    return rc;
}
