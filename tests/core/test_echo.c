/* Tests for src/core/echo.c: a wall seen through a 22 degree cone (its plateau moves to
 * the foot, its flanks to their cone edges), a round room (nothing moves), a bounced
 * reading, wrap-around, flank normals, hostile scans and parameter checks. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "houghloc-internal/echo.h"
#include "houghloc/rng.h"

#define RING 128
#define STEP_DEG (360.0 / RING)
#define HALF_DEG 11.0
#define CRITICAL_DEG 40.0
#define PI 3.14159265358979323846

/* The noiseless first echo of an infinite wall at @p d_mm, normal at @p normal_deg,
 * through a cone of half-width 11 deg: the foot when the cone holds the normal, else the
 * cone edge nearest the normal; nothing past the critical angle. */
static int32_t wall_range(double bearing_deg, double normal_deg, double d_mm)
{
    double off = fabs(remainder(bearing_deg - normal_deg, 360.0)) - HALF_DEG;
    if (off > CRITICAL_DEG)
        return -1;
    return (int32_t)lround(d_mm / cos((off > 0 ? off : 0) * PI / 180.0));
}

static void make_wall_ring(hl_scan_t *scan, double normal_deg, double d_mm)
{
    hl_scan_clear(scan);
    for (int i = 0; i < RING; i++) {
        double b = i * STEP_DEG;
        int32_t r = wall_range(b, normal_deg, d_mm);
        assert_int_equal(hl_scan_add(scan, hl_bam_from_deg(b), r < 0 ? 0 : r, (int8_t)(i % 16),
                                     r >= 0),
                         HL_OK);
    }
}

static double sdeg(hl_bam_t a)
{
    return hl_bam_to_sdeg(a);
}

/* What the estimate promises for a noiseless wall: every reading moves towards the
 * wall's normal, never away and never out of its cone; readings near the foot land
 * within 3 degrees of it; a flank reading whose outer neighbour is longer by more than
 * two sigma (so that the ring can tell it is a flank) lands at its cone edge, to within
 * half a ring step (the middle of the last uncontradicted step). */
static void check_wall(const hl_echo_params_t *p, const hl_scan_t *in, const hl_scan_t *out,
                       double normal, int *near_foot, int *steep)
{
    *near_foot = *steep = 0;
    for (uint32_t i = 0; i < in->count; i++) {
        const hl_reading_t *a = &in->readings[i], *b = &out->readings[i];
        assert_int_equal(a->range_mm, b->range_mm);
        assert_int_equal(a->valid, b->valid);
        if (!a->valid)
            continue;
        double axis = sdeg(a->bearing), off = remainder(axis - normal, 360.0);
        double moved = remainder(sdeg(b->bearing) - axis, 360.0);
        assert_true(fabs(moved) <= HALF_DEG + 0.01);
        if (fabs(off) > 1.5 && moved * off > 0)
            fail_msg("reading %+.1f deg off the normal moved away from it (%+.2f)", off, moved);
        if (fabs(off) <= 3.0) {
            assert_true(fabs(remainder(sdeg(b->bearing) - normal, 360.0)) <= 3.0);
            (*near_foot)++;
        }
        uint32_t outer = (i + (off > 0 ? 1 : in->count - 1)) % in->count;
        double sigma = p->noise_mm + a->range_mm * p->noise_permille / 1000.0;
        if (fabs(off) > HALF_DEG && in->readings[outer].valid &&
            in->readings[outer].range_mm - a->range_mm > 2 * sigma) {
            double want = off > 0 ? -HALF_DEG : HALF_DEG;
            if (fabs(moved - want) > STEP_DEG / 2 + 0.3)
                fail_msg("flank reading %+.1f deg off the normal moved %+.2f, want %+.1f", off,
                         moved, want);
            (*steep)++;
        }
    }
}

/* Estimates a noiseless wall's ring and checks it (check_wall). */
static void run_wall(double normal_deg, double d_mm)
{
    hl_echo_params_t p;
    hl_echo_params_default(&p);
    p.half_beam = hl_bam_from_deg(HALF_DEG);   /* these rings see through a hard cone */
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    make_wall_ring(in, normal_deg, d_mm);
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    int near_foot, steep;
    check_wall(&p, in, out, normal_deg, &near_foot, &steep);
    assert_true(near_foot >= 2);
    assert_true(steep >= 6);    /* three or four per flank, from about 27 deg of incidence */
    free(in);
    free(out);
}

static void test_wall_plateau_and_flanks(void **state)
{
    (void)state;
    run_wall(47.0, 2500.0);
}

/* Flank normals: on a wall seen through hard 22-degree cones (ranges in 10 mm steps, as
 * the pseudo-sonar's), every reading given a tilt has the wall's normal to within 3
 * degrees and its echo on the wall, the plateau stays square to its beam, and without
 * the option the flanks' normals (their beams') are far off. */
static void test_flank_normals(void **state)
{
    (void)state;
    const double normal = 47.0, d = 2500.0;
    hl_echo_params_t p;
    hl_echo_params_default(&p);
    p.half_beam = hl_bam_from_deg(HALF_DEG);
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    make_wall_ring(in, normal, d);
    for (uint32_t i = 0; i < in->count; i++)
        in->readings[i].range_mm = (in->readings[i].range_mm + 5) / 10 * 10;
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    double worst_beam = 0;
    for (uint32_t i = 0; i < out->count; i++) {
        if (!out->readings[i].valid)
            continue;
        assert_int_equal(out->readings[i].tilt, 0);
        double off = fabs(remainder(sdeg(hl_reading_normal(&out->readings[i], 0)) -
                                    (normal + 180.0), 360.0));
        worst_beam = off > worst_beam ? off : worst_beam;
    }
    assert_true(worst_beam > 20.0);

    p.flank_normals = true;
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    assert_int_equal(hl_scan_check(out), HL_OK);
    int tilted = 0;
    for (uint32_t i = 0; i < out->count; i++) {
        const hl_reading_t *r = &out->readings[i];
        if (!r->valid)
            continue;
        if (in->readings[i].range_mm <= d + 10) {   /* the plateau */
            assert_int_equal(r->tilt, 0);
            continue;
        }
        if (r->tilt == 0)
            continue;
        tilted++;
        double off = fabs(remainder(sdeg(hl_reading_normal(r, 0)) - (normal + 180.0), 360.0));
        assert_true(off < 3.0);
        double a = hl_bam_to_rad(r->bearing);
        double along_normal = r->range_mm * (cos(a) * cos(normal * PI / 180) +
                                             sin(a) * sin(normal * PI / 180));
        assert_true(fabs(along_normal - d) < 0.02 * d);
    }
    assert_true(tilted >= 10);
    free(in);
    free(out);
}

/* In a round room centred on the robot no reading contradicts another: all stay put. */
static void test_round_room_stays_on_axis(void **state)
{
    (void)state;
    hl_echo_params_t p;
    hl_echo_params_default(&p);
    p.half_beam = hl_bam_from_deg(HALF_DEG);   /* these rings see through a hard cone */
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    hl_scan_clear(in);
    for (int i = 0; i < RING; i++)
        hl_scan_add(in, hl_bam_from_deg(i * STEP_DEG), 3000, -1, true);
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    for (uint32_t i = 0; i < in->count; i++)
        assert_true(abs(hl_bam_diff(out->readings[i].bearing, in->readings[i].bearing)) <= 2);
    free(in);
    free(out);
}

/* One bounced reading (2 m too long) inside a wall's plateau must not drag its
 * neighbours off the foot by more than a few degrees: its contradiction is capped. */
static void test_bounced_reading_is_capped(void **state)
{
    (void)state;
    hl_echo_params_t p;
    hl_echo_params_default(&p);
    p.half_beam = hl_bam_from_deg(HALF_DEG);   /* these rings see through a hard cone */
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    const double normal = 90.0;
    make_wall_ring(in, normal, 2000.0);
    uint32_t bounced = (uint32_t)lround(normal / STEP_DEG) + 1;
    in->readings[bounced].range_mm += 2000;
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    for (int k = -2; k <= 2; k++) {
        uint32_t i = (uint32_t)((int)bounced + k);
        if (i == bounced)
            continue;
        double err = remainder(sdeg(out->readings[i].bearing) - normal, 360.0);
        if (fabs(err) > 6.0)
            fail_msg("plateau reading %u lands %+.1f deg from the foot", i, err);
    }
    free(in);
    free(out);
}

/* A wall whose normal lies on bearing 0: the ring wraps through 0 / 65535 BAM. */
static void test_wraps_through_zero(void **state)
{
    (void)state;
    run_wall(0.0, 1800.0);
}

/* Hostile scans: every reading on one bearing, random ranges, empty and all-invalid
 * scans. Each finishes, and no reading leaves its own cone. */
static void test_hostile_scans(void **state)
{
    (void)state;
    hl_echo_params_t p;
    hl_echo_params_default(&p);
    p.half_beam = hl_bam_from_deg(HALF_DEG);   /* these rings see through a hard cone */
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    hl_rng_t rng;
    hl_rng_seed(&rng, 9);
    for (int round = 0; round < 20; round++) {
        hl_scan_clear(in);
        hl_bam_t one = (hl_bam_t)hl_rng_next(&rng);
        for (int i = 0; i < HL_SCAN_MAX_READINGS; i++) {
            hl_bam_t b = round % 2 ? one : (hl_bam_t)hl_rng_next(&rng);
            hl_scan_add(in, b, (int32_t)hl_rng_below(&rng, HL_RANGE_MAX_MM + 1), -1,
                        hl_rng_below(&rng, 4) != 0);
        }
        p.flank_normals = round % 4 >= 2;
        assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
        assert_int_equal(hl_scan_check(out), HL_OK);
        for (uint32_t i = 0; i < in->count; i++)
            assert_true(abs(hl_bam_diff(out->readings[i].bearing, in->readings[i].bearing)) <=
                        p.half_beam);
    }
    hl_scan_clear(in);
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    assert_int_equal(out->count, 0);
    hl_scan_add(in, 100, 500, 0, false);
    assert_int_equal(hl_echo_correct(&p, in, out), HL_OK);
    assert_int_equal(out->readings[0].bearing, 100);
    free(in);
    free(out);
}

static void test_params_and_inputs_validated(void **state)
{
    (void)state;
    hl_echo_params_t p;
    hl_scan_t *in = malloc(sizeof *in), *out = malloc(sizeof *out);
    hl_scan_clear(in);
    hl_echo_params_default(&p);
    assert_null(hl_echo_params_error(&p));
    assert_non_null(hl_echo_params_error(NULL));
    p.half_beam = 0;
    assert_non_null(hl_echo_params_error(&p));
    assert_int_equal(hl_echo_correct(&p, in, out), HL_ERR_ARG);
    hl_echo_params_default(&p);
    p.step = 0;
    assert_non_null(hl_echo_params_error(&p));
    p.step = 1;     /* 2 * 7 deg / 1 BAM candidates: far too many */
    assert_non_null(hl_echo_params_error(&p));
    hl_echo_params_default(&p);
    p.noise_mm = 0;
    assert_non_null(hl_echo_params_error(&p));
    hl_echo_params_default(&p);
    assert_int_equal(hl_echo_correct(&p, NULL, out), HL_ERR_ARG);
    assert_int_equal(hl_echo_correct(&p, in, NULL), HL_ERR_ARG);
    assert_int_equal(hl_echo_correct(&p, in, in), HL_ERR_ARG);
    in->count = HL_SCAN_MAX_READINGS + 1;
    assert_int_equal(hl_echo_correct(&p, in, out), HL_ERR_RANGE);
    free(in);
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wall_plateau_and_flanks),
        cmocka_unit_test(test_flank_normals),
        cmocka_unit_test(test_round_room_stays_on_axis),
        cmocka_unit_test(test_bounced_reading_is_capped),
        cmocka_unit_test(test_wraps_through_zero),
        cmocka_unit_test(test_hostile_scans),
        cmocka_unit_test(test_params_and_inputs_validated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
