/* carmen_import.c - the two passes of houghloc-import-carmen (see carmen_import.h). */
#include "carmen_import.h"

#include <errno.h>
#include <lcm/eventlog.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "carmen_tum.h"
#include "houghloc/bus.h"
#include "houghloc/slam.h"

#define WHY_LEN 2048
#define PI 3.14159265358979323846
#define HIST_BINS 10000             /* 1 cm bins up to 100 m, for the no-return value */

typedef struct importer {
    const carmen_options_t *o;
    carmen_tum_t truth;
    /* learnt by pass 1 */
    double fov_deg;
    const char *fov_from;
    carmen_beams_t beams;           /* where the beams point, from the above */
    long fov_line;                  /* line of the fov PARAM, 0 when none */
    double res_deg;                 /* laser_front_laser_resolution (degrees), 0 when none */
    double max_m;                   /* largest range, and how many beams have it */
    long max_count;
    long hist[HIST_BINS + 1];       /* beams per centimetre of range; the last: beyond */
    carmen_ranges_t ranges;
    /* counted by each pass (pass 2's are reported) */
    long lines, flaser, params, skipped, written, unselected, bumped, odometry, truths;
    int beams_min, beams_max;
    carmen_counts_t counts;
    /* state along a pass */
    int pass;
    long line;                      /* the line being handled */
    int64_t last_time_us, last_utime;
    long last_time_line;
    carmen_pose_t last_used, prev;
    int64_t prev_utime;
    int32_t seq;
    lcm_eventlog_t *log;
    int64_t eventnum;
    char why[WHY_LEN];
    double ranges_buf[CARMEN_MAX_BEAMS];
    hl_bus_scan_t scan, check;      /* ~12 KiB each: on the heap with the importer */
    uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
} importer_t;

/* Sets im->why to "IN:LINE: ..." and returns -1. */
__attribute__((format(printf, 2, 3))) static int fail(importer_t *im, const char *fmt, ...)
{
    int n = snprintf(im->why, WHY_LEN, "%s:%ld: ", im->o->in, im->line);
    n = n < 0 ? 0 : n >= WHY_LEN ? WHY_LEN - 1 : n;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(im->why + n, WHY_LEN - (size_t)n, fmt, ap);
    va_end(ap);
    return -1;
}

/* Sets im->why to the message alone (no line) and returns -1. */
__attribute__((format(printf, 2, 3))) static int fail_file(importer_t *im, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(im->why, WHY_LEN, fmt, ap);
    va_end(ap);
    return -1;
}

static int32_t to_mm(double m)
{
    return (int32_t)llround(m * 1000.0);
}

static bool in_coord_range(double x_m, double y_m)
{
    return fabs(x_m * 1000.0) <= HL_COORD_MAX_MM && fabs(y_m * 1000.0) <= HL_COORD_MAX_MM;
}

static hl_pose_t to_pose(double x, double y, double theta)
{
    return (hl_pose_t){ to_mm(x), to_mm(y), hl_bam_from_rad(theta) };
}

static int put(importer_t *im, const char *channel, int64_t utime, const void *data, int len)
{
    lcm_eventlog_event_t ev = { .eventnum = im->eventnum++, .timestamp = utime,
                                .channellen = (int32_t)strlen(channel), .datalen = len,
                                .channel = (char *)channel, .data = (void *)data };
    if (lcm_eventlog_write_event(im->log, &ev) != 0) {
        return fail_file(im, "%s: write error: %s", im->o->out, strerror(errno));
    }
    return 0;
}

static int write_odometry(importer_t *im, const carmen_flaser_t *f, int64_t utime)
{
    hl_bus_odometry_t m = { .utime = utime, .pose = to_pose(f->pose.x, f->pose.y, f->pose.theta) };
    if (im->odometry > 0) {     /* speed since the previous FLASER line, for the record */
        double v = hypot(f->pose.x - im->prev.x, f->pose.y - im->prev.y) * 1e9 /
                   (double)(utime - im->prev_utime);
        m.velocity_mm_s = (int16_t)(v < 32767.0 ? lround(v) : 32767);
    }
    m.stopped = m.velocity_mm_s == 0;
    uint8_t buf[HL_BUS_ODOMETRY_BYTES];
    int len = hl_bus_encode_odometry(&m, buf, sizeof buf);
    hl_bus_odometry_t back;
    if (len < 0 || hl_bus_decode_odometry(buf, (size_t)len, &back, NULL) != HL_OK)
        return fail(im, "ODOMETRY at utime %lld does not encode", (long long)utime);
    im->odometry++;
    return put(im, HL_CHANNEL_ODOMETRY, utime, buf, len);
}

static int write_scan(importer_t *im, const carmen_flaser_t *f, int64_t utime,
                      const carmen_truth_t *t)
{
    hl_bus_scan_t *m = &im->scan;
    m->utime = utime;
    m->seq = im->seq;
    m->odometry = to_pose(f->pose.x, f->pose.y, f->pose.theta);
    hl_status_t st = carmen_make_scan(f, &im->beams, im->o->input, &im->ranges, &m->scan,
                                      &im->counts);
    char why[HL_BUS_WHY_LEN] = "";
    if (st == HL_OK)
        st = hl_scan_check(&m->scan);
    int len = st == HL_OK ? hl_bus_encode_scan(m, im->buf, sizeof im->buf) : -1;
    if (len < 0 || hl_bus_decode_scan(im->buf, (size_t)len, &im->check, why) != HL_OK)
        return fail(im, "scan seq %d does not make a valid SONAR message: %s %s", im->seq,
                    hl_status_str(st), why);
    if (put(im, HL_CHANNEL_SONAR, utime, im->buf, len) != 0)
        return -1;
    if (t) {
        hl_bus_pose_t g = { .utime = utime, .scan_seq = im->seq,
                            .pose = to_pose(t->x, t->y, t->yaw), .status = HL_BUS_POSE_ACCEPTED };
        uint8_t gbuf[HL_BUS_POSE_BYTES];
        int glen = hl_bus_encode_pose(&g, gbuf, sizeof gbuf);
        hl_bus_pose_t back;
        if (glen < 0 || hl_bus_decode_pose(gbuf, (size_t)glen, &back, why) != HL_OK)
            return fail(im, "GROUND_TRUTH of scan seq %d does not encode: %s", im->seq, why);
        if (put(im, HL_CHANNEL_GROUND_TRUTH, utime, gbuf, glen) != 0)
            return -1;
        im->truths++;
    }
    return 0;
}

/* --select: is this scan written? */
static bool selected(importer_t *im, const carmen_flaser_t *f)
{
    if (im->o->select == CARMEN_SELECT_EVERY || im->written == 0)
        return true;
    double d = hypot(f->pose.x - im->last_used.x, f->pose.y - im->last_used.y);
    double turn = fabs(remainder(f->pose.theta - im->last_used.theta, 2.0 * PI)) * 180.0 / PI;
    return d >= im->o->move_m || turn >= im->o->turn_deg;
}

static int on_flaser(importer_t *im, const carmen_flaser_t *f)
{
    if (im->flaser > 0 && f->time_us < im->last_time_us)
        return fail(im, "timestamp %lld.%06lld s goes back from line %ld's %lld.%06lld s",
                    (long long)(f->time_us / 1000000), (long long)(f->time_us % 1000000),
                    im->last_time_line, (long long)(im->last_time_us / 1000000),
                    (long long)(im->last_time_us % 1000000));
    /* equal timestamps: one microsecond later, so that utime strictly increases */
    int64_t utime = im->flaser > 0 && f->time_us <= im->last_utime ? im->last_utime + 1 : f->time_us;
    im->bumped += utime != f->time_us;
    im->last_time_us = f->time_us;
    im->last_time_line = im->line;
    im->last_utime = utime;
    im->flaser++;
    if (!in_coord_range(f->pose.x, f->pose.y))
        return fail(im, "pose (%.3f, %.3f) m is outside +-%.3f m", f->pose.x, f->pose.y,
                    HL_COORD_MAX_MM / 1000.0);
    if (im->o->input == CARMEN_INPUT_LASER && f->nbeams > HL_SCAN_MAX_READINGS)
        return fail(im, "%d beams: a scan holds at most %d readings (try --input sonar)",
                    f->nbeams, HL_SCAN_MAX_READINGS);
    if (im->beams_min == 0 || f->nbeams < im->beams_min)
        im->beams_min = f->nbeams;
    if (f->nbeams > im->beams_max)
        im->beams_max = f->nbeams;
    if (im->pass == 1)
        for (int i = 0; i < f->nbeams; i++) {
            double bin = floor(f->ranges[i] * 100.0);
            im->hist[bin < HIST_BINS ? (int)bin : HIST_BINS]++;
            if (f->ranges[i] > im->max_m || im->max_count == 0) {
                im->max_m = f->ranges[i];
                im->max_count = 0;
            }
            im->max_count += f->ranges[i] == im->max_m;
        }
    if (im->pass == 2 && write_odometry(im, f, utime) != 0)
        return -1;
    im->prev = f->pose;
    im->prev_utime = utime;
    if (!selected(im, f)) {
        im->unselected++;
        return 0;
    }
    const carmen_truth_t *t = NULL;
    if (im->o->truth) {
        t = carmen_tum_find(&im->truth, f->time_us);
        if (!t)
            return fail(im, "the scan at %lld.%06lld s has no pose in %s (its times must equal "
                        "the CARMEN timestamps to the microsecond)",
                        (long long)(f->time_us / 1000000), (long long)(f->time_us % 1000000),
                        im->o->truth);
        if (!in_coord_range(t->x, t->y))
            return fail(im, "the truth pose (%.3f, %.3f) m is outside +-%.3f m", t->x, t->y,
                        HL_COORD_MAX_MM / 1000.0);
    }
    if (im->written == INT32_MAX)
        return fail(im, "more than %d scans", INT32_MAX);
    if (im->pass == 2 && write_scan(im, f, utime, t) != 0)
        return -1;
    im->last_used = f->pose;
    im->written++;
    im->seq++;
    return 0;
}

static int on_param(importer_t *im, const carmen_param_t *p)
{
    im->params++;
    bool fov = strcmp(p->name, "laser_front_laser_fov") == 0;
    bool res = strcmp(p->name, "laser_front_laser_resolution") == 0;
    if (im->pass != 1 || (!fov && !res))
        return 0;
    double v;
    if (!carmen_parse_number(p->value, &v) || !(v > 0))
        return fail(im, "PARAM %s '%.40s' is not a positive number", p->name, p->value);
    if (res) {
        im->res_deg = v;
        return 0;
    }
    /* CARMEN writes the field of view in degrees or, as csail's log does, radians */
    double deg = v <= 2.0 * PI + 1e-3 ? v * 180.0 / PI : v;
    if (deg > 360.0)
        return fail(im, "PARAM laser_front_laser_fov %.40s is more than a full turn", p->value);
    if (im->fov_line && deg != im->fov_deg)
        return fail(im, "PARAM laser_front_laser_fov %.40s differs from line %ld's", p->value,
                    im->fov_line);
    im->fov_deg = deg;
    im->fov_line = im->line;
    return 0;
}

static int run_pass(importer_t *im, int pass)
{
    char reason[CARMEN_WHY_LEN];
    carmen_reader_t *r = carmen_open(im->o->in, reason);
    if (!r)
        return fail_file(im, "%s: %s", im->o->in, reason);
    im->pass = pass;
    im->lines = im->flaser = im->params = im->skipped = im->written = im->unselected = 0;
    im->bumped = im->odometry = im->truths = 0;
    im->beams_min = im->beams_max = 0;
    im->counts = (carmen_counts_t){ 0 };
    im->seq = 0;
    carmen_line_t l = { .flaser.ranges = im->ranges_buf };
    char *text;
    int rc = 0, status = 0;
    while (status == 0 && (rc = carmen_next_line(r, &text, &im->line, reason)) == 1) {
        im->lines++;
        if (carmen_parse_line(text, &l, reason) != 0)
            status = fail(im, "%s", reason);
        else if (l.kind == CARMEN_FLASER)
            status = on_flaser(im, &l.flaser);
        else if (l.kind == CARMEN_PARAM)
            status = on_param(im, &l.param);
        else
            im->skipped++;
    }
    if (status == 0 && rc < 0)
        status = fail_file(im, "%s: %s", im->o->in, reason);
    carmen_close(r);
    return status;
}

/* Beams within 1 m below the maximum range (to the centimetre), not counting it. */
static long near_max(const importer_t *im)
{
    double top = floor(im->max_m * 100.0);
    if (top >= HIST_BINS)
        return 0;   /* beyond the histogram, where 49.9 m decides anyway */
    long n = 0;
    for (int b = top >= 100 ? (int)top - 100 : 0; b <= (int)top; b++)
        n += im->hist[b];
    return n - im->max_count;
}

/* Between the passes: the field of view and the no-return value. */
static int decide(importer_t *im)
{
    if (im->flaser == 0)
        return fail_file(im, "%s: no FLASER line", im->o->in);
    im->fov_from = im->o->fov_deg > 0 ? "--fov-deg" : im->fov_line ? "PARAM" : "default";
    im->fov_deg = im->o->fov_deg > 0 ? im->o->fov_deg : im->fov_line ? im->fov_deg : 180.0;
    /* A resolution PARAM that does not fit the field of view (n - 1 or n steps, the last
     * beam dropped) means another field of view: refuse rather than guess which. */
    double res = im->res_deg, n = im->beams_max;
    bool spread = im->o->fov_deg > 0;
    if (res > 0 && !spread &&
        (im->beams_min != im->beams_max ||
         (fabs((n - 1) * res - im->fov_deg) > res / 2 && fabs(n * res - im->fov_deg) > res / 2)))
        return fail_file(im, "%s: PARAM laser_front_laser_resolution %g degrees does not fit "
                         "%d to %d beams over %g degrees: give the field of view with --fov-deg",
                         im->o->in, res, im->beams_min, im->beams_max, im->fov_deg);
    im->beams = (carmen_beams_t){ .fov_deg = im->fov_deg, .res_deg = spread ? 0 : res,
                                  .spread = spread };
    if (im->o->input == CARMEN_INPUT_SONAR && carmen_sonar_readings(im->fov_deg) < 1)
        return fail_file(im, "%s: a field of view of %.3f degrees is narrower than one sonar "
                         "reading (%.4f degrees)", im->o->in, im->fov_deg, CARMEN_SONAR_STEP_DEG);
    if (im->o->no_return_m > 0) {
        im->ranges = (carmen_ranges_t){ .no_return_m = im->o->no_return_m };
    } else {
        /* A no-return value is written for every beam that saw nothing: a spike at the
         * top of the range histogram, above few real returns. A log's longest real
         * return is rare and has neighbours. So the maximum is the no-return value when
         * it repeats and outnumbers all other ranges within 1 m below it. */
        bool sentinel = im->max_m < CARMEN_NO_RETURN_M && im->max_m > 0 && im->max_count >= 2 &&
                        im->max_count > near_max(im);
        im->ranges = (carmen_ranges_t){ .no_return_m = CARMEN_NO_RETURN_M,
                                        .has_sentinel = sentinel, .sentinel_m = im->max_m };
    }
    return 0;
}

static void print_summary(const importer_t *im, FILE *s)
{
    const carmen_options_t *o = im->o;
    fprintf(s, PROG ": read %s: lines=%ld flaser=%ld param=%ld skipped=%ld\n", o->in,
            im->lines, im->flaser, im->params, im->skipped);
    fprintf(s, PROG ": wrote %s: scans=%ld odometry=%ld ground_truth=%ld "
            "skipped_by_selection=%ld input=%s select=%s",
            o->out, im->written, im->odometry, im->truths, im->unselected,
            o->input == CARMEN_INPUT_LASER ? "laser" : "sonar",
            o->select == CARMEN_SELECT_EVERY ? "every" : "moved");
    if (o->select == CARMEN_SELECT_MOVED)
        fprintf(s, " move_m=%g turn_deg=%g", o->move_m, o->turn_deg);
    fputc('\n', s);
    fprintf(s, PROG ": laser: beams_per_scan=%d", im->beams_min);
    if (im->beams_max != im->beams_min)
        fprintf(s, "..%d", im->beams_max);
    bool one_count = im->beams_min == im->beams_max;
    const char *step_from;
    double step = carmen_beam_step_deg(&im->beams, one_count ? im->beams_max : 0, &step_from);
    fprintf(s, " fov_deg=%.4f (%s) step_deg=", im->fov_deg, im->fov_from);
    if (one_count)
        fprintf(s, "%.4f", step);
    else
        fputs("by_beams", s);
    fprintf(s, " (%s) max_range_m=%.3f (%ld beams, %s)\n", step_from,
            im->max_m, im->max_count,
            im->ranges.has_sentinel ? "the no-return value"
            : im->max_m >= im->ranges.no_return_m ? "no return" : "a return");
    fprintf(s, PROG ": beams of the scans written: valid=%ld no_return=%ld "
            "beyond_32.767m=%ld (not representable: invalid readings)\n",
            im->counts.valid, im->counts.no_return, im->counts.beyond);
    fprintf(s, PROG ": readings: total=%ld valid=%ld per_scan=%ld timestamps_bumped=%ld\n",
            im->counts.readings, im->counts.readings_valid,
            im->written ? im->counts.readings / im->written : 0, im->bumped);
}

/* Refuses OUT naming the same file as IN: it would be truncated before pass 2. */
static bool same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

int carmen_import(const carmen_options_t *o, FILE *summary)
{
    importer_t *im = calloc(1, sizeof *im);
    if (!im)
        return fprintf(stderr, PROG ": out of memory\n"), CARMEN_EXIT_ERROR;
    im->o = o;
    int status = 0;
    if (same_file(o->in, o->out))
        status = fail_file(im, "%s: is the input too", o->out);
    char twhy[CARMEN_TUM_WHY_LEN];
    if (status == 0 && o->truth && carmen_tum_load(o->truth, &im->truth, twhy) != 0)
        status = fail_file(im, "%s", twhy);
    if (status == 0)
        status = run_pass(im, 1);
    if (status == 0)
        status = decide(im);
    if (status == 0 && (im->log = lcm_eventlog_create(o->out, "w")) == NULL)
        status = fail_file(im, "%s: cannot create: %s", o->out, strerror(errno));
    if (status == 0)
        status = run_pass(im, 2);
    if (im->log) {
        lcm_eventlog_destroy(im->log);
        if (status != 0)
            unlink(o->out);
    }
    if (status == 0)
        print_summary(im, summary);
    else
        fprintf(stderr, "%s\n", im->why);
    carmen_tum_free(&im->truth);
    free(im);
    return status == 0 ? CARMEN_EXIT_OK : CARMEN_EXIT_ERROR;
}
