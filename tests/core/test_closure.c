/* Tests for src/core/closure.c and loop closure in the slam (slam.close_loops): a stop
 * back near an old one is matched with it, a match beyond the gate is refused, a stop
 * takes a bounded number of matches, the fit
 * pulls a drifted stop back and the map is drawn again with it, forgotten stops are not
 * offered, a stop's candidates are those near it (not the newest's), a stop's readings
 * are thinned evenly for matching, scans between stops (keyframes) join the last one, a
 * redraw spread over scans gives the map a redraw at once gives and carries the stops
 * recorded meanwhile, a fit that moves the map little is not drawn, square walls turn a
 * turned map back, and the slam starts its record afresh when its pose is set from
 * outside. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/closure.h"
#include "slam_walk.h"

#define CAP 1500

/* A room, and stops 0..6 2 m apart around a loop, the last 0.3 m from stop 0 and 1.9 m
 * from stop 1. */
typedef struct loop {
    sr_room_t room;
    hl_pose_t truth[7];
} loop_t;

static loop_t *make_loop(void)
{
    loop_t *l = calloc(1, sizeof *l);
    sr_room_make(&l->room, 0, 0, 10000, 8000, 6, 7);
    static const int xy[7][2] = { { 2000, 2000 }, { 4000, 2000 }, { 6000, 2000 },
                                  { 6000, 4000 }, { 4000, 4000 }, { 2000, 4000 },
                                  { 2000, 2300 } };
    for (int i = 0; i < 7; i++)
        l->truth[i] = (hl_pose_t){ xy[i][0], xy[i][1], 0 };
    return l;
}

/* Records stops 0..6 (the last at @p last instead of its truth) into @p c, drawing
 * each into @p map under its stamp. */
static void record_loop(loop_t *l, hl_closure_t *c, hl_map_t *map, hl_pose_t last,
                        hl_scan_t *scan)
{
    for (int i = 0; i < 7; i++) {
        hl_pose_t at = i == 6 ? last : l->truth[i];
        sr_sound(&l->room, l->truth[i], 128, 8000, 5, scan);
        hl_rng_t before = hl_map_rng(map);
        hl_map_set_stamp(map, hl_closure_next_stamp(c));
        assert_int_equal(hl_map_add_scan(map, scan, at, NULL), HL_OK);
        hl_closure_record(c, scan, at, before);
    }
}

static void test_a_stop_back_near_an_old_one_is_matched_and_pulled_back(void **state)
{
    (void)state;
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *c = hl_closure_create(16, CAP, 1);
    hl_map_t *map = hl_map_create(CAP, 1);
    assert_non_null(c);
    hl_pose_t drifted = { l->truth[6].x_mm + 150, l->truth[6].y_mm, hl_bam_from_deg(2.0) };
    record_loop(l, c, map, drifted, scan);
    assert_pose_equal(hl_closure_newest(c), drifted);

    /* Only stop 0 is 5 stops back and within 1.5 m: stamps count from 1. */
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES];
    assert_int_equal(hl_closure_candidates(c, hl_closure_newest_stamp(c), stamps,
                                           HL_CLOSURE_MAX_MATCHES), 1);
    assert_int_equal(stamps[0], 1);
    const hl_map_t *sub = hl_closure_submap(c, stamps[0], 7);
    assert_non_null(sub);
    assert_true(hl_map_count(sub) > 150);   /* stop 0 and stop 1, its neighbour */
    assert_null(hl_closure_submap(c, 99, 7));

    /* A match 600 mm from the estimate is beyond the gate (500 mm); the truth (150 mm, 2
     * deg) is not. */
    hl_pose_t far = { drifted.x_mm + 600, drifted.y_mm, drifted.theta };
    assert_false(hl_closure_match(c, stamps[0], 7, far));
    assert_true(hl_closure_match(c, stamps[0], 7, l->truth[6]));

    /* The step says "drifted", the match says "truth": the 150 mm and 2 degrees are spread
     * over the loop's seven edges, a seventh at each. The kernel weighs the match down
     * while it disagrees, and less the more the fit agrees with it: it ends near the
     * truth all the same (18 mm off, 0.3 degrees turned). */
    uint32_t before_count = hl_map_count(map);
    assert_int_equal(hl_closure_fit(c, map), 0);
    hl_pose_t fitted = hl_closure_newest(c);
    assert_true(dist(fitted, l->truth[6]) < 40 && dist(fitted, drifted) > 110);
    double turn = hl_bam_diff(fitted.theta, 0) * (360.0 / 65536.0);
    assert_true(turn > 0.1 && turn < 0.6);

    /* The map drawn again: as many vectors (none culled: far below capacity), the last
     * stop's under its stamp, now where the fitted pose puts them. */
    assert_int_equal(hl_map_count(map), before_count);
    const uint32_t *st = hl_map_stamps(map);
    uint32_t last = 0;
    for (uint32_t i = 0; i < hl_map_count(map); i++)
        last += st[i] == 7;
    assert_true(last > 50);
    hl_map_t *expect = hl_map_create(CAP, 1);
    hl_map_add_scan(expect, scan, fitted, NULL);    /* scan: the loop's last, stop 6's */
    for (uint32_t i = 0, k = 0; i < hl_map_count(map); i++)
        if (st[i] == 7) {
            assert_int_equal(hl_map_vectors(map)[i].x_mm, hl_map_vectors(expect)[k].x_mm);
            assert_int_equal(hl_map_vectors(map)[i].normal, hl_map_vectors(expect)[k].normal);
            k++;
        }
    hl_map_destroy(expect);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    free(scan);
    free(l);
}

/* The loop recorded with its last stop drifted 600 mm and 6 degrees, beyond the
 * tracker's gate, each stop drawn into the map. */
typedef struct far_loop {
    loop_t *l;
    hl_scan_t *scan;
    hl_closure_t *c;
    hl_map_t *map;
    hl_pose_t drifted;
} far_loop_t;

static far_loop_t far_loop_make(void)
{
    far_loop_t f = { make_loop(), malloc(sizeof *f.scan), hl_closure_create(16, CAP, 1),
                     hl_map_create(CAP, 1), { 0, 0, 0 } };
    hl_pose_t truth = f.l->truth[6];
    f.drifted = (hl_pose_t){ truth.x_mm + 600, truth.y_mm - 400, hl_bam_from_deg(6.0) };
    record_loop(f.l, f.c, f.map, f.drifted, f.scan);
    return f;
}

static void far_loop_free(far_loop_t *f)
{
    hl_map_destroy(f->map);
    hl_closure_destroy(f->c);
    free(f->scan);
    free(f->l);
}

/* The correlative search finds a stop drifted beyond the tracker's gate (600 mm and 6
 * degrees): its region has grown with the 12 m driven since the record began. Its
 * matches are held until settled, and taken only when two agree. */
static void test_a_correlative_search_finds_a_stop_drifted_far_and_two_must_agree(void **state)
{
    (void)state;
    far_loop_t f = far_loop_make();
    hl_closure_t *c = f.c;
    hl_map_t *map = f.map;
    hl_pose_t truth = f.l->truth[6], drifted = f.drifted;
    double mm, rad;
    hl_closure_search_region(c, 7, &mm, &rad);
    assert_true(mm > 800 && mm < 1000);                 /* 300 mm + a twentieth of ~12 m */
    assert_true(rad * 180 / 3.14159265 > 8.5 && rad * 180 / 3.14159265 < 9.5);

    /* Stops 0 and 1 are near enough to the region; stop 5 is too recent. */
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES];
    assert_int_equal(hl_closure_candidates_within(c, 7, HL_CLOSURE_RADIUS_MM + mm, stamps,
                                                  HL_CLOSURE_MAX_MATCHES), 2);
    hl_pose_t found[2];
    for (int k = 0; k < 2; k++) {
        assert_true(hl_closure_seek(c, stamps[k], 7, 0, &found[k]));
        assert_true(dist(found[k], truth) < 30);
        assert_true(abs(hl_bam_diff(found[k].theta, truth.theta)) < hl_bam_from_deg(0.5));
    }
    assert_false(hl_closure_seek(c, 99, 7, 0, &found[0]));

    /* One match alone, or two that disagree, are not taken; two that agree are. */
    hl_closure_pend(c, stamps[0], 7, found[0]);
    assert_int_equal(hl_closure_settle(c, 7), 0);
    hl_pose_t elsewhere = { found[1].x_mm + 400, found[1].y_mm, found[1].theta };
    hl_closure_pend(c, stamps[0], 7, found[0]);
    hl_closure_pend(c, stamps[1], 7, elsewhere);
    assert_int_equal(hl_closure_settle(c, 7), 0);
    hl_closure_pend(c, stamps[0], 7, found[0]);
    hl_closure_pend(c, stamps[1], 7, found[1]);
    assert_int_equal(hl_closure_settle(c, 99), 0);      /* held for another stop */
    hl_closure_pend(c, stamps[0], 7, found[0]);
    hl_closure_pend(c, stamps[1], 7, found[1]);
    assert_int_equal(hl_closure_settle(c, 7), 2);
    assert_int_equal(hl_closure_settle(c, 7), 0);       /* settled once */

    /* Two matches 14 of their sigmas from what six steps say: the fit's kernel weighs them
     * next to nothing and drops them (the steps are trusted over matches that far off; a
     * kernel widened with the region kept them, and lost on the real buildings). */
    assert_int_equal(hl_closure_fit(c, map), 2);
    assert_true(dist(hl_closure_newest(c), drifted) < 5);
    /* A match taken, though dropped: the region shrinks back to its start. */
    hl_closure_search_region(c, 7, &mm, &rad);
    assert_true(mm == HL_CLOSURE_SEARCH_MM);
    far_loop_free(&f);
}

/* A group of matches that agree is taken whole or not at all: when one of them lies
 * beyond its gate, the other is not taken either (one match left of such a group was a
 * wrong loop on a real building). The second match is held after a match was taken,
 * when the region, and with it the gate, has shrunk back to its start. */
static void test_a_group_with_a_match_beyond_the_gate_is_not_taken(void **state)
{
    (void)state;
    far_loop_t f = far_loop_make();
    hl_closure_t *c = f.c;
    hl_pose_t drifted = f.drifted;
    hl_pose_t found[2];
    assert_true(hl_closure_seek(c, 1, 7, 0, &found[0]));
    assert_true(hl_closure_seek(c, 2, 7, 0, &found[1]));

    hl_closure_pend(c, 1, 7, found[0]);     /* its gate the grown region's */
    assert_true(hl_closure_match_within(c, 1, 7, found[0], 2000, 0.5));
    double mm, rad;
    hl_closure_search_region(c, 7, &mm, &rad);
    assert_true(mm == HL_CLOSURE_SEARCH_MM);
    hl_closure_pend(c, 2, 7, found[1]);     /* 720 mm and 6 degrees off: beyond its gate */
    assert_int_equal(hl_closure_settle(c, 7), 0);

    /* A group within its gates is taken, whatever lies beyond the gate outside it. */
    hl_closure_pend(c, 1, 7, drifted);
    hl_closure_pend(c, 2, 7, drifted);
    hl_closure_pend(c, 2, 7, found[1]);
    assert_int_equal(hl_closure_settle(c, 7), 2);
    far_loop_free(&f);
}

/* Candidates are sought for a given stop: with keyframes the slam asks for the stop before
 * the newest, whose scan is complete. Stop 6 (stamp 7) is back near stop 0; a stop 8 m
 * on is near nothing. */
static void test_candidates_are_those_of_the_stop_asked_for_and_matches_are_bounded(void **state)
{
    (void)state;
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *c = hl_closure_create(16, CAP, 1);
    hl_map_t *map = hl_map_create(CAP, 1);
    record_loop(l, c, map, l->truth[6], scan);
    hl_pose_t away = { 9000, 7000, 0 };
    sr_sound(&l->room, away, 128, 8000, 5, scan);
    hl_closure_record(c, scan, away, hl_map_rng(map));
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES];
    assert_int_equal(hl_closure_newest_stamp(c), 8);
    assert_int_equal(hl_closure_candidates(c, 8, stamps, HL_CLOSURE_MAX_MATCHES), 0);
    assert_int_equal(hl_closure_candidates(c, 7, stamps, HL_CLOSURE_MAX_MATCHES), 1);
    assert_int_equal(stamps[0], 1);
    assert_int_equal(hl_closure_candidates(c, 5, stamps, HL_CLOSURE_MAX_MATCHES), 0);
    assert_int_equal(hl_closure_candidates(c, 99, stamps, HL_CLOSURE_MAX_MATCHES), 0);
    /* ... and a stop takes at most HL_CLOSURE_MAX_TAKEN matches (the graph's degree
     * bounded), however wide the gate. */
    for (int k = 0; k < HL_CLOSURE_MAX_TAKEN; k++)
        assert_true(hl_closure_match(c, 1, 7, l->truth[6]));
    assert_false(hl_closure_match(c, 1, 7, l->truth[6]));
    assert_false(hl_closure_match_within(c, 1, 7, l->truth[6], 1e6, 1.0));
    assert_int_equal(hl_closure_fit(c, map), 0);
    assert_true(dist(hl_closure_pose(c, 7), l->truth[6]) < 5);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    free(scan);
    free(l);
}

/* A stop is matched with at most so many of its readings, taken evenly through its scan
 * (slam.closure_match_readings); 0, or a scan within the bound, gives the scan itself. */
static void test_a_query_is_thinned_evenly(void **state)
{
    (void)state;
    hl_closure_t *c = hl_closure_create(4, CAP, 1);
    hl_scan_t *scan = calloc(1, sizeof *scan);
    for (uint32_t k = 0; k < 1000; k++)
        scan->readings[k] = (hl_reading_t){ .range_mm = (int32_t)(1000 + k), .valid = true };
    scan->count = 1000;
    hl_closure_record(c, scan, (hl_pose_t){ 0, 0, 0 }, (hl_rng_t){ 0 });
    uint32_t stamp = hl_closure_newest_stamp(c);
    assert_ptr_equal(hl_closure_query(c, stamp, 0), hl_closure_scan(c, stamp));
    assert_ptr_equal(hl_closure_query(c, stamp, 1000), hl_closure_scan(c, stamp));
    const hl_scan_t *q = hl_closure_query(c, stamp, 256);
    assert_int_equal(q->count, 256);
    for (uint32_t k = 1; k < q->count; k++) {   /* in order, 3 or 4 readings apart */
        int32_t gap = q->readings[k].range_mm - q->readings[k - 1].range_mm;
        assert_true(gap == 3 || gap == 4);
    }
    assert_true(q->readings[0].range_mm <= 1003 && q->readings[255].range_mm == 1999);
    assert_null(hl_closure_query(c, stamp + 1, 256));
    /* The slam's bound is a scan's at most. */
    hl_slam_params_t p;
    hl_slam_params_default(&p);
    p.closure_match_readings = HL_SCAN_MAX_READINGS + 1;
    assert_non_null(hl_slam_params_error(&p));
    p.closure_match_readings = HL_SCAN_MAX_READINGS;
    assert_null(hl_slam_params_error(&p));
    hl_closure_destroy(c);
    free(scan);
}

static void test_forgotten_stops_are_not_offered(void **state)
{
    (void)state;
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *c = hl_closure_create(6, CAP, 1);   /* one fewer than the loop */
    hl_map_t *map = hl_map_create(CAP, 1);
    record_loop(l, c, map, l->truth[6], scan);
    /* Stop 0 (stamp 1) is forgotten; stop 1 (stamp 2) is 1.9 m away. */
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES];
    assert_int_equal(hl_closure_candidates(c, hl_closure_newest_stamp(c), stamps,
                                           HL_CLOSURE_MAX_MATCHES), 0);
    assert_null(hl_closure_submap(c, 1, 7));
    assert_false(hl_closure_match(c, 1, 7, l->truth[6]));
    assert_false(hl_closure_match(c, 7, 7, l->truth[6]));   /* itself: too recent */
    /* A reset forgets all, and stamps go on rising. */
    uint32_t next = hl_closure_next_stamp(c);
    hl_closure_reset(c);
    assert_int_equal(hl_closure_next_stamp(c), next);
    assert_int_equal(hl_closure_candidates(c, hl_closure_newest_stamp(c), stamps,
                                           HL_CLOSURE_MAX_MATCHES), 0);
    assert_null(hl_closure_create(1, CAP, 1));
    assert_null(hl_closure_create(HL_CLOSURE_MAX_STOPS + 1, CAP, 1));
    hl_closure_destroy(NULL);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    free(scan);
    free(l);
}

/* Stop @p i of the loop on a map turned @p deg about stop 0 (its first stop is where it
 * truly is, the rest consistent with one another). */
static hl_pose_t turned_about_first(const loop_t *l, int i, double deg)
{
    if (i == 0)
        return l->truth[0];
    double a = deg * (3.14159265358979323846 / 180), c = cos(a), s = sin(a);
    double dx = l->truth[i].x_mm - l->truth[0].x_mm, dy = l->truth[i].y_mm - l->truth[0].y_mm;
    return (hl_pose_t){ l->truth[0].x_mm + (hl_mm_t)lround(c * dx - s * dy),
                        l->truth[0].y_mm + (hl_mm_t)lround(s * dx + c * dy),
                        hl_bam_from_deg(deg) };
}

/* As a sonar hears a room: the test kit's ring echoes from every surface, a sonar's only
 * from those nearly square to its beam. The stops all face along x, so those are the
 * readings within 12 degrees of a quarter turn. */
static void sound_specular(loop_t *l, int i, hl_scan_t *scan)
{
    sr_sound(&l->room, l->truth[i], 128, 8000, 5, scan);
    for (uint32_t k = 0; k < scan->count; k++) {
        int32_t off = hl_bam_diff(scan->readings[k].bearing, 0) % 16384;
        int32_t from_quarter = abs(off) > 8192 ? 16384 - abs(off) : abs(off);
        if (from_quarter > hl_bam_from_deg(12.0))
            scan->readings[k].valid = false;
    }
}

/* Stop 6's heading, in degrees, after the loop is recorded on a map turned 4 degrees
 * about stop 0 and its match with stop 0 fitted, with the room's walls (along x and y)
 * told to the fit or not. */
static double heading_after_fit(loop_t *l, bool square_walls, hl_scan_t *scan)
{
    hl_closure_t *c = hl_closure_create(16, CAP, 1);
    hl_map_t *map = hl_map_create(CAP, 1);
    assert_non_null(c);
    if (square_walls)
        hl_closure_square_walls(c, 0.0);
    for (int i = 0; i < 7; i++) {
        sound_specular(l, i, scan);
        hl_rng_t before = hl_map_rng(map);
        hl_map_set_stamp(map, hl_closure_next_stamp(c));
        assert_int_equal(hl_map_add_scan(map, scan, turned_about_first(l, i, 4.0), NULL), HL_OK);
        hl_closure_record(c, scan, turned_about_first(l, i, 4.0), before);
    }
    assert_true(hl_closure_match(c, 1, 7, turned_about_first(l, 6, 4.0)));
    assert_int_equal(hl_closure_fit(c, map), 0);
    double deg = hl_bam_diff(hl_closure_newest(c).theta, 0) * (360.0 / 65536.0);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    return deg;
}

/* A map turned as a whole about its first stop: the steps and the match agree with one
 * another, so the fit alone leaves it turned; told that the walls run along x and y, each
 * stop's readings turn it back. */
static void test_scans_between_stops_join_the_last_one(void **state)
{
    (void)state;
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *c = hl_closure_create(16, CAP, 1);
    hl_map_t *map = hl_map_create(CAP, 1), *alone = hl_map_create(CAP, 1);
    assert_non_null(c);
    hl_pose_t stop = l->truth[0], next = { stop.x_mm + 300, stop.y_mm + 100, hl_bam_from_deg(10) };
    assert_true(hl_closure_is_stop(c, stop, 500, hl_bam_from_deg(20)));
    sr_sound(&l->room, stop, 128, 8000, 5, scan);
    hl_closure_record(c, scan, stop, hl_map_rng(map));
    uint32_t own = scan->count;
    /* 316 mm and 10 degrees on: not a stop under 500 mm / 20 degrees, one under 300 mm
     * or 10 degrees, and always with both 0. */
    assert_false(hl_closure_is_stop(c, next, 500, hl_bam_from_deg(20)));
    assert_true(hl_closure_is_stop(c, next, 300, hl_bam_from_deg(20)));
    assert_true(hl_closure_is_stop(c, next, 500, hl_bam_from_deg(10)));
    assert_true(hl_closure_is_stop(c, next, 0, 0));
    assert_int_equal(hl_closure_newest_stamp(c), 1);
    /* The scan joined, and the stop drawn again: its readings land where the scan's own
     * would (to within the rounding of range and bearing), in order, under the stop's
     * stamp; only those whose surface faces away from the stop are left out (a grazing wall: 9 of
     * 128 here). */
    sr_sound(&l->room, next, 128, 8000, 5, scan);
    hl_map_add_scan(alone, scan, next, NULL);
    hl_closure_append(c, scan, next);
    hl_map_set_stamp(map, hl_closure_newest_stamp(c));
    hl_closure_fit(c, map);
    uint32_t joined = hl_map_count(map) - own, want_n = hl_map_count(alone);
    assert_true(joined <= want_n && joined >= want_n * 9 / 10);
    const hl_vector_t *drawn = hl_map_vectors(map) + own, *want = hl_map_vectors(alone);
    for (uint32_t i = 0, j = 0; i < joined; i++, j++) {
        while (j < want_n && (abs(drawn[i].x_mm - want[j].x_mm) > 12 ||
                              abs(drawn[i].y_mm - want[j].y_mm) > 12 ||
                              abs(hl_bam_diff(drawn[i].normal, want[j].normal)) > 2))
            j++;
        assert_true(j < want_n);
        assert_int_equal(hl_map_stamps(map)[own + i], 1);
    }
    hl_map_destroy(alone);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    free(scan);
    free(l);
}

/* Two records of the same drifted loop (each from its own room, so that the soundings'
 * noise is the same), each with its match: one fitted and drawn at once, the other
 * fitted and drawn aside a stop or two a call. */
static void drifted_loop(loop_t *l, hl_closure_t *c, hl_map_t *map, hl_scan_t *scan)
{
    hl_pose_t drifted = { l->truth[6].x_mm + 150, l->truth[6].y_mm, hl_bam_from_deg(2.0) };
    record_loop(l, c, map, drifted, scan);
    assert_true(hl_closure_match(c, 1, 7, l->truth[6]));
}

/* As the slam records a stop after a fit: stop 6's sounding drawn into @p map at @p on
 * (where the slam has the robot, in the map's frame) and recorded. */
static void record_stop_at(loop_t *l, hl_closure_t *c, hl_map_t *map, hl_pose_t on,
                           hl_scan_t *scan)
{
    sr_sound(&l->room, l->truth[6], 128, 8000, 5, scan);
    hl_rng_t rng = hl_map_rng(map);
    hl_map_set_stamp(map, hl_closure_next_stamp(c));
    hl_map_add_scan(map, scan, on, NULL);
    hl_closure_record(c, scan, on, rng);
}

static void test_a_redraw_spread_over_scans_gives_the_same_map(void **state)
{
    (void)state;
    loop_t *l = make_loop(), *twin = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *now = hl_closure_create(16, CAP, 1), *later = hl_closure_create(16, CAP, 1);
    hl_map_t *map_now = hl_map_create(CAP, 1), *map = hl_map_create(CAP, 1);
    hl_map_t *shadow = hl_map_create(CAP, 1);
    drifted_loop(l, now, map_now, scan);
    drifted_loop(twin, later, map, scan);
    hl_closure_fit(now, map_now);

    hl_pose_t tracked = hl_closure_newest(later);
    hl_closure_fit_spread(later, map, shadow);
    assert_true(hl_closure_redrawing(later));
    /* Until the swap the map and the slam's frame are the old ones. */
    uint64_t version = hl_map_version(map);
    uint32_t calls = 0;
    assert_pose_equal(hl_closure_newest(later), tracked);
    while (!hl_closure_redraw_step(later, map, shadow, 200)) {  /* 128 readings a stop */
        assert_int_equal(hl_map_version(map), version);
        calls++;
    }
    assert_int_equal(calls, 3);     /* 2 stops a call, the newest in the last */
    assert_false(hl_closure_redrawing(later));
    assert_true(hl_map_version(map) != version);
    assert_false(hl_closure_redraw_step(later, map, shadow, 200));

    /* The same map as the redraw at once, vector for vector, and the same poses; the
     * pose tracked before the fit carried to the fitted one. */
    assert_int_equal(hl_map_count(map), hl_map_count(map_now));
    for (uint32_t i = 0; i < hl_map_count(map); i++) {
        assert_int_equal(hl_map_vectors(map)[i].x_mm, hl_map_vectors(map_now)[i].x_mm);
        assert_int_equal(hl_map_vectors(map)[i].y_mm, hl_map_vectors(map_now)[i].y_mm);
        assert_int_equal(hl_map_vectors(map)[i].normal, hl_map_vectors(map_now)[i].normal);
        assert_int_equal(hl_map_stamps(map)[i], hl_map_stamps(map_now)[i]);
    }
    assert_pose_equal(hl_closure_newest(later), hl_closure_newest(now));
    assert_pose_equal(hl_closure_carry(later, tracked), hl_closure_newest(now));

    hl_map_destroy(shadow);
    hl_map_destroy(map);
    hl_map_destroy(map_now);
    hl_closure_destroy(later);
    hl_closure_destroy(now);
    free(scan);
    free(twin);
    free(l);
}

/* A drifted loop recorded and matched, its map, and a shadow for a spread redraw: the
 * setup of the tests of spread fits (cmocka state). */
typedef struct spread {
    loop_t *l;
    hl_scan_t *scan;
    hl_closure_t *c;
    hl_map_t *map, *shadow;
    hl_pose_t before;       /* the newest stop before the fit */
} spread_t;

static int spread_setup(void **state)
{
    spread_t *f = calloc(1, sizeof *f);
    f->l = make_loop();
    f->scan = malloc(sizeof *f->scan);
    f->c = hl_closure_create(16, CAP, 1);
    f->map = hl_map_create(CAP, 1);
    f->shadow = hl_map_create(CAP, 1);
    drifted_loop(f->l, f->c, f->map, f->scan);
    f->before = hl_closure_newest(f->c);
    *state = f;
    return 0;
}

static int spread_teardown(void **state)
{
    spread_t *f = *state;
    hl_map_destroy(f->shadow);
    hl_map_destroy(f->map);
    hl_closure_destroy(f->c);
    free(f->scan);
    free(f->l);
    free(f);
    return 0;
}

/* slam.closure_redraw_mm: a fit that moves no stop beyond the bound is not drawn (the map
 * and the slam stay in the frame before it, a stop recorded meanwhile is carried into the
 * fit's), and a later fit measured from the map as drawn draws them all. */
static void test_a_fit_that_moves_the_map_little_is_not_drawn(void **state)
{
    spread_t *f = *state;
    hl_closure_t *c = f->c;
    hl_map_t *map = f->map, *shadow = f->shadow;
    hl_pose_t before = f->before;
    uint64_t version = hl_map_version(map);
    hl_closure_redraw_beyond(c, 1000);  /* the fit moves the drifted stop ~150 mm, 2 deg */
    hl_closure_fit_spread(c, map, shadow);
    assert_false(hl_closure_redrawing(c));
    assert_int_equal(hl_map_version(map), version);
    assert_pose_equal(hl_closure_newest(c), before);

    hl_pose_t on = { before.x_mm + 1000, before.y_mm, before.theta };
    record_stop_at(f->l, c, map, on, f->scan);
    assert_pose_equal(hl_closure_newest(c), on);    /* in the map where the slam put it */
    hl_pose_t carried = hl_closure_carry(c, on);
    assert_true(abs(carried.x_mm - on.x_mm) + abs(carried.y_mm - on.y_mm) > 20);

    hl_closure_redraw_beyond(c, 1);
    hl_closure_fit_spread(c, map, shadow);
    assert_true(hl_closure_redrawing(c));
    while (!hl_closure_redraw_step(c, map, shadow, 100000))
        ;
    /* Drawn where the fits put it: as carried from the map's frame, give or take what the
     * second fit moved it. */
    hl_pose_t drawn = hl_closure_newest(c);
    assert_true(abs(drawn.x_mm - carried.x_mm) <= 5 && abs(drawn.y_mm - carried.y_mm) <= 5);
    assert_true(abs(hl_bam_diff(drawn.theta, carried.theta)) <= hl_bam_from_deg(0.1));
    assert_true(hl_map_version(map) != version);
}

static void test_a_stop_recorded_during_a_spread_redraw_is_carried(void **state)
{
    spread_t *f = *state;
    hl_closure_t *c = f->c;
    hl_map_t *map = f->map, *shadow = f->shadow;
    hl_pose_t before = f->before;
    hl_closure_fit_spread(c, map, shadow);
    hl_pose_t fitted = hl_closure_carry(c, before);
    /* The slam, still in the old frame, records a stop 1 m on: it is the newest, drawn
     * (in the map in use) where the slam put it, and lands as far from the fitted pose
     * once the shadow is in place. No match is sought meanwhile. */
    hl_pose_t on = { before.x_mm + 1000, before.y_mm, before.theta };
    record_stop_at(f->l, c, map, on, f->scan);
    assert_pose_equal(hl_closure_newest(c), on);
    while (!hl_closure_redraw_step(c, map, shadow, 100000))
        ;
    hl_pose_t carried = hl_closure_newest(c);
    assert_pose_equal(carried, hl_closure_carry(c, on));
    /* 1 m along x before the fit: 1 m along x turned as the fit turned the stop. */
    double turn = hl_bam_diff(fitted.theta, before.theta) * (2 * 3.14159265358979 / 65536);
    double c0 = cos(turn), s0 = sin(turn);
    assert_true(fabs(carried.x_mm - (fitted.x_mm + 1000 * c0)) <= 1);
    assert_true(fabs(carried.y_mm - (fitted.y_mm + 1000 * s0)) <= 1);
    /* Its vectors are in the map, under its stamp (8). */
    uint32_t its = 0;
    for (uint32_t i = 0; i < hl_map_count(map); i++)
        its += hl_map_stamps(map)[i] == 8;
    assert_true(its > 50);
}

/* The vectors of stop @p stamp among @p n (vectors @p v, stamps @p stamps), in slot
 * order, into @p out: how many. */
static uint32_t vectors_of(const hl_vector_t *v, const uint32_t *stamps, uint32_t n,
                           uint32_t stamp, hl_vector_t *out)
{
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++)
        if (stamps[i] == stamp)
            out[k++] = v[i];
    return k;
}

/* slam.closure_redraw_stop_mm: a spread fit that moves few stops (a sixteenth of them at
 * most) beyond the bound draws again those and the newest; the others keep their poses
 * and their vectors as they lay. Here the loop's fit (which moves most stops, and so
 * draws them all), nine stops recorded on from there, and a second fit, which moves no
 * earlier one. */
static void test_a_fit_draws_again_only_the_stops_it_moved(void **state)
{
    (void)state;
    enum { BIG = 4000, STOPS = 16 };    /* room for every stop's vectors: no cull */
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_closure_t *c = hl_closure_create(32, BIG, 1);
    hl_map_t *map = hl_map_create(BIG, 1), *shadow = hl_map_create(BIG, 1);
    drifted_loop(l, c, map, scan);
    hl_closure_redraw_stops_beyond(c, 30);
    hl_closure_fit_spread(c, map, shadow);
    while (!hl_closure_redraw_step(c, map, shadow, 100000))
        ;
    hl_pose_t on = hl_closure_newest(c);
    for (int k = 7; k < STOPS; k++) {
        on.x_mm += 100;
        record_stop_at(l, c, map, on, scan);
    }
    /* A vector of stop 3 that no redraw of it would give: kept only with the stop. */
    hl_vector_t odd = { 5000, 7000, hl_bam_from_deg(90.0), 1234 };
    hl_map_set_stamp(map, 3);
    assert_int_equal(hl_map_add(map, &odd), HL_OK);
    hl_map_set_stamp(map, hl_closure_newest_stamp(c));

    uint32_t n_old = hl_map_count(map), *stamps = malloc(BIG * sizeof *stamps);
    hl_vector_t *old = malloc(BIG * sizeof *old), *was = malloc(BIG * sizeof *was);
    hl_vector_t *is = malloc(BIG * sizeof *is);
    memcpy(old, hl_map_vectors(map), n_old * sizeof *old);
    memcpy(stamps, hl_map_stamps(map), n_old * sizeof *stamps);
    hl_pose_t before[STOPS];
    for (uint32_t k = 0; k < STOPS; k++)
        before[k] = hl_closure_pose(c, 1 + k);
    uint64_t version = hl_map_version(map);
    hl_closure_fit_spread(c, map, shadow);
    while (!hl_closure_redraw_step(c, map, shadow, 100000))
        ;
    assert_true(hl_map_version(map) != version);
    for (uint32_t k = 0; k + 1 < STOPS; k++) {     /* all but the newest kept as they lay */
        hl_pose_t now = hl_closure_pose(c, 1 + k);
        assert_memory_equal(&now, &before[k], sizeof now);
        uint32_t n_was = vectors_of(old, stamps, n_old, 1 + k, was);
        uint32_t n_is = vectors_of(hl_map_vectors(map), hl_map_stamps(map), hl_map_count(map),
                                   1 + k, is);
        assert_true(n_is > 50);
        assert_int_equal(n_is, n_was);
        assert_memory_equal(is, was, n_is * sizeof *is);
    }
    assert_true(vectors_of(hl_map_vectors(map), hl_map_stamps(map), hl_map_count(map), STOPS,
                           is) > 50);          /* the newest, drawn again */
    hl_map_destroy(shadow);
    hl_map_destroy(map);
    hl_closure_destroy(c);
    free(stamps);
    free(old);
    free(was);
    free(is);
    free(scan);
    free(l);
}

static void test_square_walls_turn_a_turned_map_back(void **state)
{
    (void)state;
    loop_t *l = make_loop();
    hl_scan_t *scan = malloc(sizeof *scan);
    double plain = heading_after_fit(l, false, scan);
    double square = heading_after_fit(l, true, scan);
    assert_true(plain > 3.9 && plain < 4.1);
    assert_true(fabs(square) < 1.5);
    /* The slam refuses square walls without loop closure, whose fit they are part of. */
    hl_slam_params_t p;
    hl_slam_params_default(&p);
    p.square_walls = true;
    assert_non_null(hl_slam_params_error(&p));
    p.close_loops = true;
    assert_null(hl_slam_params_error(&p));
    free(scan);
    free(l);
}

/* The slam with close_loops on the noisy walk of slam_walk.h. */
static void test_the_slam_closes_loops_and_starts_afresh_when_placed(void **state)
{
    (void)state;
    walk_t *w = make_walk(3);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.closure_stops = 1;
    assert_non_null(hl_slam_params_error(&p));
    p.closure_stops = 4097;
    assert_non_null(hl_slam_params_error(&p));
    p.closure_stops = 256;
    p.close_loops = true;
    hl_slam_t *s = hl_slam_create_with(&p);
    assert_non_null(s);
    hl_slam_reset(s, w->truth[0]);
    uint32_t loops = 0;
    hl_slam_step_t step;
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &step), HL_OK);
        loops += step.loops;
        if (i < HL_CLOSURE_GAP)
            assert_int_equal(step.loops, 0);     /* nothing old enough to match */
    }
    assert_true(loops > 0);     /* 40 steps in a 10 x 8 m room come back */
    const uint32_t *st = hl_map_stamps(hl_slam_map(s));
    for (uint32_t i = 0; i < hl_map_count(hl_slam_map(s)); i++)
        assert_true(st[i] >= 1 && st[i] <= STEPS);
    /* Placed by hand: no step joins the stops before to those after. */
    assert_int_equal(hl_slam_set_pose(s, w->truth[0], w->odom[0]), HL_OK);
    for (int i = 0; i < HL_CLOSURE_GAP; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &step), HL_OK);
        assert_int_equal(step.loops, 0);
    }
    hl_slam_destroy(s);

    /* Off (the default): never a loop. */
    ray_sensor_defaults(&p);
    assert_false(p.close_loops);
    s = hl_slam_create_with(&p);
    hl_slam_reset(s, w->truth[0]);
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &step), HL_OK);
        assert_int_equal(step.loops, 0);
    }
    hl_slam_destroy(s);
    free(scan);
    free(w);
}

/* A walk closed a share a scan: the slam takes its matches a few a scan
 * (closure_matches_per_scan), fits in a scan of its own and draws the map aside, and stays
 * as near the walk's truth as when it closes each stop at once. */
static void test_the_slam_spreads_its_matches_and_redraws_over_scans(void **state)
{
    (void)state;
    walk_t *w = make_walk(3);
    hl_scan_t *scan = malloc(sizeof *scan);
    hl_slam_params_t p;
    ray_sensor_defaults(&p);
    p.close_loops = true;
    p.closure_matches_per_scan = 2;
    p.closure_redraw_readings = 2000;   /* 15 stops of 128 readings a scan */
    hl_slam_t *s = hl_slam_create_with(&p);
    assert_non_null(s);
    hl_slam_reset(s, w->truth[0]);
    uint32_t loops = 0, most = 0;
    double worst = 0;
    hl_slam_step_t step;
    for (int i = 0; i < STEPS; i++) {
        sr_sound(&w->room, w->truth[i], 128, 8000, 15, scan);
        assert_int_equal(hl_slam_update(s, scan, w->odom[i], &step), HL_OK);
        loops += step.loops;
        most = step.loops > most ? step.loops : most;
        worst = fmax(worst, dist(step.pose, w->truth[i]));
    }
    /* 11 matches (63 at once: a stop made while an earlier one's are sought, fitted or
     * drawn seeks none), never more than 2 a scan; every pose within 17 mm of the truth
     * (21 at once). */
    assert_true(loops >= 8);
    assert_true(most <= 2);
    assert_true(worst < 50);
    const uint32_t *st = hl_map_stamps(hl_slam_map(s));
    for (uint32_t i = 0; i < hl_map_count(hl_slam_map(s)); i++)
        assert_true(st[i] >= 1 && st[i] <= STEPS);
    hl_slam_destroy(s);
    free(scan);
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_stop_back_near_an_old_one_is_matched_and_pulled_back),
        cmocka_unit_test(test_a_correlative_search_finds_a_stop_drifted_far_and_two_must_agree),
        cmocka_unit_test(test_a_group_with_a_match_beyond_the_gate_is_not_taken),
        cmocka_unit_test(test_candidates_are_those_of_the_stop_asked_for_and_matches_are_bounded),
        cmocka_unit_test(test_a_query_is_thinned_evenly),
        cmocka_unit_test(test_forgotten_stops_are_not_offered),
        cmocka_unit_test(test_scans_between_stops_join_the_last_one),
        cmocka_unit_test(test_a_redraw_spread_over_scans_gives_the_same_map),
        cmocka_unit_test_setup_teardown(test_a_fit_that_moves_the_map_little_is_not_drawn,
                                        spread_setup, spread_teardown),
        cmocka_unit_test(test_a_fit_draws_again_only_the_stops_it_moved),
        cmocka_unit_test_setup_teardown(test_a_stop_recorded_during_a_spread_redraw_is_carried,
                                        spread_setup, spread_teardown),
        cmocka_unit_test(test_square_walls_turn_a_turned_map_back),
        cmocka_unit_test(test_the_slam_closes_loops_and_starts_afresh_when_placed),
        cmocka_unit_test(test_the_slam_spreads_its_matches_and_redraws_over_scans),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
