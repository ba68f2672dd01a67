/* test_cycle_map.c - MAP's rate (src/daemon/cycle_map.c): the bound in message time and
 * the bound in bytes (daemon.map_input_ratio), driven by the tour with a fake clock. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "support.h"

static hl_bus_map_t decode_map(const out_msg_t *m, hl_vector_t *storage)
{
    hl_bus_map_t out = { .max_vectors = HL_MAP_MAX_CAPACITY, .vectors = storage };
    assert_non_null(m);
    assert_int_equal(hl_bus_decode_map(m->data, m->len, &out, NULL), HL_OK);
    return out;
}

static uint64_t map_version(hl_cycle_t *c)
{
    return hl_map_version(hl_slam_map(hl_cycle_slam(c)));
}

/* After the first MAP, each one is paid for by the SONAR and ODOMETRY bytes taken since
 * the one before, at map_input_ratio; and it goes out at the first scan that pays for
 * it: a changed map is never held back longer than the rule says. */
static void test_input_bytes_pay_for_each_map(void **state)
{
    (void)state;
    const int32_t ratio = 4;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = ratio;      /* and map_period_ms = 0: only the bytes bound */
    hl_cycle_t *c = capture_cycle(cap, &p);
    assert_non_null(c);
    load_tour();
    int64_t since = 0, input = 0, later_bytes = 0;
    size_t maps = 0, scans = 0, held = 0;
    uint64_t published = map_version(c);
    for (size_t i = 0; i < n_tour && scans < 40; i++) {
        const event_t *e = &tour[i];
        hl_cycle_on_message(c, e->ch, e->data, e->len, e->utime);
        since += (int64_t)e->len;
        input += (int64_t)e->len;
        scans += e->ch == HL_CH_SONAR;
        size_t now = capture_count(cap, HL_CH_MAP);
        if (now > maps) {
            assert_int_equal(now, maps + 1);        /* at most one per message */
            assert_int_equal(e->ch, HL_CH_SONAR);   /* only a scan changes the map */
            const out_msg_t *m = capture_nth(cap, HL_CH_MAP, maps);
            if (maps > 0) {
                assert_true(since * ratio >= (int64_t)m->len);
                later_bytes += (int64_t)m->len;
            }
            published = map_version(c);
            since = 0;
            maps = now;
        } else if (e->ch == HL_CH_SONAR && map_version(c) != published) {
            /* a changed map held back: its size was not paid for yet */
            size_t size = hl_bus_map_bytes(hl_map_count(hl_slam_map(hl_cycle_slam(c))));
            assert_true(since * ratio < (int64_t)size);
            held++;
        }
    }
    assert_int_equal(scans, 40);
    assert_true(maps >= 5);         /* the bound spaces maps out, it does not stop them */
    assert_true(held >= 10);        /* ... and it did hold some back */
    assert_true(maps + held >= 39);
    assert_true(later_bytes <= ratio * input);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* map_input_ratio 0: no bound in bytes, every change goes out (map_period_ms 0). */
static void test_ratio_zero_sends_every_change(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    load_tour();
    size_t scans = 0, changes = 0;
    for (size_t i = 0; i < n_tour && scans < 20; i++) {
        uint64_t before = map_version(c);
        hl_cycle_on_message(c, tour[i].ch, tour[i].data, tour[i].len, tour[i].utime);
        scans += tour[i].ch == HL_CH_SONAR;
        changes += map_version(c) != before;
    }
    assert_true(changes >= 19);
    assert_int_equal(capture_count(cap, HL_CH_MAP), changes);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* Both bounds hold: an allowance in bytes does not lift map_period_ms. */
static void test_period_still_bounds(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = HL_CYCLE_MAP_RATIO_MAX;
    p.map_period_ms = 3600000;      /* an hour of message time: only the first */
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 15);
    assert_int_equal(capture_count(cap, HL_CH_MAP), 1);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* Bytes that are not taken (garbage, truncated, replayed or out-of-order messages) buy
 * no MAP: the MAP stream is the clean input's, byte for byte. */
static void test_refused_input_buys_nothing(void **state)
{
    (void)state;
    capture_t *clean = calloc(1, sizeof *clean), *dirty = calloc(1, sizeof *dirty);
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = 2;
    hl_cycle_t *a = capture_cycle(clean, &p), *b = capture_cycle(dirty, &p);
    feed_tour(a, 30);
    uint32_t x = 777;
    uint8_t junk[900];
    size_t scans = 0;
    for (size_t i = 0; i < n_tour && scans < 30; i++) {
        const event_t *e = &tour[i];
        hl_cycle_on_message(b, e->ch, e->data, e->len, e->utime);
        scans += e->ch == HL_CH_SONAR;
        for (size_t k = 0; k < sizeof junk; k++)
            junk[k] = (uint8_t)((x = x * 1103515245u + 12345u) >> 16);
        hl_cycle_on_message(b, e->ch, junk, sizeof junk, e->utime);        /* garbage */
        hl_cycle_on_message(b, e->ch, e->data, e->len - 1, e->utime);      /* truncated */
        hl_cycle_on_message(b, e->ch, e->data, e->len, e->utime);          /* a replay */
    }
    size_t n = capture_count(clean, HL_CH_MAP);
    assert_true(n >= 3);
    assert_int_equal(capture_count(dirty, HL_CH_MAP), n);
    for (size_t i = 0; i < n; i++) {
        const out_msg_t *u = capture_nth(clean, HL_CH_MAP, i), *v = capture_nth(dirty, HL_CH_MAP, i);
        assert_int_equal(u->len, v->len);
        assert_memory_equal(u->data, v->data, u->len);
    }
    assert_true(hl_cycle_counts(b)->bad_messages > 0);
    hl_cycle_destroy(a);
    hl_cycle_destroy(b);
    capture_clear(clean);
    capture_clear(dirty);
    free(clean);
    free(dirty);
}

/* The flush at the end sends the final map whatever the bounds held back, so a log's
 * last MAP is the map the run ended with; with nothing new it sends nothing. */
static void test_flush_sends_the_final_map(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = 1;          /* a full map costs several scans of input */
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 25);
    size_t n = capture_count(cap, HL_CH_MAP);
    hl_vector_t *v = malloc(HL_MAP_MAX_CAPACITY * sizeof *v);
    hl_bus_map_t last = decode_map(capture_nth(cap, HL_CH_MAP, n - 1), v);
    assert_int_not_equal(last.version, map_version(c));   /* held back */
    hl_cycle_flush_map(c);
    assert_int_equal(capture_count(cap, HL_CH_MAP), n + 1);
    last = decode_map(capture_nth(cap, HL_CH_MAP, n), v);
    const hl_map_t *map = hl_slam_map(hl_cycle_slam(c));
    assert_int_equal(last.version, hl_map_version(map));
    assert_int_equal(last.count, hl_map_count(map));
    assert_memory_equal(last.vectors, hl_map_vectors(map), last.count * sizeof *v);
    hl_cycle_flush_map(c);
    assert_int_equal(capture_count(cap, HL_CH_MAP), n + 1);
    free(v);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* The same input gives the same MAP stream, whatever the clock says. */
static void test_bounded_stream_is_deterministic(void **state)
{
    (void)state;
    capture_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    b->clock_step_us = 913;
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = 3;
    p.map_period_ms = 5000;
    hl_cycle_t *ca = capture_cycle(a, &p), *cb = capture_cycle(b, &p);
    feed_tour(ca, 30);
    feed_tour(cb, 30);
    size_t n = capture_count(a, HL_CH_MAP);
    assert_true(n >= 3);
    assert_int_equal(capture_count(b, HL_CH_MAP), n);
    for (size_t i = 0; i < n; i++) {
        const out_msg_t *x = capture_nth(a, HL_CH_MAP, i), *y = capture_nth(b, HL_CH_MAP, i);
        assert_int_equal(x->len, y->len);
        assert_memory_equal(x->data, y->data, x->len);
    }
    hl_cycle_destroy(ca);
    hl_cycle_destroy(cb);
    capture_clear(a);
    capture_clear(b);
    free(a);
    free(b);
}

/* A map file whose last scan is a day ahead of the input that follows a restart (a
 * replay started again, a clock reset): MAP still goes out at the period's pace, not
 * once and then never until the input's clock passes the file's. */
static void test_restart_behind_file_time(void **state)
{
    (void)state;
    capture_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    hl_cycle_params_t p = test_params();
    p.map_period_ms = 1000;
    p.map_input_ratio = 0;
    hl_cycle_t *first = capture_cycle(a, &p);
    feed_tour(first, 5);
    hl_mapfile_t m;
    hl_cycle_snapshot(first, &m);
    m.last_scan_utime += 86400LL * 1000000;
    hl_cycle_t *second = capture_cycle(b, &p);
    assert_int_equal(hl_cycle_restore(second, &m), HL_OK);
    hl_cycle_flush_map(second);     /* the loaded map out at once, at the file's time */
    assert_int_equal(capture_count(b, HL_CH_MAP), 1);
    feed_tour(second, 20);      /* the tour again, from its start: a day behind the file */
    size_t maps = capture_count(b, HL_CH_MAP);
    assert_true(maps >= 10);
    /* the last MAP is the map as it stands, and carries the input's time */
    static hl_vector_t storage[HL_MAP_MAX_CAPACITY];
    hl_bus_map_t last = decode_map(capture_nth(b, HL_CH_MAP, maps - 1), storage);
    assert_true(last.utime < m.last_scan_utime - 3600LL * 1000000);
    hl_cycle_destroy(first);
    hl_cycle_destroy(second);
    capture_clear(a);
    capture_clear(b);
    free(a);
    free(b);
}

static void test_ratio_out_of_range_refused(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.map_input_ratio = -1;
    assert_null(capture_cycle(cap, &p));
    p.map_input_ratio = HL_CYCLE_MAP_RATIO_MAX + 1;
    assert_null(capture_cycle(cap, &p));
    p.map_input_ratio = HL_CYCLE_MAP_RATIO_MAX;
    hl_cycle_t *c = capture_cycle(cap, &p);
    assert_non_null(c);
    hl_cycle_destroy(c);
    free(cap);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_input_bytes_pay_for_each_map),
        cmocka_unit_test(test_ratio_zero_sends_every_change),
        cmocka_unit_test(test_period_still_bounds),
        cmocka_unit_test(test_refused_input_buys_nothing),
        cmocka_unit_test(test_flush_sends_the_final_map),
        cmocka_unit_test(test_bounded_stream_is_deterministic),
        cmocka_unit_test(test_restart_behind_file_time),
        cmocka_unit_test(test_ratio_out_of_range_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
