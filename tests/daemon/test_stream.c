/* test_stream.c - sensor streams from the network cannot be poisoned (stream.h): a lone
 * outlier is dropped, a restarted source or a stepped clock is followed after
 * HL_STREAM_CONFIRM messages, and through the cycle no message stops localization. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "stream.h"
#include "support.h"

#include <houghloc/bus.h>

static hl_stream_mark_t mark(int64_t seq, int64_t utime)
{
    return (hl_stream_mark_t){ seq, utime };
}

static void test_in_order_is_taken(void **state)
{
    (void)state;
    hl_stream_t s;
    hl_stream_init(&s, true);
    assert_int_equal(hl_stream_offer(&s, mark(5, 1000)), HL_STREAM_TAKE);
    assert_int_equal(hl_stream_offer(&s, mark(6, 2000)), HL_STREAM_TAKE);
    /* a gap of lost scans is still in order */
    assert_int_equal(hl_stream_offer(&s, mark(6 + HL_STREAM_MAX_SEQ_STEP, 3000)), HL_STREAM_TAKE);
    assert_int_equal(s.last.seq, 6 + HL_STREAM_MAX_SEQ_STEP);
}

/* One message far ahead is dropped, and the real stream goes on as if it never came. */
static void test_lone_outlier_is_dropped(void **state)
{
    (void)state;
    const hl_stream_mark_t poison[] = {
        mark(INT32_MAX, INT64_MAX), mark(20, INT64_MAX), mark(INT32_MAX, 3000),
        mark(11 + HL_STREAM_MAX_SEQ_STEP, 3000),
        mark(11, 2000 + HL_STREAM_MAX_TIME_STEP_US + 1),
        mark(10, 2000),             /* a repeat */
        mark(9, 1000),              /* behind */
        mark(INT32_MIN, INT64_MIN),
    };
    for (size_t k = 0; k < sizeof poison / sizeof poison[0]; k++) {
        hl_stream_t s;
        hl_stream_init(&s, true);
        assert_int_equal(hl_stream_offer(&s, mark(10, 2000)), HL_STREAM_TAKE);
        assert_int_equal(hl_stream_offer(&s, poison[k]), HL_STREAM_HOLD);
        for (int64_t i = 11; i < 20; i++)
            assert_int_equal(hl_stream_offer(&s, mark(i, 2000 + (i - 10) * 1000)),
                             HL_STREAM_TAKE);
        /* the same outlier again, once the stream has gone on: still held, alone */
        assert_int_equal(hl_stream_offer(&s, poison[k]), HL_STREAM_HOLD);
        assert_int_equal(hl_stream_offer(&s, mark(20, 20000)), HL_STREAM_TAKE);
    }
}

/* A publisher restarted (seq from 0) or a clock stepped back: HL_STREAM_CONFIRM - 1
 * messages held, then the stream follows the new one. */
static void test_restart_resynchronizes(void **state)
{
    (void)state;
    hl_stream_t s;
    hl_stream_init(&s, true);
    for (int64_t i = 100; i < 110; i++)
        assert_int_equal(hl_stream_offer(&s, mark(i, i * 1000000)), HL_STREAM_TAKE);
    for (int k = 1; k < HL_STREAM_CONFIRM; k++)
        assert_int_equal(hl_stream_offer(&s, mark(k - 1, k * 1000)), HL_STREAM_HOLD);
    assert_int_equal(hl_stream_offer(&s, mark(HL_STREAM_CONFIRM - 1, HL_STREAM_CONFIRM * 1000)),
                     HL_STREAM_RESYNC);
    assert_int_equal(hl_stream_offer(&s, mark(HL_STREAM_CONFIRM, 1000000)), HL_STREAM_TAKE);

    /* a clock stepped forward by a day, sequence numbers going on */
    hl_stream_t o;
    hl_stream_init(&o, false);      /* ODOMETRY: time only */
    const int64_t day = 86400LL * 1000000;
    assert_int_equal(hl_stream_offer(&o, mark(0, 5000)), HL_STREAM_TAKE);
    assert_int_equal(hl_stream_offer(&o, mark(0, day)), HL_STREAM_HOLD);
    assert_int_equal(hl_stream_offer(&o, mark(0, day + 100000)), HL_STREAM_HOLD);
    assert_int_equal(hl_stream_offer(&o, mark(0, day + 200000)), HL_STREAM_RESYNC);
    assert_int_equal(o.last.utime, day + 200000);
}

/* Outliers that do not follow one another never take the stream over, and a message in
 * order between them clears the run. */
static void test_scattered_outliers_never_resync(void **state)
{
    (void)state;
    hl_stream_t s;
    hl_stream_init(&s, true);
    assert_int_equal(hl_stream_offer(&s, mark(1, 1000)), HL_STREAM_TAKE);
    for (int k = 0; k < 1000; k++) {
        /* behind the stream and each behind the one before: no run */
        assert_int_equal(hl_stream_offer(&s, mark(-(int64_t)k, -(int64_t)k * 1000)),
                         HL_STREAM_HOLD);
    }
    /* a run of two, then the real stream: the run is gone, a third does not complete it */
    assert_int_equal(hl_stream_offer(&s, mark(5000, 900000000000)), HL_STREAM_HOLD);
    assert_int_equal(hl_stream_offer(&s, mark(5001, 900001000000)), HL_STREAM_HOLD);
    assert_int_equal(hl_stream_offer(&s, mark(2, 2000)), HL_STREAM_TAKE);
    assert_int_equal(hl_stream_offer(&s, mark(5002, 900002000000)), HL_STREAM_HOLD);
    assert_int_equal(s.last.seq, 2);
}

/* ---- through the cycle -------------------------------------------------------------- */

/* The tour's SONAR @p e re-encoded with another seq and utime. */
static size_t reseq_scan(const event_t *e, int32_t seq, int64_t utime, uint8_t *buf, size_t cap)
{
    static hl_bus_scan_t s;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_scan(e->data, e->len, &s, why), HL_OK);
    s.seq = seq;
    s.utime = utime;
    int len = hl_bus_encode_scan(&s, buf, cap);
    assert_true(len > 0);
    return (size_t)len;
}

static size_t retime_odometry(const event_t *e, int64_t utime, uint8_t *buf, size_t cap)
{
    hl_bus_odometry_t o;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_odometry(e->data, e->len, &o, why), HL_OK);
    o.utime = utime;
    int len = hl_bus_encode_odometry(&o, buf, cap);
    assert_true(len > 0);
    return (size_t)len;
}

/* One SONAR with a huge seq and utime and one ODOMETRY at 2^63 - 1, sent before the
 * second scan: every real scan is still answered, pose for pose as without them. */
static void test_cycle_drops_poison(void **state)
{
    (void)state;
    enum { SCANS = 12 };
    static uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
    capture_t *clean = calloc(1, sizeof *clean), *dirty = calloc(1, sizeof *dirty);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *a = capture_cycle(clean, &p), *b = capture_cycle(dirty, &p);
    feed_tour(a, SCANS);
    load_tour();
    size_t scans = 0;
    bool poisoned = false;
    for (size_t i = 0; i < n_tour && scans < SCANS; i++) {
        const event_t *e = &tour[i];
        if (scans == 1 && !poisoned && e->ch == HL_CH_SONAR) {
            size_t n = reseq_scan(e, INT32_MAX - 5, INT64_MAX / 2, buf, sizeof buf);
            hl_cycle_on_message(b, HL_CH_SONAR, buf, n, e->utime);
            for (size_t j = i; j < n_tour; j++)
                if (tour[j].ch == HL_CH_ODOMETRY) {
                    n = retime_odometry(&tour[j], INT64_MAX, buf, sizeof buf);
                    hl_cycle_on_message(b, HL_CH_ODOMETRY, buf, n, e->utime);
                    break;
                }
            poisoned = true;
        }
        hl_cycle_on_message(b, e->ch, e->data, e->len, e->utime);
        scans += e->ch == HL_CH_SONAR;
    }
    assert_true(poisoned);
    assert_int_equal(capture_count(clean, HL_CH_POSE), SCANS);
    assert_int_equal(capture_count(dirty, HL_CH_POSE), SCANS);
    for (size_t i = 0; i < SCANS; i++) {
        const out_msg_t *u = capture_nth(clean, HL_CH_POSE, i), *v = capture_nth(dirty, HL_CH_POSE, i);
        assert_int_equal(u->len, v->len);
        assert_memory_equal(u->data, v->data, u->len);
    }
    assert_int_equal(hl_cycle_counts(b)->bad_messages, 2);
    hl_cycle_destroy(a);
    hl_cycle_destroy(b);
    capture_clear(clean);
    capture_clear(dirty);
    free(clean);
    free(dirty);
}

/* The SONAR publisher restarts (seq from 0, its clock an hour and more behind): at most
 * HL_STREAM_CONFIRM - 1 of its scans go unanswered, then every one is localized again. */
static void test_cycle_follows_restarted_source(void **state)
{
    (void)state;
    enum { BEFORE = 6, AFTER = 10 };
    static uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    load_tour();
    size_t scans = 0;
    const int64_t back = 7200LL * 1000000;     /* two hours */
    for (size_t i = 0; i < n_tour && scans < BEFORE + AFTER; i++) {
        const event_t *e = &tour[i];
        if (e->ch == HL_CH_SONAR && scans >= BEFORE) {
            hl_bus_scan_t *tmp = calloc(1, sizeof *tmp);
            char why[HL_BUS_WHY_LEN];
            assert_int_equal(hl_bus_decode_scan(e->data, e->len, tmp, why), HL_OK);
            size_t n = reseq_scan(e, (int32_t)(scans - BEFORE), tmp->utime - back, buf,
                                  sizeof buf);
            free(tmp);
            hl_cycle_on_message(c, HL_CH_SONAR, buf, n, e->utime);
        } else if (e->ch == HL_CH_ODOMETRY && scans >= BEFORE) {
            hl_bus_odometry_t o;
            char why[HL_BUS_WHY_LEN];
            assert_int_equal(hl_bus_decode_odometry(e->data, e->len, &o, why), HL_OK);
            size_t n = retime_odometry(e, o.utime - back, buf, sizeof buf);
            hl_cycle_on_message(c, HL_CH_ODOMETRY, buf, n, e->utime);
        } else {
            hl_cycle_on_message(c, e->ch, e->data, e->len, e->utime);
        }
        scans += e->ch == HL_CH_SONAR;
    }
    size_t poses = capture_count(cap, HL_CH_POSE);
    assert_int_equal(poses, BEFORE + AFTER - (HL_STREAM_CONFIRM - 1));
    /* the last POSE is the last scan's, on the new clock */
    const out_msg_t *m = capture_nth(cap, HL_CH_POSE, poses - 1);
    hl_bus_pose_t pose;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_pose(m->data, m->len, &pose, why), HL_OK);
    assert_int_equal(pose.scan_seq, AFTER - 1);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_in_order_is_taken),
        cmocka_unit_test(test_lone_outlier_is_dropped),
        cmocka_unit_test(test_restart_resynchronizes),
        cmocka_unit_test(test_scattered_outliers_never_resync),
        cmocka_unit_test(test_cycle_drops_poison),
        cmocka_unit_test(test_cycle_follows_restarted_source),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
