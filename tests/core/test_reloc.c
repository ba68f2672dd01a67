/* Tests for src/core/reloc.c: global relocalization with the heading unknown finds the
 * pose in cluttered rooms, calls a symmetric room ambiguous with the mirror pose as the
 * runner-up, refuses bad input, and is deterministic. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/reloc.h"
#include "synthroom.h"
#include "reloc_ring.h"

typedef struct fixture {
    sr_room_t room;
    hl_vector_t map[1500];
    uint32_t n;
    hl_scan_t scan;
    hl_reloc_t *reloc;
} fixture_t;

static fixture_t *make_fixture(double width, double height, int boxes, uint64_t seed)
{
    fixture_t *f = calloc(1, sizeof *f);
    sr_room_make(&f->room, -2000, 1000, width, height, boxes, seed);
    f->n = sr_make_map(&f->room, 1500, 128, 8000, 10, f->map);
    f->reloc = ring_reloc();
    assert_non_null(f->reloc);
    return f;
}

static void free_fixture(fixture_t *f)
{
    hl_reloc_destroy(f->reloc);
    free(f);
}

static bool near_pose(hl_pose_t a, hl_pose_t b, int32_t mm, double deg)
{
    int64_t dx = a.x_mm - b.x_mm, dy = a.y_mm - b.y_mm;
    int32_t dt = hl_bam_diff(a.theta, b.theta);
    return dx * dx + dy * dy <= (int64_t)mm * mm && abs(dt) <= hl_bam_from_deg(deg);
}

static void test_finds_pose_with_heading_unknown(void **state)
{
    (void)state;
    int found = 0, right = 0, wrong = 0, trials = 0;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        fixture_t *f = make_fixture(10000, 8000, 25, seed);
        for (int i = 0; i < 10; i++, trials++) {
            hl_pose_t truth = sr_free_pose(&f->room, 600);
            sr_sound(&f->room, truth, 128, 8000, 10, &f->scan);
            hl_reloc_result_t r;
            assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, &f->scan, &r), HL_OK);
            assert_true(r.headings_tried >= 1 && r.hypotheses_tried >= 1);
            bool ok = near_pose(r.pose, truth, 100, 3.0);
            if (r.found && r.have_runner_up)    /* a clear answer: its readings win */
                assert_true(r.edge > r.runner_edge);
            found += r.found;
            right += r.found && ok;
            wrong += r.found && !ok;
        }
        free_fixture(f);
    }
    print_message("reloc: %d of %d found, %d right, %d wrong\n", found, trials, right, wrong);
    /* Measured: 28 of 30 right, 1 wrong (the cluttered corner of the first room, where
     * a wrong pose explains more readings than the true one: docs/results/relocalization.md). An ideal
     * ring is the hardest input for the heading stage; the sonar tour does better
     * (tests/daemon/test_cycle_lost.c). */
    assert_true(wrong <= 1);
    assert_true(right >= 27);
}

static void test_symmetric_room_is_ambiguous(void **state)
{
    (void)state;
    /* an empty square room: four poses explain every scan equally well */
    fixture_t *f = make_fixture(6000, 6000, 0, 5);
    hl_pose_t truth = { -2000 + 1500, 1000 + 2000, hl_bam_from_deg(30.0) };
    sr_sound(&f->room, truth, 128, 8000, 10, &f->scan);
    hl_reloc_result_t r;
    assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, &f->scan, &r), HL_OK);
    assert_false(r.found);
    assert_true(r.have_runner_up);
    assert_true(hl_reloc_confidence(&r) < 0.2);
    /* the answer and the runner-up are both one of the four symmetric poses */
    int matched = 0;
    for (int k = 0; k < 4; k++) {
        /* rotate the truth by k quarter turns about the room's centre (1000, 4000) */
        double cx = 1000, cy = 4000, dx = truth.x_mm - cx, dy = truth.y_mm - cy;
        double rx = k == 0 ? dx : k == 1 ? -dy : k == 2 ? -dx : dy;
        double ry = k == 0 ? dy : k == 1 ? dx : k == 2 ? -dy : -dx;
        hl_pose_t m = { (hl_mm_t)(cx + rx), (hl_mm_t)(cy + ry),
                        (hl_bam_t)(truth.theta + k * 16384) };
        matched += near_pose(r.pose, m, 150, 3.0);
        matched += near_pose(r.runner_up, m, 150, 3.0);
    }
    assert_int_equal(matched, 2);
    /* the mirror poses explain the same readings: no edge either way, and an edge rule
     * does not call it found */
    assert_true(r.edge < 13 && r.runner_edge < 13);
    hl_reloc_params_t p;
    hl_reloc_params_default(&p);
    p.headings = 18;
    p.max_edge_ratio = 0.4;
    hl_loc_params_t fine;
    hl_loc_params_default(&fine);
    hl_reloc_t *edgy = hl_reloc_create(&p, &fine);
    hl_reloc_result_t e;
    assert_int_equal(hl_reloc_run(edgy, f->map, f->n, &f->scan, &e), HL_OK);
    assert_false(e.found);
    hl_reloc_destroy(edgy);
    free_fixture(f);
}

/* short_mm: at a pose 1 m short of where the scan was taken, the readings towards the
 * far wall stop 1 m before it; with short_mm they count against, and the pose's score
 * falls, while the true pose's (every reading ends on a wall) stays. */
static void test_short_readings_count_against(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(6000, 6000, 0, 5);
    hl_pose_t truth = { -2000 + 3500, 1000 + 2500, hl_bam_from_deg(10.0) };
    sr_sound(&f->room, truth, 128, 8000, 10, &f->scan);
    hl_pose_t back = { truth.x_mm - 1000, truth.y_mm, truth.theta };
    hl_reloc_params_t p;
    hl_reloc_params_default(&p);
    p.short_mm = 3000;
    hl_loc_params_t fine;
    hl_loc_params_default(&fine);
    hl_reloc_t *with = hl_reloc_create(&p, &fine);
    assert_non_null(with);
    uint32_t t0 = hl_reloc_judge(f->reloc, f->map, f->n, &f->scan, truth);
    uint32_t t1 = hl_reloc_judge(with, f->map, f->n, &f->scan, truth);
    uint32_t b0 = hl_reloc_judge(f->reloc, f->map, f->n, &f->scan, back);
    uint32_t b1 = hl_reloc_judge(with, f->map, f->n, &f->scan, back);
    assert_true(t0 > 100);
    assert_int_equal(t1, t0);
    assert_true(b0 < t0);
    assert_true(b1 + 10 < b0);
    p.short_mm = 300;       /* at most the 300 mm margin: refused */
    assert_non_null(hl_reloc_params_error(&p));
    hl_reloc_destroy(with);
    free_fixture(f);
}

static void test_is_deterministic(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(10000, 8000, 25, 9);
    hl_pose_t truth = sr_free_pose(&f->room, 600);
    sr_sound(&f->room, truth, 128, 8000, 10, &f->scan);
    hl_reloc_result_t a, b;
    assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, &f->scan, &a), HL_OK);
    assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, &f->scan, &b), HL_OK);
    assert_memory_equal(&a, &b, sizeof a);
    free_fixture(f);
}

static void test_bad_input(void **state)
{
    (void)state;
    fixture_t *f = make_fixture(10000, 8000, 25, 3);
    hl_pose_t truth = sr_free_pose(&f->room, 600);
    sr_sound(&f->room, truth, 128, 8000, 10, &f->scan);
    hl_reloc_result_t r;
    assert_int_equal(hl_reloc_run(NULL, f->map, f->n, &f->scan, &r), HL_ERR_ARG);
    assert_int_equal(hl_reloc_run(f->reloc, NULL, 3, &f->scan, &r), HL_ERR_ARG);
    assert_int_equal(hl_reloc_run(f->reloc, f->map, 0, &f->scan, &r), HL_ERR_EMPTY);
    assert_false(r.found);
    hl_scan_t *empty = calloc(1, sizeof *empty);
    assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, empty, &r), HL_ERR_EMPTY);
    empty->count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_reloc_run(f->reloc, f->map, f->n, empty, &r), HL_ERR_RANGE);
    free(empty);

    hl_reloc_params_t p;
    hl_reloc_params_default(&p);
    assert_null(hl_reloc_params_error(&p));
    hl_loc_params_t fine;
    hl_loc_params_default(&fine);
    p.headings = 0;
    assert_non_null(hl_reloc_params_error(&p));
    assert_null(hl_reloc_create(&p, &fine));
    hl_reloc_params_default(&p);
    p.max_ratio = 1.5;
    assert_non_null(hl_reloc_params_error(&p));
    hl_reloc_params_default(&p);
    p.coarse_max_cells = 1000;     /* the room's bounding box does not fit */
    hl_reloc_t *small = hl_reloc_create(&p, &fine);
    assert_non_null(small);
    assert_int_equal(hl_reloc_run(small, f->map, f->n, &f->scan, &r), HL_ERR_CAPACITY);
    hl_reloc_destroy(small);
    hl_reloc_destroy(NULL);
    free_fixture(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_finds_pose_with_heading_unknown),
        cmocka_unit_test(test_symmetric_room_is_ambiguous),
        cmocka_unit_test(test_short_readings_count_against),
        cmocka_unit_test(test_is_deterministic),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
