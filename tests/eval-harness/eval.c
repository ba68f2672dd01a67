/*
 * hl-eval - scores and compares houghlocd's recorded output: the harness of the tests
 * (the goldens, the integration tests), of make demo and of the laboratory's scripts. Not
 * installed; houghloc-eval (tools/eval) is the installed scorer.
 *
 *   hl-eval start IN.lcmlog             the first scan's true pose: "X_M Y_M HEADING_DEG"
 *   hl-eval score IN.lcmlog OUT.lcmlog  error of every POSE against GROUND_TRUTH, the
 *                                       odometry-only error, and a last line
 *       demo stops=<n> rmse_mm=<x> max_mm=<y> odometry_rmse_mm=<z> wild_accepted=<k>
 *   hl-eval live LOG [OUT.lcmlog]       the same for a live run's one log (make demo):
 *                                       each scan against the last GROUND_TRUTH before it;
 *                                       with OUT, the POSE of a replay of LOG instead
 *   (score and live take --quiet, and --start X,Y,DEG: the daemon's start pose, default
 *   the origin as the daemon's; the truth is compared in the daemon's map frame, its
 *   first pose laid on that start pose: truth_frame.h)
 *   hl-eval extract LOG CHANNEL FILE    the payloads of every event on CHANNEL, each as
 *                                       a 4-byte big-endian length and the bytes, so that
 *                                       two runs compare with cmp(1)
 *   hl-eval text LOG CHANNEL FILE       the messages on CHANNEL (POSE, GROUND_TRUTH,
 *                                       SONAR, ODOMETRY) as text, one line each, every
 *                                       field (golden_text.h; the goldens' format)
 *   hl-eval status LOG                  the last STATUS in LOG as one line of key=value
 *   hl-eval truth LOG                   the last GROUND_TRUTH pose in LOG as X,Y,DEG
 *   hl-eval latency IN OUT              each POSE's time after its scan, by the
 *                                       recorders' clocks (latency.h)
 *   hl-eval split LOG N FIRST REST      FIRST gets the events before the N-th SONAR scan
 *                                       (counting from 0), REST the others
 *   hl-eval garble LOG OUT              OUT is LOG with hostile events between the real
 *                                       ones: random bytes, truncated copies, replayed
 *                                       scans and messages of the wrong type, on every
 *                                       input channel
 *
 * Every log is checked with hl_log_check before liblcm reads it (tools/eval/runlog.h,
 * shared with houghloc-eval and houghloc-map).
 */
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <lcm/eventlog.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/logcheck.h"
#include "houghloc/slam.h"
#include "houghloc/version.h"
#include "golden_text.h"
#include "latency.h"
#include "runlog.h"
#include "truth_frame.h"

static const char usage[] =
    "Usage: hl-eval start IN.lcmlog\n"
    "       hl-eval score [--quiet] [--start X,Y,DEG] IN.lcmlog OUT.lcmlog\n"
    "       hl-eval live [--quiet] [--start X,Y,DEG] LOG [OUT.lcmlog]\n"
    "       hl-eval extract LOG CHANNEL FILE\n"
    "       hl-eval text LOG CHANNEL FILE\n"
    "       hl-eval status LOG\n"
    "       hl-eval truth LOG\n"
    "       hl-eval latency IN.lcmlog OUT.lcmlog\n"
    "       hl-eval split LOG N FIRST REST\n"
    "       hl-eval garble LOG OUT\n"
    "Scores houghlocd's POSE output (OUT) against the GROUND_TRUTH of its input (IN),\n"
    "or extracts one channel's payloads for a byte-for-byte comparison (extract), or its\n"
    "messages as text, one line each with every field (text: POSE, GROUND_TRUTH, SONAR,\n"
    "ODOMETRY).\n"
    "score prints the error at every stop and ends with the line\n"
    "  demo stops=<n> rmse_mm=<x> max_mm=<y> odometry_rmse_mm=<z> wild_accepted=<k>\n"
    "where the odometry error integrates the scans' odometry from the first true pose and\n"
    "wild_accepted counts ACCEPTED poses more than 0.5 m from the truth. live does the\n"
    "same for the one log of a live run, each scan against the last GROUND_TRUTH before it.\n"
    "The truth is compared in the daemon's map frame: its first pose (the robot standing\n"
    "where the run began) is laid on the daemon's start pose, --start (metres, metres,\n"
    "degrees; default 0,0,0, the daemon's default [start]).\n"
    "latency pairs the SONAR recorded in IN with the POSE recorded in OUT by seq and\n"
    "prints each POSE's delay after its scan by the recorders' event times:\n"
    "  latency poses=<n> p50_ms=<x> p99_ms=<y> max_ms=<z> scans_unanswered=<k>\n"
    "          poses_unpaired=<j>\n"
    "       hl-eval --help | --version\n";

typedef hl_runlog_stop_t stop_t;

static int each_event(const char *path, hl_runlog_event_fn fn, void *user)
{
    return hl_runlog_each_event("hl-eval", path, fn, user);
}

static bool is_channel(const lcm_eventlog_event_t *ev, const char *name)
{
    return hl_runlog_is_channel(ev, name);
}

static double dist(hl_pose_t a, hl_pose_t b)
{
    return hypot((double)a.x_mm - b.x_mm, (double)a.y_mm - b.y_mm);
}

/* a's heading minus b's, in degrees, the short way round */
static double heading_error_deg(hl_pose_t a, hl_pose_t b)
{
    return hl_bam_diff(a.theta, b.theta) * 360.0 / HL_BAM_PER_TURN;
}

static int cmd_start(const char *in)
{
    hl_runlog_t r = { .prog = "hl-eval" };
    int rc = hl_runlog_load_input(&r, in);
    for (size_t i = 0; rc == 0 && i < r.n; i++) {
        if (r.stops[i].has_scan && r.stops[i].has_truth) {
            hl_pose_t t = r.stops[i].truth;
            printf("%.3f %.3f %.4f\n", t.x_mm / 1000.0, t.y_mm / 1000.0, hl_bam_to_sdeg(t.theta));
            break;
        }
    }
    hl_runlog_free(&r);
    return rc;
}

#define WILD_MM 500.0   /* the paper's wild error */

/* What score and live take besides their logs. */
typedef struct score_opts {
    bool quiet;
    hl_pose_t start;        /* the daemon's start pose (--start) */
} score_opts_t;

/* Moves every stop's truth into the map frame of a daemon started at @p start.
 * @return 0, or 1 after the message when a pose leaves the coordinate range. */
static int truth_to_map_frame(hl_runlog_t *r, hl_pose_t start, const char *in)
{
    if (!r->has_first_truth)
        return 0;   /* no stop has a truth: score says so */
    hl_truth_frame_t f;
    hl_truth_frame_init(&f, start);
    hl_truth_frame_anchor(&f, r->first_truth);
    for (size_t i = 0; i < r->n; i++) {
        stop_t *s = &r->stops[i];
        if (s->has_truth && !hl_truth_frame_map(&f, s->truth, &s->truth)) {
            fprintf(stderr, "hl-eval: %s: scan %d's true pose moved to the map frame lies "
                    "beyond +-%.3f m (check --start)\n", in, s->seq, HL_COORD_MAX_MM / 1000.0);
            return 1;
        }
    }
    return 0;
}

/* Prints the error at every stop of @p r and the last line; @p what names the output. */
static int score(hl_runlog_t *r, int rc, const char *in, const char *out, const score_opts_t *o)
{
    const stop_t *first = NULL;
    double se = 0, se_odo = 0, max = 0;
    size_t n = 0, missing = 0, wild = 0;
    const bool quiet = o->quiet;
    if (rc == 0)
        rc = truth_to_map_frame(r, o->start, in);
    for (size_t i = 0; rc == 0 && i < r->n; i++) {
        const stop_t *s = &r->stops[i];
        if (!s->has_scan || !s->has_truth)
            continue;
        if (!s->has_pose) {
            missing++;
            continue;
        }
        if (!first)
            first = s;
        hl_pose_t odo = hl_pose_compose(first->truth, hl_pose_between(first->odometry, s->odometry));
        double e = dist(s->pose, s->truth), e_odo = dist(odo, s->truth);
        se += e * e;
        se_odo += e_odo * e_odo;
        max = e > max ? e : max;
        wild += s->status == HL_BUS_POSE_ACCEPTED && e > WILD_MM;
        n++;
        if (!quiet)
            printf("stop %4zu  scan %5d  error %7.0f mm %+6.1f deg  odometry %7.0f mm %+6.1f deg\n",
                   n, s->seq, e, heading_error_deg(s->pose, s->truth), e_odo,
                   heading_error_deg(odo, s->truth));
    }
    if (rc == 0 && missing > 0) {
        fprintf(stderr, "hl-eval: %s: %zu scans of %s have no POSE\n", out, missing, in);
        rc = 1;
    }
    if (rc == 0 && n == 0) {
        fprintf(stderr, "hl-eval: %s: no POSE for any scan of %s\n", out, in);
        rc = 1;
    }
    if (rc == 0)
        printf("demo stops=%zu rmse_mm=%.1f max_mm=%.1f odometry_rmse_mm=%.1f wild_accepted=%zu\n",
               n, sqrt(se / (double)n), max, sqrt(se_odo / (double)n), wild);
    hl_runlog_free(r);
    return rc;
}

static int cmd_score(const char *in, const char *out, const score_opts_t *o)
{
    hl_runlog_t r = { .prog = "hl-eval" };
    int rc = hl_runlog_load_input(&r, in) || hl_runlog_load_output(&r, out);
    return score(&r, rc, in, out, o);
}

static int cmd_live(const char *log, const char *out, const score_opts_t *o)
{
    hl_runlog_t r = { .prog = "hl-eval" };
    int rc = hl_runlog_load_live(&r, log, out == NULL);
    if (rc == 0 && out)
        rc = hl_runlog_load_output(&r, out);
    return score(&r, rc, log, out ? out : log, o);
}

/* score and live: [--quiet] [--start X,Y,DEG | --start=X,Y,DEG] LOGS (2 for score, 1 or 2
 * for live), options in any order before the logs. @return the exit code. */
static int cmd_scoring(int argc, char **argv)
{
    const bool live = strcmp(argv[1], "live") == 0;
    score_opts_t o = { .quiet = false };
    const char *logs[2];
    int nlogs = 0;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--quiet") == 0) {
            o.quiet = true;
        } else if (strncmp(a, "--start", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
            const char *v = a[7] == '=' ? a + 8 : i + 1 < argc ? argv[++i] : NULL;
            char why[HL_TRUTH_FRAME_WHY_LEN];
            if (!v)
                return fprintf(stderr, "hl-eval: %s: --start needs X,Y,DEG\n", argv[1]), 2;
            if (!hl_truth_frame_parse_pose(v, &o.start, why))
                return fprintf(stderr, "hl-eval: %s: --start %s\n", argv[1], why), 2;
        } else if (a[0] == '-' && a[1] != '\0') {
            return fprintf(stderr, "hl-eval: %s: unknown option '%s' (try --help)\n", argv[1],
                           a), 2;
        } else if (nlogs < 2) {
            logs[nlogs++] = a;
        } else {
            return fprintf(stderr, "hl-eval: %s: too many arguments at '%s' (try --help)\n",
                           argv[1], a), 2;
        }
    }
    if (live ? nlogs < 1 : nlogs != 2)
        return fprintf(stderr, "hl-eval: %s: expected %s (try --help)\n", argv[1],
                       live ? "LOG [OUT.lcmlog]" : "IN.lcmlog OUT.lcmlog"), 2;
    return live ? cmd_live(logs[0], nlogs == 2 ? logs[1] : NULL, &o)
                : cmd_score(logs[0], logs[1], &o);
}

typedef struct extract {
    const char *channel;
    FILE *out;
} extract_t;

static bool on_extract(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    extract_t *x = user;
    if (!is_channel(ev, x->channel))
        return true;
    uint32_t n = (uint32_t)ev->datalen;
    uint8_t len[4] = { (uint8_t)(n >> 24), (uint8_t)(n >> 16), (uint8_t)(n >> 8), (uint8_t)n };
    if (fwrite(len, 1, 4, x->out) != 4 || fwrite(ev->data, 1, n, x->out) != n)
        return snprintf(why, HL_BUS_WHY_LEN, "write error: %s", strerror(errno)), false;
    return true;
}

static int cmd_extract(const char *log, const char *channel, const char *file)
{
    extract_t x = { channel, fopen(file, "wb") };
    if (!x.out)
        return fprintf(stderr, "hl-eval: %s: %s\n", file, strerror(errno)), 1;
    int rc = each_event(log, on_extract, &x);
    if (fclose(x.out) != 0 && rc == 0) {
        fprintf(stderr, "hl-eval: %s: %s\n", file, strerror(errno));
        rc = 1;
    }
    return rc;
}

static bool on_status(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    hl_bus_status_t *s = user;
    if (!is_channel(ev, HL_CHANNEL_STATUS))
        return true;
    if (hl_bus_decode_status(ev->data, ev->datalen, s, why) != HL_OK)
        return false;
    s->utime = s->utime ? s->utime : 1;     /* mark "seen" even for utime 0 */
    return true;
}

static int cmd_status(const char *log)
{
    hl_bus_status_t s = { 0 };
    if (each_event(log, on_status, &s) != 0)
        return 1;
    if (s.utime == 0)
        return fprintf(stderr, "hl-eval: %s: no STATUS message\n", log), 1;
    printf("status state=%d destination_seq=%lld scans=%" PRId64 " accepted=%" PRId64
           " rejected_wild=%" PRId64 " odometry_only=%" PRId64 " relocalized=%" PRId64
           " lost=%" PRId64 " bad_packets=%" PRId64 " bad_messages=%" PRId64
           " rejected_requests=%" PRId64 " map_vectors=%d map_version=%" PRId64
           " saves=%" PRId64 " compute_median_us=%d compute_p99_us=%d compute_samples=%d\n",
           s.state, (long long)s.destination_seq, s.scans, s.accepted, s.rejected_wild,
           s.odometry_only, s.relocalized, s.lost, s.bad_packets, s.bad_messages,
           s.rejected_requests, s.map_vectors, s.map_version, s.saves, s.compute_median_us,
           s.compute_p99_us, s.compute_samples);
    return 0;
}

typedef struct last_truth {
    hl_bus_pose_t pose;
    bool seen;
} last_truth_t;

static bool on_truth(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    last_truth_t *t = user;
    if (!is_channel(ev, HL_CHANNEL_GROUND_TRUTH))
        return true;
    t->seen = true;
    return hl_bus_decode_pose(ev->data, ev->datalen, &t->pose, why) == HL_OK;
}

/* The last GROUND_TRUTH pose of a log as X,Y,DEG (houghloc-sim's --start syntax). */
static int cmd_truth(const char *log)
{
    last_truth_t t = { .seen = false };
    if (each_event(log, on_truth, &t) != 0)
        return 1;
    if (!t.seen)
        return fprintf(stderr, "hl-eval: %s: no GROUND_TRUTH message\n", log), 1;
    printf("%.3f,%.3f,%.2f\n", t.pose.pose.x_mm / 1000.0, t.pose.pose.y_mm / 1000.0,
           hl_bam_to_sdeg(t.pose.pose.theta));
    return 0;
}

/* ---- writing logs: split and garble ---------------------------------------------------- */

typedef struct writer {
    lcm_eventlog_t *out[2];
    int which;              /* split: 0 until the N-th scan, then 1 */
    long scans, split_at;
    uint32_t rng;
    uint8_t *prev_sonar;    /* garble: the previous scan, to replay */
    int32_t prev_sonar_len;
    int64_t n;
} writer_t;

static bool put(writer_t *w, lcm_eventlog_t *log, const lcm_eventlog_event_t *ev,
                const char *channel, const void *data, int32_t len, char *why)
{
    lcm_eventlog_event_t e = *ev;
    e.eventnum = w->n++;
    e.channel = (char *)channel;
    e.channellen = (int32_t)strlen(channel);
    e.data = (void *)data;
    e.datalen = len;
    if (lcm_eventlog_write_event(log, &e) != 0)
        return snprintf(why, HL_BUS_WHY_LEN, "write error: %s", strerror(errno)), false;
    return true;
}

static bool on_split(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    writer_t *w = user;
    if (is_channel(ev, HL_CHANNEL_SONAR) && w->scans++ == w->split_at)
        w->which = 1;
    char channel[HL_LOG_CHANNEL_MAX + 1];
    snprintf(channel, sizeof channel, "%.*s", (int)ev->channellen, ev->channel);
    return put(w, w->out[w->which], ev, channel, ev->data, ev->datalen, why);
}

static uint32_t next_rand(writer_t *w)
{
    w->rng = w->rng * 1664525u + 1013904223u;
    return w->rng >> 8;
}

static bool on_garble(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    writer_t *w = user;
    static const char *const inputs[] = { HL_CHANNEL_SONAR, HL_CHANNEL_ODOMETRY,
                                          HL_CHANNEL_DESTINATION, HL_CHANNEL_COMMAND };
    char channel[HL_LOG_CHANNEL_MAX + 1];
    snprintf(channel, sizeof channel, "%.*s", (int)ev->channellen, ev->channel);
    if (!put(w, w->out[0], ev, channel, ev->data, ev->datalen, why))
        return false;
    uint8_t junk[700];
    uint32_t r = next_rand(w);
    const char *target = inputs[r % 4];
    bool ok = true;
    switch ((r >> 4) % 4) {
    case 0: /* random bytes */
        for (size_t i = 0; i < sizeof junk; i++)
            junk[i] = (uint8_t)next_rand(w);
        ok = put(w, w->out[0], ev, target, junk, (int32_t)(next_rand(w) % sizeof junk), why);
        break;
    case 1: /* this event truncated, on its own channel */
        ok = put(w, w->out[0], ev, channel, ev->data, ev->datalen / 2, why);
        break;
    case 2: /* this event's bytes on another input channel: the wrong type */
        ok = put(w, w->out[0], ev, target, ev->data, ev->datalen, why);
        break;
    default: /* the previous scan again: out of order */
        if (w->prev_sonar)
            ok = put(w, w->out[0], ev, HL_CHANNEL_SONAR, w->prev_sonar, w->prev_sonar_len, why);
        break;
    }
    if (is_channel(ev, HL_CHANNEL_SONAR)) {
        free(w->prev_sonar);
        w->prev_sonar = malloc((size_t)ev->datalen);
        if (!w->prev_sonar)
            return snprintf(why, HL_BUS_WHY_LEN, "out of memory"), false;
        memcpy(w->prev_sonar, ev->data, (size_t)ev->datalen);
        w->prev_sonar_len = ev->datalen;
    }
    return ok;
}

static int cmd_write(const char *in, hl_runlog_event_fn fn, writer_t *w, const char *out0,
                     const char *out1)
{
    const char *paths[2] = { out0, out1 };
    int rc = 0;
    for (int i = 0; i < 2 && paths[i]; i++) {
        w->out[i] = lcm_eventlog_create(paths[i], "w");
        if (!w->out[i]) {
            fprintf(stderr, "hl-eval: %s: cannot create: %s\n", paths[i], strerror(errno));
            rc = 1;
        }
    }
    if (rc == 0)
        rc = each_event(in, fn, w);
    for (int i = 0; i < 2; i++)
        if (w->out[i])
            lcm_eventlog_destroy(w->out[i]);
    free(w->prev_sonar);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return fputs(usage, stdout), 0;
    if (argc >= 2 && strcmp(argv[1], "--version") == 0)
        return printf("hl-eval %s\n", HL_VERSION), 0;
    if (argc == 3 && strcmp(argv[1], "start") == 0)
        return cmd_start(argv[2]);
    if (argc >= 2 && (strcmp(argv[1], "score") == 0 || strcmp(argv[1], "live") == 0))
        return cmd_scoring(argc, argv);
    if (argc == 5 && strcmp(argv[1], "extract") == 0)
        return cmd_extract(argv[2], argv[3], argv[4]);
    if (argc == 5 && strcmp(argv[1], "text") == 0)
        return hl_eval_text("hl-eval", argv[2], argv[3], argv[4]);
    if (argc == 3 && strcmp(argv[1], "status") == 0)
        return cmd_status(argv[2]);
    if (argc == 3 && strcmp(argv[1], "truth") == 0)
        return cmd_truth(argv[2]);
    if (argc == 4 && strcmp(argv[1], "latency") == 0)
        return hl_eval_latency("hl-eval", argv[2], argv[3]);
    if (argc == 6 && strcmp(argv[1], "split") == 0) {
        const char *a = argv[3];
        char *end;
        errno = 0;
        long n = strtol(a, &end, 10);
        if (*a < '0' || *a > '9' || *end || errno)
            return fprintf(stderr, "hl-eval: split: '%s' is not a scan count 0..%ld\n", a,
                           LONG_MAX), 2;
        writer_t w = { .split_at = n };
        return cmd_write(argv[2], on_split, &w, argv[4], argv[5]);
    }
    if (argc == 4 && strcmp(argv[1], "garble") == 0) {
        writer_t w = { .rng = 12345 };
        return cmd_write(argv[2], on_garble, &w, argv[3], NULL);
    }
    fprintf(stderr, "hl-eval: expected start, score, live, extract, text, status, truth, latency, split "
            "or garble with their arguments (try --help)\n");
    return 2;
}
