/* Tests for src/robot/drive.c: a fake base that executes HEAD and MOVE exactly, whose
 * map frame is its odometry frame turned and shifted (the localization is perfect). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/drive.h"

#define MAP_FROM_ODOM ((hl_pose_t){ 2000, -1000, 16384 })   /* 90 deg */

typedef struct base {
    hl_pose_t odo;
    hl_bam_t head_target;
    int32_t move_left;      /* mm still to drive */
    bool turning, stall, frozen;
    int64_t t_ms;
    int soundings;
} base_t;

static void obey(base_t *b, const hl_drive_out_t *o)
{
    if (o->cmd == HL_DRIVE_CMD_HEAD) {
        b->head_target = (hl_bam_t)(o->arg * 65536 / 360);
        b->turning = true;
    } else if (o->cmd == HL_DRIVE_CMD_MOVE) {
        b->move_left = o->arg;
    } else if (o->cmd == HL_DRIVE_CMD_STOP) {
        b->turning = false;
        b->move_left = 0;
    }
}

/* 100 ms of robot time: 300 mm/s, 45 deg/s. */
static hl_drive_in_t advance(base_t *b)
{
    b->t_ms += 100;
    bool moving = false;
    if (!b->frozen && !b->stall && b->turning) {
        int32_t off = hl_bam_diff(b->head_target, b->odo.theta), step = 819;
        b->odo.theta = abs(off) <= step ? b->head_target
                                        : (hl_bam_t)(b->odo.theta + (off > 0 ? step : -step));
        b->turning = b->odo.theta != b->head_target;
        moving = true;
    } else if (!b->frozen && !b->stall && b->move_left > 0) {
        int32_t d = b->move_left < 30 ? b->move_left : 30;
        double th = b->odo.theta * 2 * 3.14159265358979323846 / 65536;
        b->odo.x_mm += (int32_t)lround(d * cos(th));
        b->odo.y_mm += (int32_t)lround(d * sin(th));
        b->move_left -= d;
        moving = true;
    }
    return (hl_drive_in_t){ .robot_ms = b->t_ms, .odometry = b->odo,
                            .estimate = hl_pose_compose(MAP_FROM_ODOM, b->odo),
                            .moving = moving, .stalled = b->stall && b->move_left > 0 };
}

/* Drives to (x, y) until the drive ends; @return its phase. */
static hl_drive_phase_t go(hl_drive_t *d, base_t *b, int32_t x, int32_t y, bool has_heading,
                           hl_bam_t heading, int max_sips)
{
    hl_drive_in_t in = advance(b);
    hl_drive_out_t out;
    hl_drive_start(d, x, y, has_heading, heading, &in, &out);
    obey(b, &out);
    for (int i = 0; i < max_sips && hl_drive_phase(d) < HL_DRIVE_ARRIVED; i++) {
        in = advance(b);
        if (hl_drive_phase(d) == HL_DRIVE_SOUND) {
            b->soundings++;
            b->odo.theta = (hl_bam_t)(b->odo.theta + 3584);  /* a sounding turns 19.7 deg */
            in = advance(b);
            hl_drive_localized(d, &in, &out);
        } else {
            hl_drive_on_sip(d, &in, &out);
        }
        obey(b, &out);
    }
    return hl_drive_phase(d);
}

static void setup(hl_drive_t *d)
{
    hl_drive_params_t p;
    hl_drive_params_default(&p);
    assert_int_equal(hl_drive_init(d, &p), HL_OK);
}

static void test_arrives_in_legs_no_longer_than_the_limit(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    /* the goal is 4 m away in the map frame: three legs of at most 1.5 m */
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    int32_t gx = start.x_mm + 4000, gy = start.y_mm;
    assert_int_equal(go(&d, &b, gx, gy, false, 0, 5000), HL_DRIVE_ARRIVED);
    assert_int_equal(d.legs, 3);
    assert_int_equal(b.soundings, 3);
    hl_pose_t end = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    assert_true(hypot(end.x_mm - gx, end.y_mm - gy) <= 150);
}

static void test_final_heading_is_restored_after_the_sounding(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    hl_bam_t want = 49152;  /* 270 deg in the map frame */
    assert_int_equal(go(&d, &b, start.x_mm - 500, start.y_mm + 700, true, want, 5000),
                     HL_DRIVE_ARRIVED);
    hl_pose_t end = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    assert_true(abs(hl_bam_diff(end.theta, want)) <= 182);     /* within a degree */
    assert_int_equal(b.soundings, 2);   /* after the leg, after the first final turn */
}

static void test_a_stall_fails_at_once_and_stops(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { .stall = true };
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    b.stall = false;
    hl_drive_in_t in = advance(&b);
    hl_drive_out_t out;
    hl_drive_start(&d, start.x_mm, start.y_mm + 1000, false, 0, &in, &out);
    obey(&b, &out);
    b.stall = true;         /* the wheels are blocked: the turn never starts */
    for (int i = 0; i < 200 && hl_drive_phase(&d) != HL_DRIVE_FAILED; i++) {
        in = advance(&b);
        in.stalled = true;
        hl_drive_on_sip(&d, &in, &out);
    }
    assert_int_equal(hl_drive_phase(&d), HL_DRIVE_FAILED);
    assert_int_equal(out.cmd, HL_DRIVE_CMD_STOP);
    assert_non_null(strstr(hl_drive_why(&d), "stalled"));
}

static void test_a_base_that_never_stops_times_out(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    hl_drive_in_t in = advance(&b);
    hl_drive_out_t out;
    hl_drive_start(&d, start.x_mm + 1000, start.y_mm, false, 0, &in, &out);
    int sips = 0;
    for (; sips < 2000 && hl_drive_phase(&d) != HL_DRIVE_FAILED; sips++) {
        in = advance(&b);
        in.moving = true;   /* says it moves, forever */
        hl_drive_on_sip(&d, &in, &out);
    }
    assert_int_equal(hl_drive_phase(&d), HL_DRIVE_FAILED);
    assert_non_null(strstr(hl_drive_why(&d), "timed out turning"));
    /* a 90 deg turn at 45 deg/s is 2 s, plus 5 s of slack */
    assert_in_range(sips, 69, 72);
}

static void test_gives_up_after_max_legs(void **state)
{
    (void)state;
    hl_drive_t d;
    hl_drive_params_t p;
    hl_drive_params_default(&p);
    p.max_legs = 2;
    assert_int_equal(hl_drive_init(&d, &p), HL_OK);
    base_t b = { 0 };
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    assert_int_equal(go(&d, &b, start.x_mm, start.y_mm + 5000, false, 0, 5000), HL_DRIVE_FAILED);
    assert_non_null(strstr(hl_drive_why(&d), "after 2 legs"));
    p.max_leg_mm = 5;
    assert_non_null(hl_drive_params_error(&p));
    assert_int_equal(hl_drive_init(&d, &p), HL_ERR_ARG);
}


/* A wall across the way at map x = WALL_X: what the base's front sonar reads while the
 * robot drives east in the map frame (range from the centre, 0 when it faces away). */
#define WALL_X 4000
static int32_t wall_ahead(const hl_drive_in_t *in)
{
    double th = hl_bam_to_rad(in->estimate.theta);
    if (cos(th) < 0.9)
        return 0;
    return (int32_t)lround((WALL_X - in->estimate.x_mm) / cos(th));
}

/* Drives towards (x, y) with the wall's readings fed in; @p via when not NULL aims each
 * leg there (the planner's corner). Records the speeds commanded and the closest the
 * centre came to the wall. */
typedef struct trip {
    int32_t speeds[64];
    int nspeeds;
    int32_t closest;        /* the least WALL_X - x seen */
    int blocked;            /* legs the safety stop ended */
} trip_t;

static hl_drive_phase_t go_to_wall(hl_drive_t *d, base_t *b, int32_t x, int32_t y,
                                   const int32_t *via, trip_t *t, int max_sips)
{
    hl_drive_in_t in = advance(b);
    hl_drive_out_t out;
    t->closest = INT32_MAX;
    if (via)
        hl_drive_set_via(d, via[0], via[1]);
    hl_drive_start(d, x, y, false, 0, &in, &out);
    obey(b, &out);
    for (int i = 0; i < max_sips && hl_drive_phase(d) < HL_DRIVE_ARRIVED; i++) {
        in = advance(b);
        in.ahead_mm = wall_ahead(&in);
        if (WALL_X - in.estimate.x_mm < t->closest)
            t->closest = WALL_X - in.estimate.x_mm;
        if (hl_drive_phase(d) == HL_DRIVE_SOUND) {
            t->blocked += hl_drive_blocked(d, NULL);
            if (via)
                hl_drive_set_via(d, via[0], via[1]);
            hl_drive_localized(d, &in, &out);
        } else {
            hl_drive_on_sip(d, &in, &out);
        }
        if (out.speed_mm_s > 0 && t->nspeeds < 64)
            t->speeds[t->nspeeds++] = out.speed_mm_s;
        obey(b, &out);
    }
    return hl_drive_phase(d);
}

static void test_a_leg_aims_at_the_via_point(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    /* the goal 1 m east; the way first goes 1 m north (a corner round something) */
    int32_t via[2] = { start.x_mm, start.y_mm + 1000 };
    hl_drive_in_t in = advance(&b);
    hl_drive_out_t out;
    hl_drive_set_via(&d, via[0], via[1]);
    hl_drive_start(&d, start.x_mm + 1000, start.y_mm, false, 0, &in, &out);
    assert_int_equal(out.cmd, HL_DRIVE_CMD_HEAD);
    /* north in the map frame is 0 deg in the odometry frame (MAP_FROM_ODOM turns 90) */
    assert_int_equal(out.arg, 0);
    obey(&b, &out);
    for (int i = 0; i < 200 && out.cmd != HL_DRIVE_CMD_MOVE; i++) {
        in = advance(&b);
        hl_drive_on_sip(&d, &in, &out);
    }
    assert_int_equal(out.cmd, HL_DRIVE_CMD_MOVE);
    assert_int_equal(out.arg, 1000);            /* to the via point, not the goal's 1.41 m */
    assert_int_equal(out.speed_mm_s, 300);      /* each leg sets the speed */
    assert_false(d.has_via);                    /* used once */
}

static void test_the_safety_stop_holds_short_of_a_wall_and_fails_blocked(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    b.odo.theta = 49152;    /* facing east in the map frame */
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    assert_int_equal(start.x_mm, 2000);
    /* a goal beyond the wall: the robot stops before it each time and finally fails */
    trip_t t = { 0 };
    assert_int_equal(go_to_wall(&d, &b, WALL_X + 1000, start.y_mm, NULL, &t, 20000),
                     HL_DRIVE_FAILED);
    assert_non_null(strstr(hl_drive_why(&d), "blocked: an obstacle"));
    assert_int_equal(t.blocked, HL_DRIVE_MAX_BLOCKS + 1);
    /* the fake base stops at once (each new leg creeps one packet, 30 mm, before its first
     * reading stops it): the body (radius 250) never touched the wall */
    assert_true(t.closest > 250);
    assert_true(t.closest <= 350);
    /* it slowed before: speeds fell from 300 towards the quarter */
    assert_true(t.nspeeds >= 2);
    assert_int_equal(t.speeds[0], 300);
    int32_t least = 300;
    for (int i = 0; i < t.nspeeds; i++)
        least = t.speeds[i] < least ? t.speeds[i] : least;
    assert_true(least < 150);
    assert_true(least >= 75);
}

static void test_a_goal_short_of_the_wall_is_reached(void **state)
{
    (void)state;
    hl_drive_t d;
    setup(&d);
    base_t b = { 0 };
    b.odo.theta = 49152;
    hl_pose_t start = hl_pose_compose(MAP_FROM_ODOM, b.odo);
    /* 400 mm before the wall: the safety stop ends the last leg within reach of it */
    trip_t t = { 0 };
    assert_int_equal(go_to_wall(&d, &b, WALL_X - 400, start.y_mm, NULL, &t, 20000),
                     HL_DRIVE_ARRIVED);
    assert_true(t.closest >= 320);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_arrives_in_legs_no_longer_than_the_limit),
        cmocka_unit_test(test_final_heading_is_restored_after_the_sounding),
        cmocka_unit_test(test_a_stall_fails_at_once_and_stops),
        cmocka_unit_test(test_a_base_that_never_stops_times_out),
        cmocka_unit_test(test_gives_up_after_max_legs),
        cmocka_unit_test(test_a_leg_aims_at_the_via_point),
        cmocka_unit_test(test_the_safety_stop_holds_short_of_a_wall_and_fails_blocked),
        cmocka_unit_test(test_a_goal_short_of_the_wall_is_reached),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
