/* test_cycle_counts.c - counters past 32 bits: a map version and a STATUS counter taken
 * across 2^31 and 2^32 still go out on MAP and STATUS, and the largest a counter holds
 * (HL_COUNT_MAX) is kept, never wrapped. Driven by the tour with a fake clock. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "cycle_internal.h"     /* to preset a counter near its edge */
#include "support.h"

static hl_vector_t storage[HL_MAP_MAX_CAPACITY];

static hl_bus_map_t map_of(const out_msg_t *m)
{
    hl_bus_map_t out = { .max_vectors = HL_MAP_MAX_CAPACITY, .vectors = storage };
    assert_non_null(m);
    assert_int_equal(hl_bus_decode_map(m->data, m->len, &out, NULL), HL_OK);
    return out;
}

static hl_bus_status_t status_of(const out_msg_t *m)
{
    hl_bus_status_t s;
    assert_non_null(m);
    assert_int_equal(hl_bus_decode_status(m->data, m->len, &s, NULL), HL_OK);
    return s;
}

/* A cycle restored from a map of the tour's first scans whose version is @p version. */
static hl_cycle_t *restored_at(capture_t *cap, uint64_t version)
{
    capture_t *first_cap = calloc(1, sizeof *first_cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *first = capture_cycle(first_cap, &p);
    feed_tour(first, 5);
    hl_mapfile_t m;
    hl_cycle_snapshot(first, &m);
    m.state.map_version = version;
    hl_cycle_t *c = capture_cycle(cap, &p);
    assert_int_equal(hl_cycle_restore(c, &m), HL_OK);
    hl_cycle_destroy(first);
    capture_clear(first_cap);
    free(first_cap);
    return c;
}

/* A map version restored just below 2^31 and just below 2^32 (a map file that lived that
 * long): the scans that follow take it across the edge, and every MAP and STATUS still
 * goes out, each MAP's version above the last. */
static void test_map_version_crosses_32_bit_edges(void **state)
{
    (void)state;
    const uint64_t edges[] = { (UINT64_C(1) << 31) - 2, (UINT64_C(1) << 32) - 2 };
    for (size_t k = 0; k < 2; k++) {
        capture_t *cap = calloc(1, sizeof *cap);
        hl_cycle_t *c = restored_at(cap, edges[k]);
        feed_tour(c, 20);
        hl_cycle_set_state(c, HL_BUS_STATE_LOCALIZING, 0);
        uint64_t now = hl_map_version(hl_slam_map(hl_cycle_slam(c)));
        assert_true(now > edges[k] + 2);     /* it did cross */
        assert_null(strstr(hl_cycle_last_error(c), "MAP"));

        size_t maps = capture_count(cap, HL_CH_MAP);
        assert_true(maps >= 10);     /* period 0, no byte bound: every change */
        int64_t before = (int64_t)edges[k] - 1;
        for (size_t i = 0; i < maps; i++) {
            hl_bus_map_t m = map_of(capture_nth(cap, HL_CH_MAP, i));
            assert_true(m.version > before);
            before = m.version;
        }
        assert_true((uint64_t)before == now);

        hl_bus_status_t s = status_of(capture_nth(cap, HL_CH_STATUS,
                                                  capture_count(cap, HL_CH_STATUS) - 1));
        assert_true((uint64_t)s.map_version == now);
        assert_int_equal(s.scans, 20);

        /* and the state a save would write carries it */
        hl_mapfile_t m;
        hl_cycle_snapshot(c, &m);
        assert_true(m.state.map_version == now);
        hl_cycle_destroy(c);
        capture_clear(cap);
        free(cap);
    }
}

/* A flood of malformed messages counted past 2^31 (15 hours of a flood at 40,000 a
 * second): STATUS still goes out, counting each. */
static void test_bad_messages_past_2_31(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    c->n.bad_messages = INT32_MAX - 1;
    uint8_t junk[10] = { 1, 2, 3 };
    for (int i = 0; i < 3; i++) {
        hl_cycle_on_message(c, HL_CH_SONAR, junk, sizeof junk, 0);
        hl_cycle_tick(c, 1000000 * (int64_t)(i + 1));
    }
    hl_cycle_set_state(c, HL_BUS_STATE_IDLE, 4000000);
    assert_int_equal(hl_cycle_counts(c)->bad_messages, (int64_t)INT32_MAX + 2);
    hl_bus_status_t s = status_of(capture_nth(cap, HL_CH_STATUS,
                                              capture_count(cap, HL_CH_STATUS) - 1));
    assert_int_equal(s.bad_messages, (int64_t)INT32_MAX + 2);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* At HL_COUNT_MAX a counter and the map version stay put: STATUS and MAP still go out,
 * with the largest value an LCM int64_t holds, never a wrapped (negative) one. */
static void test_counters_stop_at_the_limit(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_t *c = restored_at(cap, (uint64_t)HL_COUNT_MAX - 1);
    c->n.bad_messages = HL_COUNT_MAX - 1;
    c->n.scans = HL_COUNT_MAX;
    uint8_t junk[10] = { 1, 2, 3 };
    for (int i = 0; i < 3; i++)
        hl_cycle_on_message(c, HL_CH_ODOMETRY, junk, sizeof junk, 0);
    feed_tour(c, 10);
    hl_cycle_set_state(c, HL_BUS_STATE_LOCALIZING, 0);
    assert_true(hl_map_version(hl_slam_map(hl_cycle_slam(c))) == (uint64_t)HL_COUNT_MAX);
    hl_bus_status_t s = status_of(capture_nth(cap, HL_CH_STATUS,
                                              capture_count(cap, HL_CH_STATUS) - 1));
    assert_int_equal(s.bad_messages, HL_COUNT_MAX);
    assert_int_equal(s.scans, HL_COUNT_MAX);
    assert_int_equal(s.map_version, HL_COUNT_MAX);
    size_t maps = capture_count(cap, HL_CH_MAP);
    assert_true(maps >= 1);
    assert_int_equal(map_of(capture_nth(cap, HL_CH_MAP, maps - 1)).version, HL_COUNT_MAX);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_map_version_crosses_32_bit_edges),
        cmocka_unit_test(test_bad_messages_past_2_31),
        cmocka_unit_test(test_counters_stop_at_the_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
