/*
 * bench_localize - times the fixed-point localizer and the floating-point reference on
 * a synthetic cluttered room (128 readings per scan), one line per workload:
 *
 *   bench <workload> median_us=<n> p90_us=<n> ref_median_us=<n> votes=<n> mem_bytes=<n>
 *         group_mm=<n>
 *
 * Workloads: w1_global_xy (heading known, global x, y over a 10 m x 10 m map, 24 mm
 * cells, 1500 vectors), w2_local_xyt (+-1 m window, +-8.8 deg at 1.1 deg, 1500 vectors),
 * w3_map15k (as w2 with 15,000 vectors, voting in 48 mm groups as a dense map is
 * configured: localize.group_mm, tools/lab/realeval/laser.conf). Scans cycle over POSES free poses so the
 * timing is not one input's luck. Single-threaded: the figures are for one core.
 *
 * A fourth line times what improved mode adds per scan, echo-bearing estimation
 * (echo.h) and refinement (refine.h, x and y, from 100 mm off, 1500 vectors):
 *
 *   bench w4_echo_refine median_us=<n> p90_us=<n> echo_median_us=<n> refine_median_us=<n>
 *         mem_bytes=<n>
 *
 * and a fifth a laser's scan: w5_laser15k (360 readings against 15,000 vectors in a
 * +-1 m window, 48 mm groups, as w3), in the first line's format. The reference runs at most 20 times
 * for w3 and 5 for w5 (it takes a quarter of a second and more per run there).
 *
 * The sixth times the global search of a kidnapped robot (reloc.h, hl_reloc_run at its
 * defaults): 128 readings against 1,500 vectors over a room the size of the lab (12 m x
 * 9 m), heading unknown; at most 40 runs (tens of milliseconds each). correct_pct is the
 * share of runs whose answer is found and within 0.5 m and 5 degrees of the truth:
 *
 *   bench w6_reloc_lab median_us=<n> p90_us=<n> correct_pct=<n> mem_bytes=<n>
 *
 * The seventh times the map itself: a laser's scans along a walk of 500 steps of 100 mm
 * (360 readings each, about 180,000 vectors) drawn into a map of 15,000 vectors with
 * round places, 2 a place, as the laser profile's map is made and as a loop closure's
 * redraw draws it again, tens of thousands of vectors a scan; at most 20 runs:
 *
 *   bench w7_map_round median_us=<n> p90_us=<n> ns_per_vector=<n> vectors=<n> mem_bytes=<n>
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/echo.h"
#include "houghloc-internal/localize.h"
#include "houghloc-internal/map.h"
#include "houghloc-internal/refine.h"
#include "houghloc-internal/reloc.h"
#include "ref_localize.h"
#include "timing.h"
#include "synthroom.h"

#define POSES 8

typedef struct workload {
    const char *name;
    uint32_t map_size;
    hl_mm_t window_mm;
    bool search_theta;
    int readings;           /* per scan: 128 (the sonar ring) or 360 (a laser) */
    hl_mm_t group_mm;       /* localize.group_mm: 0 (default) or 48 for a dense map */
    int max_ref_runs;       /* the reference is slow: cap its runs */
    bool echo_refine;       /* w4: what improved mode adds, not a search (run_echo_refine) */
    bool reloc;             /* w6: the global search, heading unknown (run_reloc) */
    bool map;               /* w7: the map's round places (run_map_round) */
} workload_t;


static double quantile(double *v, int n, double q)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[(int)(q * (n - 1) + 0.5)];
}

static int run_workload(const workload_t *w, int runs, int ref_runs)
{
    static sr_room_t room;
    sr_room_make(&room, 0, 0, 10000, 10000, 30, 42);
    hl_vector_t *map = malloc(w->map_size * sizeof *map);
    hl_scan_t *scans = malloc(POSES * sizeof *scans);
    hl_pose_t truth[POSES];
    double *t = malloc((size_t)runs * sizeof *t), *tr = malloc((size_t)ref_runs * sizeof *tr);
    if (!map || !scans || !t || !tr)
        return 1;
    uint32_t n = sr_make_map(&room, w->map_size, w->readings, 8000, 10, map);
    for (int i = 0; i < POSES; i++) {
        truth[i] = sr_free_pose(&room, 500);
        sr_sound(&room, truth[i], w->readings, 8000, 10, &scans[i]);
    }
    if (ref_runs > w->max_ref_runs)
        ref_runs = w->max_ref_runs;

    hl_loc_params_t p;
    hl_loc_params_default(&p);
    p.max_map_vectors = n;
    p.group_mm = w->group_mm;
    uint32_t global_side = (uint32_t)(10200 / p.cell_mm + 2);   /* the whole 10 m room */
    p.max_cells = w->window_mm > 0 ? hl_loc_cells_for_window(&p, w->window_mm, w->search_theta)
                                   : global_side * global_side;
    hl_localizer_t *loc = hl_loc_create(&p);
    ref_localizer_t *ref = ref_create(&p);
    if (!loc || !ref) {
        fprintf(stderr, "bench: cannot create the localizers\n");
        return 1;
    }
    hl_loc_query_t q[POSES];
    for (int i = 0; i < POSES; i++) {
        /* local searches start from a prediction off by a typical odometry error */
        hl_pose_t pred = truth[i];
        if (w->window_mm > 0) {
            pred.x_mm += 150;
            pred.y_mm -= 100;
            pred.theta = (hl_bam_t)(pred.theta + hl_bam_from_deg(3.0));
        }
        q[i] = (hl_loc_query_t){ .predicted = pred, .window_mm = w->window_mm,
                                 .search_theta = w->search_theta };
    }
    hl_loc_result_t res;
    uint32_t votes0 = 0;
    for (int i = 0; i < runs; i++) {
        double t0 = now_us();
        hl_status_t st = hl_loc_run(loc, map, n, &scans[i % POSES], &q[i % POSES], &res);
        t[i] = now_us() - t0;
        if (st != HL_OK) {
            fprintf(stderr, "bench: %s: %s\n", w->name, hl_status_str(st));
            return 1;
        }
        if (i == 0)
            votes0 = res.votes;
    }
    ref_result_t rr;
    for (int i = 0; i < ref_runs; i++) {
        double t0 = now_us();
        ref_run(ref, map, n, &scans[i % POSES], &q[i % POSES], &rr);
        tr[i] = now_us() - t0;
    }
    printf("bench %s median_us=%.0f p90_us=%.0f ref_median_us=%.0f votes=%u mem_bytes=%zu "
           "group_mm=%d\n",
           w->name, quantile(t, runs, 0.5), quantile(t, runs, 0.9),
           quantile(tr, ref_runs, 0.5), votes0, hl_loc_mem_bytes(loc), (int)w->group_mm);
    fflush(stdout);
    hl_loc_destroy(loc);
    ref_destroy(ref);
    free(map);
    free(scans);
    free(t);
    free(tr);
    return 0;
}

static int run_echo_refine(int runs)
{
    static sr_room_t room;
    static hl_scan_t scans[POSES], echoed;
    sr_room_make(&room, 0, 0, 10000, 10000, 30, 42);
    hl_vector_t *map = malloc(1500 * sizeof *map);
    double *te = malloc((size_t)runs * sizeof *te), *tf = malloc((size_t)runs * sizeof *tf);
    double *tt = malloc((size_t)runs * sizeof *tt);
    hl_pose_t truth[POSES];
    hl_refine_params_t rp;
    hl_refine_params_default(&rp);
    hl_refiner_t *ref = hl_refine_create(&rp, 1500);
    if (!map || !te || !tf || !tt || !ref) {
        fprintf(stderr, "bench: out of memory\n");
        return 1;
    }
    uint32_t n = sr_make_map(&room, 1500, 128, 8000, 10, map);
    for (int i = 0; i < POSES; i++) {
        truth[i] = sr_free_pose(&room, 500);
        sr_sound(&room, truth[i], 128, 8000, 10, &scans[i]);
    }
    hl_echo_params_t ep;
    hl_echo_params_default(&ep);
    for (int i = 0; i < runs; i++) {
        hl_pose_t start = truth[i % POSES], out;
        start.x_mm += 80;
        start.y_mm -= 60;
        double t0 = now_us();
        hl_echo_correct(&ep, &scans[i % POSES], &echoed);
        double t1 = now_us();
        /* the synthetic sensor is a thin ray: refine the scan as measured */
        hl_refine_run(ref, map, n, &scans[i % POSES], start, false, &out);
        double t2 = now_us();
        te[i] = t1 - t0;
        tf[i] = t2 - t1;
        tt[i] = t2 - t0;
    }
    printf("bench w4_echo_refine median_us=%.0f p90_us=%.0f echo_median_us=%.0f "
           "refine_median_us=%.0f mem_bytes=%zu\n",
           quantile(tt, runs, 0.5), quantile(tt, runs, 0.9), quantile(te, runs, 0.5),
           quantile(tf, runs, 0.5), hl_refine_mem_bytes(ref) + sizeof echoed);
    hl_refine_destroy(ref);
    free(map);
    free(te);
    free(tf);
    free(tt);
    return 0;
}

#define RELOC_MAX_RUNS 40

static int run_reloc(int runs)
{
    static sr_room_t room;
    static hl_scan_t scans[POSES];
    sr_room_make(&room, 0, 0, 12000, 9000, 30, 42);   /* the lab's size */
    if (runs > RELOC_MAX_RUNS)
        runs = RELOC_MAX_RUNS;
    hl_vector_t *map = malloc(1500 * sizeof *map);
    double *t = malloc((size_t)runs * sizeof *t);
    if (!map || !t) {
        fprintf(stderr, "bench: out of memory\n");
        return 1;
    }
    uint32_t n = sr_make_map(&room, 1500, 128, 8000, 10, map);
    hl_pose_t truth[POSES];
    for (int i = 0; i < POSES; i++) {   /* sr_free_pose draws the heading too */
        truth[i] = sr_free_pose(&room, 500);
        sr_sound(&room, truth[i], 128, 8000, 10, &scans[i]);
    }
    hl_loc_params_t lp;
    hl_loc_params_default(&lp);
    lp.max_map_vectors = n;
    hl_reloc_params_t rp;
    hl_reloc_params_default(&rp);
    hl_reloc_t *r = hl_reloc_create(&rp, &lp);
    if (!r) {
        fprintf(stderr, "bench: cannot create the global search\n");
        return 1;
    }
    int correct = 0;
    for (int i = 0; i < runs; i++) {
        hl_reloc_result_t res;
        const hl_pose_t *want = &truth[i % POSES];
        double t0 = now_us();
        hl_status_t st = hl_reloc_run(r, map, n, &scans[i % POSES], &res);
        t[i] = now_us() - t0;
        if (st != HL_OK && st != HL_ERR_EMPTY) {
            fprintf(stderr, "bench: w6_reloc_lab: %s\n", hl_status_str(st));
            return 1;
        }
        double dx = res.pose.x_mm - want->x_mm, dy = res.pose.y_mm - want->y_mm;
        int32_t dt = hl_bam_diff(res.pose.theta, want->theta);
        correct += st == HL_OK && res.found && dx * dx + dy * dy <= 500.0 * 500.0 &&
                   abs(dt) <= hl_bam_from_deg(5.0);
    }
    printf("bench w6_reloc_lab median_us=%.0f p90_us=%.0f correct_pct=%.0f mem_bytes=%zu\n",
           quantile(t, runs, 0.5), quantile(t, runs, 0.9), 100.0 * correct / runs,
           hl_reloc_mem_bytes(r));
    fflush(stdout);
    hl_reloc_destroy(r);
    free(map);
    free(t);
    return 0;
}

#define MAP_STEPS 500
#define MAP_MAX_RUNS 20

static int run_map_round(int runs)
{
    static sr_room_t room;
    static hl_scan_t scan;
    sr_room_make(&room, 0, 0, 20000, 15000, 60, 7);
    hl_vector_t *v = malloc((size_t)MAP_STEPS * 360 * sizeof *v);
    double *t = malloc((size_t)runs * sizeof *t);
    if (!v || !t) {
        fprintf(stderr, "bench: out of memory\n");
        return 1;
    }
    uint32_t n = 0;
    hl_pose_t at = sr_free_pose(&room, 500);
    for (int step = 0; step < MAP_STEPS; step++) {
        sr_sound(&room, at, 360, 8000, 10, &scan);
        for (uint32_t k = 0; k < scan.count; k++)
            n += hl_vector_from_reading(at, &scan.readings[k], &v[n]);
        at = sr_walk(&room, at, 100, 400);
    }
    hl_map_params_t p;
    hl_map_params_default(&p);
    p.capacity = 15000;
    p.per_place = 2;
    p.round_places = true;
    if (runs > MAP_MAX_RUNS)
        runs = MAP_MAX_RUNS;
    size_t mem = 0;
    for (int i = 0; i < runs; i++) {
        hl_map_t *map = hl_map_create_with(&p);
        if (!map) {
            fprintf(stderr, "bench: cannot create the map\n");
            return 1;
        }
        double t0 = now_us();
        for (uint32_t k = 0; k < n; k++)
            hl_map_add(map, &v[k]);
        t[i] = now_us() - t0;
        mem = hl_map_mem_bytes(map);
        hl_map_destroy(map);
    }
    double median = quantile(t, runs, 0.5);
    printf("bench w7_map_round median_us=%.0f p90_us=%.0f ns_per_vector=%.0f vectors=%u "
           "mem_bytes=%zu\n", median, quantile(t, runs, 0.9), 1000 * median / n, n, mem);
    fflush(stdout);
    free(v);
    free(t);
    return 0;
}

static const char usage[] =
    "usage: hl-bench [RUNS [WORKLOAD]]\n"
    "Times the localizer on synthetic rooms, one line per workload (RUNS 1..100000,\n"
    "default 200; WORKLOAD w1 .. w7 or its full name, default all).\n";

int main(int argc, char **argv)
{
    int runs = 200;
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return fputs(usage, stdout), 0;
    if (argc > 3) {
        fprintf(stderr, "hl-bench: unexpected argument '%s' (try --help)\n", argv[3]);
        return 2;
    }
    const char *only = argc > 2 ? argv[2] : NULL;   /* a workload's name, or its w<n> */
    if (argc > 1) {
        const char *a = argv[1];
        char *end;
        errno = 0;
        long v = strtol(a, &end, 10);
        if (*a < '0' || *a > '9' || *end || errno || v < 1 || v > 100000) {
            fprintf(stderr, "hl-bench: RUNS '%s' is not a whole number 1..100000 (try --help)\n",
                    a);
            return 2;
        }
        runs = (int)v;
    }
    const workload_t w[] = {
        { "w1_global_xy", 1500, 0, false, 128, 0, 200, false, false, false },
        { "w2_local_xyt", 1500, 1000, true, 128, 0, 200, false, false, false },
        { "w3_map15k", 15000, 1000, true, 128, 48, 20, false, false, false },
        { "w4_echo_refine", 0, 0, false, 0, 0, 0, true, false, false },
        { "w5_laser15k", 15000, 1000, true, 360, 48, 5, false, false, false },
        { "w6_reloc_lab", 1500, 0, true, 128, 0, 0, false, true, false },
        { "w7_map_round", 0, 0, false, 0, 0, 0, false, false, true },
    };
    bool any = false;
    for (size_t i = 0; i < sizeof w / sizeof w[0]; i++) {
        if (only && strcmp(only, w[i].name) != 0 &&
            (strncmp(only, w[i].name, 2) != 0 || only[2] != '\0'))
            continue;
        any = true;
        int bad = w[i].echo_refine ? run_echo_refine(runs)
                  : w[i].reloc     ? run_reloc(runs)
                  : w[i].map       ? run_map_round(runs)
                                   : run_workload(&w[i], runs, runs);
        if (bad)
            return 1;
    }
    if (!any) {
        fprintf(stderr, "hl-bench: no workload '%s' (w1 .. w7)\n", only);
        return 2;
    }
    return 0;
}
