/* Tests for src/robot/sounder.c and profile.c: a fake base that turns when told and
 * reports every transducer's range, one SIP per 100 ms of robot time. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "houghloc/sounder.h"

/* The fake base: it turns at 45 deg/s towards a commanded heading, reports "moving"
 * while it does, and has every transducer fire once per @p fire_every SIPs with a raw
 * range that encodes (step heading, transducer) so the test can check the assembly. */
typedef struct base {
    hl_bam_t heading, target;
    int64_t t_ms;
    int fire_every;
    bool deaf;              /* transducer 3 never answers */
    int n_turns;
} base_t;

static uint16_t raw_of(hl_bam_t heading, int t)
{
    return (uint16_t)(1000 + t * 100 + (heading / 512) % 64);
}

static void sip_of(base_t *b, hl_sounder_sip_t *s)
{
    b->t_ms += 100;
    int32_t off = hl_bam_diff(b->target, b->heading);
    int32_t step = 45 * 65536 / 360 / 10;  /* per 100 ms */
    bool moving = off != 0;
    if (abs(off) <= step)
        b->heading = b->target;
    else
        b->heading = (hl_bam_t)(b->heading + (off > 0 ? step : -step));
    memset(s, 0, sizeof *s);
    s->robot_ms = b->t_ms;
    s->odometry = (hl_pose_t){ 1000, -500, b->heading };
    s->moving = moving;
    if ((b->t_ms / 100) % b->fire_every == 0)
        for (int t = 0; t < 16; t++) {
            if (b->deaf && t == 3)
                continue;
            s->transducer[s->readings] = (uint8_t)t;
            s->raw[s->readings++] = raw_of(b->heading, t);
        }
}

/* Runs a sounding on @p b to its end; @return SIPs used. */
static int run(hl_sounder_t *s, base_t *b, int max_sips)
{
    hl_sounder_start(s);
    for (int i = 0; i < max_sips; i++) {
        hl_sounder_sip_t sip;
        sip_of(b, &sip);
        int32_t head = -1;
        hl_sounder_cmd_t cmd = hl_sounder_on_sip(s, &sip, &head);
        if (cmd == HL_SOUNDER_CMD_HEAD) {
            assert_in_range(head, 0, 359);
            b->target = (hl_bam_t)(head * 65536 / 360);
            b->n_turns++;
        }
        if (hl_sounder_state(s) != HL_SOUNDER_BUSY)
            return i + 1;
    }
    return max_sips;
}

static void setup(hl_sounder_t *s, const char *profile_name)
{
    hl_sounder_params_t p;
    hl_sounder_params_default(&p);
    p.calib.min_raw = 0;
    hl_robot_profile_t prof;
    assert_int_equal(hl_robot_profile_find(profile_name, &prof), HL_OK);
    assert_int_equal(hl_sounder_init(s, &p, &prof), HL_OK);
}

static void test_a_sounding_is_128_readings_at_measured_bearings(void **state)
{
    (void)state;
    hl_sounder_t s;
    setup(&s, "bonnie");
    base_t b = { .heading = 100, .target = 100, .fire_every = 2 };
    run(&s, &b, 1000);
    assert_int_equal(hl_sounder_state(&s), HL_SOUNDER_DONE);
    assert_int_equal(b.n_turns, 7);
    static hl_scan_t scan;
    hl_pose_t odo;
    assert_int_equal(hl_sounder_take(&s, &scan, &odo), HL_OK);
    assert_int_equal(hl_sounder_state(&s), HL_SOUNDER_IDLE);
    assert_int_equal(scan.count, 128);
    assert_int_equal(odo.x_mm, 1000);
    assert_int_equal(odo.theta, b.heading);
    /* every reading: its transducer's bearing plus the turn from its step to the last;
     * the range (gain 1) tells which step heading it was taken at */
    for (uint32_t i = 0; i < scan.count; i++) {
        const hl_reading_t *r = &scan.readings[i];
        assert_true(r->valid);
        int t = r->transducer;
        hl_bam_t step_heading = (hl_bam_t)(r->bearing - t * 4096 + odo.theta);
        assert_int_equal(r->range_mm, raw_of(step_heading, t));
        if (i > 0)
            assert_true(r->bearing >= scan.readings[i - 1].bearing);
    }
    /* the steps cover 7 x 2.8125 deg = 19.7 deg, each aimed at a whole degree */
    int32_t swept = hl_bam_diff(odo.theta, 100);
    assert_in_range(swept, 3584 - 182, 3584 + 182);
}

static void test_a_deaf_transducer_fails_the_sounding_with_a_reason(void **state)
{
    (void)state;
    hl_sounder_t s;
    setup(&s, "bonnie");
    base_t b = { .fire_every = 1, .deaf = true };
    run(&s, &b, 1000);
    assert_int_equal(hl_sounder_state(&s), HL_SOUNDER_FAILED);
    assert_non_null(strstr(hl_sounder_why(&s), "position 1 of 8"));
    assert_non_null(strstr(hl_sounder_why(&s), "1 transducers gave no reading"));
    static hl_scan_t scan;
    hl_pose_t odo;
    assert_int_equal(hl_sounder_take(&s, &scan, &odo), HL_ERR_EMPTY);
}

static void test_readings_taken_while_moving_do_not_count(void **state)
{
    (void)state;
    hl_sounder_t s;
    setup(&s, "bonnie");
    /* the base is still turning to an old command when the sounding starts: nothing
     * is read until it has come to rest for settle_ms */
    base_t b = { .heading = 0, .target = 16384, .fire_every = 1 };
    int sips = run(&s, &b, 1000);
    assert_int_equal(hl_sounder_state(&s), HL_SOUNDER_DONE);
    /* 2 s of turning, then 8 positions of at least settle + one SIP each */
    assert_true(sips >= 20 + 8 * 4);
    static hl_scan_t scan;
    hl_pose_t odo;
    assert_int_equal(hl_sounder_take(&s, &scan, &odo), HL_OK);
    for (uint32_t i = 0; i < scan.count; i++) {
        hl_bam_t step_heading = (hl_bam_t)(scan.readings[i].bearing -
                                           scan.readings[i].transducer * 4096 + odo.theta);
        assert_true(hl_bam_diff(step_heading, 16384) >= 0);   /* after the old turn */
    }
}

static void test_profiles_and_parameters(void **state)
{
    (void)state;
    hl_robot_profile_t p;
    assert_int_equal(hl_robot_profile_find("pioneer3", &p), HL_OK);
    assert_int_equal(p.transducers, 16);
    assert_int_equal(p.bearing[0], 16384);          /* 90 deg: the left side */
    assert_int_equal(p.bearing[3], 10 * 65536 / 360);
    assert_int_equal(p.bearing[11], (hl_bam_t)(-170 * 65536 / 360));
    assert_int_equal(hl_robot_profile_find("roomba", &p), HL_ERR_ARG);
    assert_int_equal(hl_robot_profile_find(NULL, &p), HL_ERR_ARG);

    hl_sounder_params_t sp;
    hl_sounder_params_default(&sp);
    assert_null(hl_sounder_params_error(&sp));
    sp.steps = 0;
    assert_non_null(hl_sounder_params_error(&sp));
    sp.steps = 33;
    assert_non_null(hl_sounder_params_error(&sp));
    hl_sounder_params_default(&sp);
    sp.calib.gain_q16 = 0;
    assert_non_null(hl_sounder_params_error(&sp));
    hl_sounder_t s;
    assert_int_equal(hl_sounder_init(&s, &sp, &p), HL_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_sounding_is_128_readings_at_measured_bearings),
        cmocka_unit_test(test_a_deaf_transducer_fails_the_sounding_with_a_reason),
        cmocka_unit_test(test_readings_taken_while_moving_do_not_count),
        cmocka_unit_test(test_profiles_and_parameters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
