/*
 * bench_cycle - times the online cycle (hl_slam_update: echo bearings, Hough
 * localization, refinement, map integration) over the SONAR scans of a recorded tour,
 * and fingerprints every result so that a speed-up can be shown to change nothing.
 *
 *   hl-bench-cycle [--log FILE] [--reps N] [--start X_MM,Y_MM,DEG] [--paper]
 *                  [--close-loops] [--square-walls] [--long-drives]
 *                  [--lost-after N] [--search-every N] [--steps]
 *
 * Reads the SONAR events of FILE (default logs/tour.lcmlog; every other channel is
 * skipped, so a stale GROUND_TRUTH type does not matter), then runs the tour N times
 * (default 5), each with a new slam (hl_slam_create, hl_slam_reset) at the start pose
 * (default the origin) with the defaults but the LOST state off (slam.lost_after and
 * slam.search_every 0: the tracker alone; --paper: the paper's cycle, unguarded, without
 * echo bearings and refinement, the other parameters as they are; --close-loops: with
 * loop closure, slam.close_loops; --square-walls: and
 * square walls along x and y, slam.square_walls; --long-drives: a drive of 2 m or more also
 * tried turned about its start, slam.long_drive_mm = 2000; --lost-after, --search-every:
 * the recovery's lost_after and search_every, 2 and 10 in the daemon). Each hl_slam_update
 * is timed with CLOCK_MONOTONIC. Prints one line per repetition and a summary:
 *
 *   cycle rep=<i> scans=<n> median_us=<n> p90_us=<n> p99_us=<n> max_us=<n> checksum=<hex>
 *   cycle summary reps=<N> median_of_medians_us=<n> p90_us=<n> p99_us=<n> checksum=<hex>
 *
 * The checksum is FNV-1a (64 bit) over, for every step: the return status, the step's
 * pose, prediction, slam status, every field of the Hough result, the vectors added, the
 * recovery's changes (lost_why, found_how) and the global search's answer when the step
 * carries one, and then the map's count, version and every map vector. Every repetition must give the
 * same checksum (the exit status is 1 otherwise). --steps prints each step's pose and
 * status as well.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <lcm/eventlog.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "timing.h"
#include "houghloc/bus.h"
#include "houghloc/params.h"
#include "houghloc/slam.h"

#define MAX_SCANS 4096

typedef struct recorded {
    hl_pose_t odometry;
    hl_scan_t scan;
} recorded_t;


/* Nearest-rank quantile of a sorted array. */
static double quantile(const double *sorted, int n, double q)
{
    return sorted[(int)(q * (n - 1) + 0.5)];
}

/* ---- FNV-1a over explicit fields (never over struct bytes: padding) ---------------- */

static void fnv_bytes(uint64_t *h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        *h ^= b[i];
        *h *= 1099511628211ull;
    }
}

static void fnv_i64(uint64_t *h, int64_t v)
{
    fnv_bytes(h, &v, sizeof v);
}

static void fnv_pose(uint64_t *h, hl_pose_t p)
{
    fnv_i64(h, p.x_mm);
    fnv_i64(h, p.y_mm);
    fnv_i64(h, p.theta);
}

static void fnv_step(uint64_t *h, hl_status_t st, const hl_slam_step_t *s, const hl_map_t *map)
{
    fnv_i64(h, st);
    fnv_pose(h, s->pose);
    fnv_pose(h, s->predicted);
    fnv_i64(h, s->status);
    fnv_pose(h, s->loc.pose);
    fnv_pose(h, s->loc.cell_pose);
    fnv_i64(h, s->loc.ix);
    fnv_i64(h, s->loc.iy);
    fnv_i64(h, s->loc.it);
    fnv_i64(h, s->loc.peak);
    fnv_i64(h, s->loc.second);
    fnv_i64(h, s->loc.votes);
    fnv_i64(h, s->loc.pairs);
    fnv_i64(h, s->added);
    fnv_i64(h, s->lost_why);
    fnv_i64(h, s->found_how);
    if (s->status == HL_SLAM_RELOCALIZED || s->status == HL_SLAM_LOST) {
        fnv_pose(h, s->search.pose);
        fnv_i64(h, s->search.score);
        fnv_pose(h, s->search.runner_up);
        fnv_i64(h, s->search.runner_up_score);
    }
    uint32_t n = hl_map_count(map);
    const hl_vector_t *v = hl_map_vectors(map);
    fnv_i64(h, n);
    fnv_i64(h, hl_map_version(map));
    for (uint32_t i = 0; i < n; i++) {
        fnv_i64(h, v[i].x_mm);
        fnv_i64(h, v[i].y_mm);
        fnv_i64(h, v[i].normal);
        fnv_i64(h, v[i].range_mm);
    }
}

/* ---- input ------------------------------------------------------------------------ */

static int read_tour(const char *path, recorded_t *out, int max)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log) {
        fprintf(stderr, "hl-bench-cycle: cannot open %s: %s\n", path, strerror(errno));
        return -1;
    }
    int n = 0;
    for (lcm_eventlog_event_t *e; (e = lcm_eventlog_read_next_event(log));
         lcm_eventlog_free_event(e)) {
        if (strcmp(e->channel, HL_CHANNEL_SONAR) != 0)
            continue;
        if (n == max) {
            fprintf(stderr, "hl-bench-cycle: more than %d scans in %s\n", max, path);
            n = -1;
            lcm_eventlog_free_event(e);
            break;
        }
        static hl_bus_scan_t bs;
        char why[HL_BUS_WHY_LEN];
        if (hl_bus_decode_scan(e->data, (size_t)e->datalen, &bs, why) != HL_OK) {
            fprintf(stderr, "hl-bench-cycle: %s: event %lld: %s\n", path,
                    (long long)e->eventnum, why);
            n = -1;
            lcm_eventlog_free_event(e);
            break;
        }
        out[n].odometry = bs.odometry;
        out[n].scan = bs.scan;
        n++;
    }
    lcm_eventlog_destroy(log);
    return n;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: hl-bench-cycle [--log FILE] [--reps N] [--start X_MM,Y_MM,DEG] "
               "[--paper] [--close-loops] [--square-walls] [--long-drives] "
               "[--lost-after N] [--search-every N] [--steps]\n");
}

static int bad_usage(const char *what, const char *value)
{
    fprintf(stderr, "hl-bench-cycle: %s '%s' (try --help)\n", what, value);
    return 2;
}

/* A whole number lo..hi, nothing more. */
static bool parse_count(const char *a, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(a, &end, 10);
    if (*a < '0' || *a > '9' || *end || errno || v < lo || v > hi)
        return false;
    *out = v;
    return true;
}

/* One field of --start: X_MM or Y_MM, a whole number within +-HL_COORD_MAX_MM; *s moves
 * past it. */
static bool parse_coord(const char **s, hl_mm_t *out)
{
    const char *p = *s + (**s == '-' || **s == '+');
    if (*p < '0' || *p > '9')
        return false;
    char *end;
    errno = 0;
    long v = strtol(*s, &end, 10);
    if (errno || v < -HL_COORD_MAX_MM || v > HL_COORD_MAX_MM)
        return false;
    *out = (hl_mm_t)v;
    *s = end;
    return true;
}

/* --start X_MM,Y_MM,DEG: two coordinates and a finite heading in degrees, nothing more. */
static bool parse_start(const char *s, hl_pose_t *out)
{
    hl_mm_t x, y;
    if (!parse_coord(&s, &x) || *s++ != ',' || !parse_coord(&s, &y) || *s++ != ',')
        return false;
    if (!(*s == '-' || *s == '+' || *s == '.' || (*s >= '0' && *s <= '9')) ||
        strpbrk(s, "xX") != NULL)
        return false;
    char *end;
    errno = 0;
    double deg = strtod(s, &end);
    if (*end || errno || !(deg >= -1e6 && deg <= 1e6))
        return false;
    *out = (hl_pose_t){ x, y, hl_bam_from_deg(deg) };
    return true;
}

int main(int argc, char **argv)
{
    const char *path = "logs/tour.lcmlog";
    int reps = 5;
    bool paper = false, steps = false, close_loops = false, square_walls = false;
    bool long_drives = false;
    int32_t lost_after = 0, search_every = 0;
    hl_pose_t start = { 0, 0, 0 };
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--log") && i + 1 < argc) {
            path = argv[++i];
        } else if (!strcmp(argv[i], "--reps") && i + 1 < argc) {
            long v;
            if (!parse_count(argv[++i], 1, 1000, &v))
                return bad_usage("--reps wants a whole number 1..1000, not", argv[i]);
            reps = (int)v;
        } else if (!strcmp(argv[i], "--lost-after") && i + 1 < argc) {
            long v;
            if (!parse_count(argv[++i], 0, 1000000, &v))
                return bad_usage("--lost-after wants a whole number 0..1000000, not", argv[i]);
            lost_after = (int32_t)v;
        } else if (!strcmp(argv[i], "--search-every") && i + 1 < argc) {
            long v;
            if (!parse_count(argv[++i], 0, 1000000, &v))
                return bad_usage("--search-every wants a whole number 0..1000000, not", argv[i]);
            search_every = (int32_t)v;
        } else if (!strcmp(argv[i], "--start") && i + 1 < argc) {
            if (!parse_start(argv[++i], &start))
                return bad_usage("--start wants X_MM,Y_MM,DEG (millimetres within +-4194304, "
                                 "degrees), not", argv[i]);
        } else if (!strcmp(argv[i], "--paper")) {
            paper = true;
        } else if (!strcmp(argv[i], "--close-loops")) {
            close_loops = true;
        } else if (!strcmp(argv[i], "--square-walls")) {
            close_loops = square_walls = true;
        } else if (!strcmp(argv[i], "--long-drives")) {
            long_drives = true;
        } else if (!strcmp(argv[i], "--steps")) {
            steps = true;
        } else {
            return bad_usage("unknown or incomplete option", argv[i]);
        }
    }

    static recorded_t tour[MAX_SCANS];
    int n = read_tour(path, tour, MAX_SCANS);
    if (n <= 0) {
        if (n == 0)
            fprintf(stderr, "hl-bench-cycle: no SONAR events in %s\n", path);
        return 1;
    }

    hl_params_t p;
    hl_params_default(&p);
    char lost_after_s[16], search_every_s[16];
    snprintf(lost_after_s, sizeof lost_after_s, "%d", (int)lost_after);
    snprintf(search_every_s, sizeof search_every_s, "%d", (int)search_every);
    const char *sets[][2] = {
        { "slam.lost_after", lost_after_s }, { "slam.search_every", search_every_s },
        { "slam.guarded", paper ? "false" : "true" },
        { "slam.echo_bearings", paper ? "false" : "true" },
        { "slam.refine", paper ? "false" : "true" },
        { "slam.close_loops", close_loops ? "true" : "false" },
        { "slam.square_walls", square_walls ? "true" : "false" },
        { "slam.long_drive_mm", long_drives ? "2000" : "0" },
    };
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++)
        if (hl_params_set(&p, sets[i][0], sets[i][1]) != HL_OK) {
            fprintf(stderr, "hl-bench-cycle: %s\n", hl_params_error(&p));
            return 1;
        }
    double *t = malloc((size_t)n * sizeof *t), *meds = malloc((size_t)reps * sizeof *meds);
    double *all = malloc((size_t)n * reps * sizeof *all);
    if (!t || !meds || !all) {
        fprintf(stderr, "hl-bench-cycle: out of memory\n");
        return 1;
    }

    uint64_t first_sum = 0;
    int status = 0;
    for (int r = 0; r < reps; r++) {
        /* A fresh slam each time: hl_slam_reset keeps the map's culling generator and
         * version running, so a reset tour would not repeat the first one exactly. */
        hl_slam_t *slam = hl_slam_create(&p);
        if (!slam) {
            fprintf(stderr, "hl-bench-cycle: cannot create the slam\n");
            return 1;
        }
        hl_slam_reset(slam, start);
        uint64_t h = 14695981039346656037ull;
        for (int i = 0; i < n; i++) {
            hl_slam_step_t step;
            memset(&step, 0, sizeof step);
            double t0 = now_us();
            hl_status_t st = hl_slam_update(slam, &tour[i].scan, tour[i].odometry, &step);
            t[i] = now_us() - t0;
            all[r * n + i] = t[i];
            fnv_step(&h, st, &step, hl_slam_map(slam));
            if (steps && r == 0)
                printf("step %d st=%d status=%d pose=%d,%d,%u votes=%u peak=%u map=%u\n", i,
                       (int)st, (int)step.status, step.pose.x_mm, step.pose.y_mm,
                       (unsigned)step.pose.theta, step.loc.votes, step.loc.peak,
                       hl_map_count(hl_slam_map(slam)));
        }
        hl_slam_destroy(slam);
        qsort(t, (size_t)n, sizeof *t, cmp_double);
        meds[r] = quantile(t, n, 0.5);
        printf("cycle rep=%d scans=%d median_us=%.0f p90_us=%.0f p99_us=%.0f max_us=%.0f "
               "checksum=%016llx\n",
               r, n, meds[r], quantile(t, n, 0.9), quantile(t, n, 0.99), t[n - 1],
               (unsigned long long)h);
        if (r == 0)
            first_sum = h;
        else if (h != first_sum)
            status = 1;
    }
    qsort(meds, (size_t)reps, sizeof *meds, cmp_double);
    qsort(all, (size_t)n * reps, sizeof *all, cmp_double);
    printf("cycle summary reps=%d median_of_medians_us=%.0f p90_us=%.0f p99_us=%.0f "
           "checksum=%016llx%s\n",
           reps, quantile(meds, reps, 0.5), quantile(all, n * reps, 0.9),
           quantile(all, n * reps, 0.99), (unsigned long long)first_sum,
           status ? " REPETITIONS DIFFER" : "");
    free(t);
    free(meds);
    free(all);
    return status;
}
