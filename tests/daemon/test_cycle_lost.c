/* test_cycle_lost.c - the LOST state (cycle_lost.c): a kidnapped robot is noticed after a
 * run of rejected scans, found by the global search and confirmed by the next scan; a
 * RELOCALIZE command does the same on demand; SET_POSE ends it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "support.h"

typedef struct run {
    capture_t cap;
    hl_cycle_t *c;
    hl_bus_scan_t scan;         /* decode scratch */
    uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
} run_t;

static run_t *start(int32_t lost_after)
{
    run_t *r = calloc(1, sizeof *r);
    hl_cycle_params_t p = test_params();
    char v[16];
    snprintf(v, sizeof v, "%d", lost_after);
    assert_int_equal(hl_params_set(&p.params, "slam.lost_after", v), HL_OK);
    r->c = capture_cycle(&r->cap, &p);
    assert_non_null(r->c);
    return r;
}

static void finish(run_t *r)
{
    hl_cycle_destroy(r->c);
    capture_clear(&r->cap);
    free(r);
}

static hl_bus_pose_t nth_pose(const run_t *r, size_t k)
{
    const out_msg_t *m = capture_nth(&r->cap, HL_CH_POSE, k);
    assert_non_null(m);
    hl_bus_pose_t p;
    assert_int_equal(hl_bus_decode_pose(m->data, m->len, &p, NULL), HL_OK);
    return p;
}

/* The index in tour[] of the k-th SONAR message. */
static size_t sonar_event(size_t k)
{
    for (size_t i = 0; i < n_tour; i++)
        if (tour[i].ch == HL_CH_SONAR && k-- == 0)
            return i;
    fail_msg("the tour has fewer scans");
    return 0;
}

static hl_bus_scan_t decode_scan(size_t k)
{
    hl_bus_scan_t s;
    const event_t *e = &tour[sonar_event(k)];
    assert_int_equal(hl_bus_decode_scan(e->data, e->len, &s, NULL), HL_OK);
    return s;
}

/* Feeds the tour's scan @p k again as scan @p seq at @p utime, its odometry replaced by
 * @p odometry: the sounding of one place while the wheels say another. */
static void feed_as(run_t *r, size_t k, int32_t seq, int64_t utime, hl_pose_t odometry)
{
    r->scan = decode_scan(k);
    r->scan.seq = seq;
    r->scan.utime = utime;
    r->scan.odometry = odometry;
    int len = hl_bus_encode_scan(&r->scan, r->buf, sizeof r->buf);
    assert_true(len > 0);
    hl_cycle_on_message(r->c, HL_CH_SONAR, r->buf, (size_t)len, utime);
}

static int64_t dist_mm(hl_pose_t a, hl_pose_t b)
{
    double dx = a.x_mm - b.x_mm, dy = a.y_mm - b.y_mm;
    return (int64_t)sqrt(dx * dx + dy * dy);
}

/* STATUS counts every scan by what became of it: its counters, one per POSE status, add
 * up to its scans and agree with the POSE stream. */
static void assert_counts_match_poses(run_t *r)
{
    int32_t by_status[5] = { 0 };
    size_t n = capture_count(&r->cap, HL_CH_POSE);
    for (size_t k = 0; k < n; k++) {
        hl_bus_pose_t p = nth_pose(r, k);
        assert_in_range(p.status, 0, 4);
        by_status[p.status]++;
    }
    hl_cycle_tick(r->c, 0);
    const out_msg_t *m = capture_nth(&r->cap, HL_CH_STATUS, capture_count(&r->cap, HL_CH_STATUS) - 1);
    hl_bus_status_t s;
    assert_int_equal(hl_bus_decode_status(m->data, m->len, &s, NULL), HL_OK);
    assert_int_equal(s.scans, (int32_t)n);
    assert_int_equal(s.accepted, by_status[HL_BUS_POSE_ACCEPTED]);
    assert_int_equal(s.rejected_wild, by_status[HL_BUS_POSE_REJECTED_WILD]);
    assert_int_equal(s.odometry_only, by_status[HL_BUS_POSE_ODOMETRY_ONLY]);
    assert_int_equal(s.relocalized, by_status[HL_BUS_POSE_RELOCALIZED]);
    assert_int_equal(s.lost, by_status[HL_BUS_POSE_LOST]);
    assert_true(s.relocalized >= 1);
    assert_int_equal(s.accepted + s.rejected_wild + s.odometry_only + s.relocalized + s.lost,
                     s.scans);
}

/* The robot, at the end of the tour, is carried back to where scan 100 was sounded; its
 * odometry goes on from the tour's last reading. */
static void test_kidnapped_robot_is_found_again(void **state)
{
    (void)state;
    run_t *r = start(2);
    load_tour();
    feed_tour(r->c, 128);
    size_t before = capture_count(&r->cap, HL_CH_POSE);
    assert_int_equal(before, 128);
    hl_bus_pose_t end = nth_pose(r, 127);
    assert_false(hl_cycle_lost(r->c));

    hl_bus_scan_t last = decode_scan(127), from = decode_scan(100);
    int64_t t = last.utime;
    int lost_at = -1, found_at = -1, tracking_at = -1;
    for (int i = 0; i < 12 && tracking_at < 0; i++) {
        hl_bus_scan_t here = decode_scan(100 + (size_t)i);
        hl_pose_t odo = hl_pose_compose(last.odometry, hl_pose_between(from.odometry, here.odometry));
        t += 5000000;
        feed_as(r, 100 + (size_t)i, last.seq + 1 + i, t, odo);
        hl_bus_pose_t out = nth_pose(r, before + (size_t)i);
        hl_bus_pose_t tour_pose = nth_pose(r, 100 + (size_t)i);
        if (hl_cycle_lost(r->c) && lost_at < 0)
            lost_at = i;
        if (out.status == HL_BUS_POSE_RELOCALIZED && found_at < 0) {
            found_at = i;
            /* found where the tour had been, and said so with the search's figures */
            assert_true(dist_mm(out.pose, tour_pose.pose) < 300);
            assert_true(out.search_score > 0.3f && out.search_score <= 1.0f);
            assert_true(out.runner_up_score < out.search_score);
            assert_true(out.confidence > 0.0f);
        }
        if (found_at >= 0 && out.status == HL_BUS_POSE_ACCEPTED) {
            tracking_at = i;
            assert_true(dist_mm(out.pose, tour_pose.pose) < 300);
        }
    }
    print_message("kidnap: lost at %d, found at %d, tracking at %d (from %lld mm away)\n",
                  lost_at, found_at, tracking_at, (long long)dist_mm(end.pose, nth_pose(r, 100).pose));
    assert_true(dist_mm(end.pose, nth_pose(r, 100).pose) > 2000);
    assert_in_range(lost_at, 0, 3);
    assert_in_range(found_at, lost_at, lost_at + 2);
    assert_int_equal(tracking_at, found_at + 1);
    assert_false(hl_cycle_lost(r->c));
    assert_counts_match_poses(r);
    finish(r);
}

/* What the last SONAR handled published, from capture message @p from on: its POSE
 * first, and any STATUS (the state it caused) after it. @return the STATUS count. */
static int assert_pose_first(const run_t *r, size_t from)
{
    int statuses = 0;
    bool posed = false;
    for (size_t i = from; i < r->cap.n; i++) {
        hl_chan_t ch = r->cap.msgs[i].ch;
        if (ch == HL_CH_STATUS) {
            assert_true(posed);     /* a STATUS before the POSE of its scan */
            statuses++;
        }
        if (ch == HL_CH_POSE) {
            assert_false(posed);    /* one POSE a scan */
            posed = true;
        }
    }
    assert_true(posed);
    return statuses;
}

/* The kidnap again, scan by scan: each scan's POSE goes out before the STATUS of the state
 * it causes (LOST when the scan made the daemon lost, LOCALIZING when it found the robot
 * again), and that STATUS says the state the scan left. */
static void test_pose_before_status(void **state)
{
    (void)state;
    run_t *r = start(2);
    load_tour();
    feed_tour(r->c, 128);
    hl_bus_scan_t last = decode_scan(127), from = decode_scan(100);
    int64_t t = last.utime;
    int changes = 0;
    for (int i = 0; i < 12; i++) {
        hl_bus_scan_t here = decode_scan(100 + (size_t)i);
        hl_pose_t odo = hl_pose_compose(last.odometry, hl_pose_between(from.odometry, here.odometry));
        t += 5000000;
        size_t before = r->cap.n;
        bool was_lost = hl_cycle_lost(r->c);
        feed_as(r, 100 + (size_t)i, last.seq + 1 + i, t, odo);
        int statuses = assert_pose_first(r, before);
        if (was_lost != hl_cycle_lost(r->c)) {
            /* the state changed with this scan: one STATUS says so, after the POSE */
            assert_int_equal(statuses, 1);
            hl_bus_status_t st;
            const out_msg_t *m = &r->cap.msgs[r->cap.n - 1];
            assert_int_equal(m->ch, HL_CH_STATUS);
            assert_int_equal(hl_bus_decode_status(m->data, m->len, &st, NULL), HL_OK);
            assert_int_equal(st.state, hl_cycle_lost(r->c) ? HL_BUS_STATE_LOST
                                                           : HL_BUS_STATE_LOCALIZING);
            changes++;
        }
    }
    assert_true(changes >= 2);      /* lost, and found again */
    assert_false(hl_cycle_lost(r->c));
    finish(r);
}

/* RELOCALIZE while tracking well: lost; the next scan's global search puts the robot where
 * tracking does, which ends it at once. */
static void test_relocalize_command(void **state)
{
    (void)state;
    run_t *r = start(2);
    load_tour();
    feed_tour(r->c, 120);
    hl_bus_command_t cmd = { .utime = 1, .seq = 5, .kind = HL_BUS_COMMAND_RELOCALIZE };
    uint8_t buf[HL_BUS_COMMAND_BYTES];
    int len = hl_bus_encode_command(&cmd, buf, sizeof buf);
    assert_true(len > 0);
    hl_cycle_on_message(r->c, HL_CH_COMMAND, buf, (size_t)len, 0);
    assert_true(hl_cycle_lost(r->c));
    uint32_t epoch = hl_cycle_lost_epoch(r->c);
    assert_true(epoch >= 1);
    /* the next scans of the tour */
    size_t n0 = capture_count(&r->cap, HL_CH_POSE);
    load_tour();
    size_t scans = 0;
    for (size_t i = 0; i < n_tour && scans < 123; i++) {
        if (tour[i].ch == HL_CH_SONAR && scans++ < 120)
            continue;
        if (scans <= 120)
            continue;
        hl_cycle_on_message(r->c, tour[i].ch, tour[i].data, tour[i].len, tour[i].utime);
    }
    assert_int_equal(nth_pose(r, n0).status, HL_BUS_POSE_ACCEPTED);
    assert_false(hl_cycle_lost(r->c));
    assert_int_equal(nth_pose(r, n0 + 1).status, HL_BUS_POSE_ACCEPTED);
    assert_int_equal(hl_cycle_lost_epoch(r->c), epoch);
    finish(r);
}

/* With the automatic entry off (lost_after 0, the default), RELOCALIZE still makes the
 * daemon lost, and a scan the search cannot place (no valid reading) neither ends the
 * lost state nor is published ACCEPTED. */
static void test_relocalize_with_automatic_entry_off(void **state)
{
    (void)state;
    run_t *r = start(0);
    load_tour();
    feed_tour(r->c, 40);
    hl_bus_command_t cmd = { .utime = 1, .seq = 7, .kind = HL_BUS_COMMAND_RELOCALIZE };
    uint8_t buf[HL_BUS_COMMAND_BYTES];
    int len = hl_bus_encode_command(&cmd, buf, sizeof buf);
    assert_true(len > 0);
    hl_cycle_on_message(r->c, HL_CH_COMMAND, buf, (size_t)len, 0);
    assert_true(hl_cycle_lost(r->c));
    size_t n0 = capture_count(&r->cap, HL_CH_POSE);
    hl_bus_scan_t last = decode_scan(39);
    r->scan = decode_scan(40);
    for (uint32_t i = 0; i < r->scan.scan.count; i++)
        r->scan.scan.readings[i].valid = false;
    r->scan.seq = last.seq + 1;
    r->scan.utime = last.utime + 1000000;
    r->scan.odometry = last.odometry;
    len = hl_bus_encode_scan(&r->scan, r->buf, sizeof r->buf);
    assert_true(len > 0);
    hl_cycle_on_message(r->c, HL_CH_SONAR, r->buf, (size_t)len, r->scan.utime);
    assert_int_equal(nth_pose(r, n0).status, HL_BUS_POSE_LOST);
    assert_true(hl_cycle_lost(r->c));
    finish(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kidnapped_robot_is_found_again),
        cmocka_unit_test(test_pose_before_status),
        cmocka_unit_test(test_relocalize_command),
        cmocka_unit_test(test_relocalize_with_automatic_entry_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
