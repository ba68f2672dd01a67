/* Tests for the one pass through hl_slam_update (src/core/slam.c, slam_lost.c): each scan
 * is checked once, echo-corrected once and localized by tracking once, no local or global
 * search runs twice with the same inputs within a scan, and the watch (search_every)
 * searches only the scans it should. The stages are counted where they run: this program
 * is linked with -Wl,--wrap for each of them (tests/core/core_tests.mk), so a stage called
 * from anywhere in the core counts. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slam_walk.h"
#include "valid_scan.h"

/* ---- the stages, counted ---------------------------------------------------------------- */

#define MAX_SEEN 64

typedef struct counts {
    int checks;             /* hl_scan_check */
    int echoes;             /* hl_echo_correct, checked or not */
    int local;              /* hl_loc_run outside a global search: tracking's local searches */
    int global;             /* hl_reloc_run_scans */
    int repeated_local;     /* a local search with the same inputs as one before it */
    int repeated_global;    /* ... a global search */
    int in_global;          /* depth inside a global search */
    uint64_t seen_local[MAX_SEEN], seen_global[MAX_SEEN];
    int n_local, n_global;
} counts_t;

static counts_t n;

static void fnv(uint64_t *h, const void *p, size_t len)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < len; i++) {
        *h ^= b[i];
        *h *= 1099511628211ull;
    }
}

static void fnv_scan(uint64_t *h, const hl_scan_t *scan)
{
    fnv(h, &scan->count, sizeof scan->count);
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *r = &scan->readings[i];
        fnv(h, &r->bearing, sizeof r->bearing);
        fnv(h, &r->range_mm, sizeof r->range_mm);
        fnv(h, &r->tilt, sizeof r->tilt);
        fnv(h, &r->valid, sizeof r->valid);
    }
}

static void fnv_map(uint64_t *h, const hl_vector_t *map, uint32_t count)
{
    fnv(h, &count, sizeof count);
    for (uint32_t i = 0; i < count; i++) {
        fnv(h, &map[i].x_mm, sizeof map[i].x_mm);
        fnv(h, &map[i].y_mm, sizeof map[i].y_mm);
        fnv(h, &map[i].normal, sizeof map[i].normal);
        fnv(h, &map[i].range_mm, sizeof map[i].range_mm);
    }
}

/* Notes inputs @p h among those of this scan; @return whether they were seen before. */
static bool seen_before(uint64_t *seen, int *count, uint64_t h)
{
    for (int i = 0; i < *count; i++)
        if (seen[i] == h)
            return true;
    assert_true(*count < MAX_SEEN);
    seen[(*count)++] = h;
    return false;
}

hl_status_t __real_hl_scan_check(const hl_scan_t *scan);
hl_status_t __wrap_hl_scan_check(const hl_scan_t *scan);
hl_status_t __wrap_hl_scan_check(const hl_scan_t *scan)
{
    n.checks++;
    return __real_hl_scan_check(scan);
}

hl_status_t __real_hl_echo_correct(const hl_echo_params_t *p, const hl_scan_t *in,
                                   hl_scan_t *out);
hl_status_t __wrap_hl_echo_correct(const hl_echo_params_t *p, const hl_scan_t *in,
                                   hl_scan_t *out);
hl_status_t __wrap_hl_echo_correct(const hl_echo_params_t *p, const hl_scan_t *in,
                                   hl_scan_t *out)
{
    n.echoes++;
    return __real_hl_echo_correct(p, in, out);
}

hl_status_t __real_hl_echo_correct_valid(const hl_echo_params_t *p, const hl_scan_t *in,
                                         hl_scan_t *out);
hl_status_t __wrap_hl_echo_correct_valid(const hl_echo_params_t *p, const hl_scan_t *in,
                                         hl_scan_t *out);
hl_status_t __wrap_hl_echo_correct_valid(const hl_echo_params_t *p, const hl_scan_t *in,
                                         hl_scan_t *out)
{
    n.echoes++;
    return __real_hl_echo_correct_valid(p, in, out);
}

static void count_local(const hl_vector_t *map, uint32_t count, const hl_scan_t *scan,
                        const hl_loc_query_t *q)
{
    if (n.in_global)
        return;
    n.local++;
    uint64_t h = 14695981039346656037ull;
    fnv_map(&h, map, count);
    fnv_scan(&h, scan);
    fnv(&h, &q->predicted, sizeof q->predicted);
    fnv(&h, &q->window_mm, sizeof q->window_mm);
    n.repeated_local += seen_before(n.seen_local, &n.n_local, h);
}

hl_status_t __real_hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t count,
                              const hl_scan_t *scan, const hl_loc_query_t *q,
                              hl_loc_result_t *r);
hl_status_t __wrap_hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t count,
                              const hl_scan_t *scan, const hl_loc_query_t *q,
                              hl_loc_result_t *r);
hl_status_t __wrap_hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t count,
                              const hl_scan_t *scan, const hl_loc_query_t *q,
                              hl_loc_result_t *r)
{
    count_local(map, count, scan, q);
    return __real_hl_loc_run(loc, map, count, scan, q, r);
}

hl_status_t __real_hl_loc_run_valid(hl_localizer_t *loc, const hl_vector_t *map,
                                    uint32_t count, const hl_scan_t *scan,
                                    const hl_loc_query_t *q, hl_loc_result_t *r);
hl_status_t __wrap_hl_loc_run_valid(hl_localizer_t *loc, const hl_vector_t *map,
                                    uint32_t count, const hl_scan_t *scan,
                                    const hl_loc_query_t *q, hl_loc_result_t *r);
hl_status_t __wrap_hl_loc_run_valid(hl_localizer_t *loc, const hl_vector_t *map,
                                    uint32_t count, const hl_scan_t *scan,
                                    const hl_loc_query_t *q, hl_loc_result_t *r)
{
    count_local(map, count, scan, q);
    return __real_hl_loc_run_valid(loc, map, count, scan, q, r);
}

static void count_global(const hl_vector_t *map, uint32_t count, const hl_scan_t *const *scans,
                         uint32_t nscans)
{
    n.global++;
    uint64_t h = 14695981039346656037ull;
    fnv_map(&h, map, count);
    for (uint32_t k = 0; k < nscans; k++)
        fnv_scan(&h, scans[k]);
    n.repeated_global += seen_before(n.seen_global, &n.n_global, h);
}

hl_status_t __real_hl_reloc_run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t count,
                                      const hl_scan_t *const *scans, const hl_pose_t *odometry,
                                      uint32_t nscans, hl_reloc_result_t *out);
hl_status_t __wrap_hl_reloc_run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t count,
                                      const hl_scan_t *const *scans, const hl_pose_t *odometry,
                                      uint32_t nscans, hl_reloc_result_t *out);
hl_status_t __wrap_hl_reloc_run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t count,
                                      const hl_scan_t *const *scans, const hl_pose_t *odometry,
                                      uint32_t nscans, hl_reloc_result_t *out)
{
    count_global(map, count, scans, nscans);
    n.in_global++;
    hl_status_t st = __real_hl_reloc_run_scans(r, map, count, scans, odometry, nscans, out);
    n.in_global--;
    return st;
}

hl_status_t __real_hl_reloc_run_scans_valid(hl_reloc_t *r, const hl_vector_t *map,
                                            uint32_t count, const hl_scan_t *const *scans,
                                            const hl_pose_t *odometry, uint32_t nscans,
                                            hl_reloc_result_t *out);
hl_status_t __wrap_hl_reloc_run_scans_valid(hl_reloc_t *r, const hl_vector_t *map,
                                            uint32_t count, const hl_scan_t *const *scans,
                                            const hl_pose_t *odometry, uint32_t nscans,
                                            hl_reloc_result_t *out);
hl_status_t __wrap_hl_reloc_run_scans_valid(hl_reloc_t *r, const hl_vector_t *map,
                                            uint32_t count, const hl_scan_t *const *scans,
                                            const hl_pose_t *odometry, uint32_t nscans,
                                            hl_reloc_result_t *out)
{
    count_global(map, count, scans, nscans);
    n.in_global++;
    hl_status_t st = __real_hl_reloc_run_scans_valid(r, map, count, scans, odometry, nscans,
                                                     out);
    n.in_global--;
    return st;
}

/* ---- the walks -------------------------------------------------------------------------- */

/* Steps of the walk that make the map before anything else happens. */
#define MAPPED 30

typedef struct run {
    walk_run_t walk;
    bool echo;              /* echo bearings on: one echo correction a scan */
    counts_t total;         /* over every scan so far */
} run_t;

/* The daemon's recovery (lost_after 2) with the watch every @p search_every scans, and
 * the sonar's echo bearings on (the synthetic ray is thin: they move little). */
static run_t start(uint64_t seed, int32_t search_every)
{
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.echo_bearings = true;
    p.lost_after = 2;
    p.search_every = search_every;
    return (run_t){ .walk = walk_run_start(seed, &p), .echo = p.echo_bearings };
}

static void finish(run_t *r)
{
    walk_run_finish(&r->walk);
}

/* One scan sounded at @p truth, the odometry saying @p odometry, counted on its own: it is
 * checked once and echo-corrected once, and no search repeats its inputs. */
static hl_slam_step_t sound(run_t *r, hl_pose_t truth, hl_pose_t odometry, counts_t *out)
{
    sr_sound(&r->walk.w->room, truth, 128, 8000, 15, r->walk.scan);
    memset(&n, 0, sizeof n);
    hl_slam_step_t step;
    assert_int_equal(hl_slam_update(r->walk.s, r->walk.scan, odometry, &step), HL_OK);
    assert_int_equal(n.checks, 1);
    assert_int_equal(n.echoes, r->echo ? 1 : 0);
    assert_int_equal(n.repeated_local, 0);
    assert_int_equal(n.repeated_global, 0);
    assert_int_equal(n.in_global, 0);
    r->total.checks += n.checks;
    r->total.echoes += n.echoes;
    r->total.local += n.local;
    r->total.global += n.global;
    if (out)
        *out = n;
    return step;
}

/* A walk tracked throughout: one local search a scan, and the global search only on the
 * watch's periodic scans and those tracking doubts. */
static void test_tracked_walk_one_search_a_scan(void **state)
{
    (void)state;
    run_t r = start(31, 10);
    int watched = 0, doubted = 0;
    for (int i = 0; i < STEPS; i++) {
        counts_t c;
        hl_slam_step_t step = sound(&r, r.walk.w->truth[i], r.walk.w->odom[i], &c);
        assert_false(hl_slam_lost(r.walk.s));
        assert_int_equal(c.local, 1);
        assert_int_equal(c.global, step.watched ? 1 : 0);
        bool doubt = step.status != HL_SLAM_ACCEPTED;
        if (i % 10 == 0 || doubt)
            assert_true(step.watched);
        watched += step.watched;
        doubted += doubt && i % 10 != 0;
    }
    assert_int_equal(r.total.checks, STEPS);
    assert_int_equal(r.total.echoes, STEPS);
    assert_int_equal(r.total.local, STEPS);
    /* the periodic scans (0, 10, 20, 30), those in doubt, and few else */
    print_message("tracked walk: %d scans, %d searched (%d in doubt)\n", STEPS, watched, doubted);
    assert_true(watched >= 4);
    assert_true(watched <= STEPS / 4);
    assert_int_equal(r.total.global, watched);
    finish(&r);
}

/* Where a kidnapper sets the robot down after MAPPED steps. */
static int far_step(const run_t *r)
{
    return walk_far_step(r->walk.w, MAPPED);
}

/* Carried away between two periodic searches: the first scan there is in doubt, so the
 * watch searches it, finds the robot (RELOCALIZED), and the next scan confirms it with
 * the one local search it also tracks with. Every scan of it in one pass. */
static void test_carried_away_searched_when_in_doubt(void **state)
{
    (void)state;
    run_t r = start(22, 1000);
    for (int i = 0; i < MAPPED; i++)
        sound(&r, r.walk.w->truth[i], r.walk.w->odom[i], NULL);
    assert_false(hl_slam_lost(r.walk.s));
    int k = far_step(&r);
    hl_pose_t still = r.walk.w->odom[MAPPED - 1];
    counts_t c;
    hl_slam_step_t out = sound(&r, r.walk.w->truth[k], still, &c);
    assert_true(out.watched);
    assert_int_equal(out.status, HL_SLAM_RELOCALIZED);
    assert_int_equal(out.lost_why, HL_SLAM_LOST_ELSEWHERE);
    assert_true(dist(out.pose, r.walk.w->truth[k]) < 300);
    assert_int_equal(c.local, 1);
    assert_int_equal(c.global, 1);

    /* the next step: the candidate confirmed by one local search, which tracking takes */
    hl_pose_t moved = hl_pose_compose(still, hl_pose_between(r.walk.w->truth[k], r.walk.w->truth[k + 1]));
    out = sound(&r, r.walk.w->truth[k + 1], moved, &c);
    assert_int_equal(out.found_how, HL_SLAM_FOUND_CONFIRMED);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);
    assert_int_equal(c.local, 1);
    assert_int_equal(c.global, 0);
    assert_false(hl_slam_lost(r.walk.s));
    finish(&r);
}

/* Without the watch, the same carry is noticed after lost_after doubtful scans: the scan
 * that makes the tracker lost searches once, the one tracking rejected is not localized
 * again, and while lost each scan is still checked and prepared once. */
static void test_lost_by_doubt_one_pass(void **state)
{
    (void)state;
    run_t r = start(22, 0);
    for (int i = 0; i < MAPPED; i++)
        sound(&r, r.walk.w->truth[i], r.walk.w->odom[i], NULL);
    int k = far_step(&r);
    hl_pose_t still = r.walk.w->odom[MAPPED - 1];
    counts_t c;
    hl_slam_step_t out = sound(&r, r.walk.w->truth[k], still, &c);
    assert_int_equal(out.status, HL_SLAM_REJECTED_WILD);
    assert_false(out.watched);
    assert_int_equal(c.global, 0);
    out = sound(&r, r.walk.w->truth[k], still, &c);
    assert_int_equal(out.lost_why, HL_SLAM_LOST_DOUBTFUL);
    assert_true(out.searched_lost);
    assert_int_equal(c.local, 1);
    assert_int_equal(c.global, 1);
    for (int i = 1; i < 4; i++) {
        hl_pose_t at = r.walk.w->truth[k + i];
        sound(&r, at, hl_pose_compose(still, hl_pose_between(r.walk.w->truth[k], at)), &c);
        assert_true(c.local <= 2);     /* the candidate's, and tracking's from its own */
    }
    finish(&r);
}

/* A tracker restored from a saved state searches its scans (the robot may have moved
 * while nothing watched), though the period would not, until a search puts the robot
 * where tracking does; the scans after, tracked well, are not searched. */
static void test_restored_tracker_searches_first_scan(void **state)
{
    (void)state;
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.echo_bearings = false;   /* the thin ray tracks closest without them */
    p.lost_after = 2;
    p.search_every = 1000;
    run_t a = { .walk = walk_run_start(32, &p), .echo = p.echo_bearings };
    for (int i = 0; i < 20; i++)
        sound(&a, a.walk.w->truth[i], a.walk.w->odom[i], NULL);
    hl_slam_state_t st;
    hl_slam_get_state(a.walk.s, &st);
    hl_map_t *m = hl_slam_map(a.walk.s);

    run_t b = { .walk = walk_run_start(32, &p), .echo = p.echo_bearings };
    sound(&b, b.walk.w->truth[0], b.walk.w->odom[0], NULL);   /* its period's first scan behind it */
    assert_int_equal(hl_slam_restore(b.walk.s, &st, hl_map_vectors(m), hl_map_count(m)), HL_OK);
    counts_t c;
    hl_slam_step_t out = sound(&b, b.walk.w->truth[20], b.walk.w->odom[20], &c);
    assert_true(out.watched);
    assert_int_equal(c.global, 1);
    assert_int_equal(out.status, HL_SLAM_ACCEPTED);     /* the search agreed: confirmed
                                                           (a room whose search is not
                                                           ambiguous here) */
    out = sound(&b, b.walk.w->truth[21], b.walk.w->odom[21], &c);
    assert_false(out.watched);
    assert_int_equal(c.global, 0);
    finish(&a);
    finish(&b);
}

/* ... and while no search confirms it (here none ever answers: a bar no pose clears), it
 * searches every scan for search_every scans after the restore, then the period alone. */
static void test_restored_tracker_unconfirmed_window(void **state)
{
    (void)state;
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.echo_bearings = true;
    p.lost_after = 2;
    p.search_every = 5;
    p.reloc.min_explained_pct = 100.0;
    p.reloc.max_ratio = 0.01;
    run_t a = { .walk = walk_run_start(33, &p), .echo = p.echo_bearings };
    for (int i = 0; i < 20; i++)
        sound(&a, a.walk.w->truth[i], a.walk.w->odom[i], NULL);
    hl_slam_state_t st;
    hl_slam_get_state(a.walk.s, &st);
    hl_map_t *m = hl_slam_map(a.walk.s);

    run_t b = { .walk = walk_run_start(33, &p), .echo = p.echo_bearings };
    sound(&b, b.walk.w->truth[0], b.walk.w->odom[0], NULL);    /* scan 0: periodic */
    assert_int_equal(hl_slam_restore(b.walk.s, &st, hl_map_vectors(m), hl_map_count(m)), HL_OK);
    for (int i = 1; i <= 6; i++) {     /* scans 1 .. 6 of this tracker */
        counts_t c;
        hl_slam_step_t out = sound(&b, b.walk.w->truth[19 + i], b.walk.w->odom[19 + i], &c);
        assert_int_equal(out.status, HL_SLAM_ACCEPTED);
        assert_false(out.search.found);
        assert_int_equal(out.watched, i <= 5);     /* the window; scan 5 is periodic too */
        assert_int_equal(c.global, i <= 5);
    }
    finish(&a);
    finish(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tracked_walk_one_search_a_scan),
        cmocka_unit_test(test_carried_away_searched_when_in_doubt),
        cmocka_unit_test(test_lost_by_doubt_one_pass),
        cmocka_unit_test(test_restored_tracker_searches_first_scan),
        cmocka_unit_test(test_restored_tracker_unconfirmed_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
