/*
 * test_alloc.c - no heap allocation per cycle: after start-up, a replay of the whole tour
 * (every SONAR and ODOMETRY message, STATUS ticks, requests, snapshots) through the cycle
 * calls malloc, calloc and realloc zero times. Linked with -Wl,--wrap for the three, which
 * redirects every call made by houghloc's own code (the core, bus and daemon archives) to
 * the counters below; liblcm and libc are shared libraries and are not ours to count.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "support.h"

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t n);

static bool counting;
static long allocations;

void *__wrap_malloc(size_t n)
{
    allocations += counting;
    return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    allocations += counting;
    return __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t n)
{
    allocations += counting;
    return __real_realloc(p, n);
}

static size_t emitted;

static void count_emit(void *ctx, hl_chan_t ch, const void *data, size_t len)
{
    (void)ctx;
    (void)ch;
    (void)data;
    emitted += len;
}

static int64_t fake_clock(void *ctx)
{
    (void)ctx;
    static int64_t t;
    return t += 100;
}

static void test_no_allocation_per_cycle(void **state)
{
    (void)state;
    load_tour();
    hl_cycle_params_t p = test_params();
    p.save_every = 10;
    hl_cycle_io_t io = { .emit = count_emit, .now_us = fake_clock };
    hl_cycle_t *c = hl_cycle_create(&p, &io);
    assert_non_null(c);
    uint8_t req[HL_BUS_COMMAND_BYTES];
    hl_bus_command_t save = { .utime = 1, .seq = 1, .kind = HL_BUS_COMMAND_SAVE };

    allocations = 0;
    counting = true;
    size_t scans = 0;
    for (size_t i = 0; i < n_tour; i++) {
        hl_cycle_on_message(c, tour[i].ch, tour[i].data, tour[i].len, tour[i].utime);
        if (tour[i].ch != HL_CH_SONAR)
            continue;
        scans++;
        hl_cycle_tick(c, (int64_t)scans * 1000000);
        if (hl_cycle_save_due(c)) {
            hl_mapfile_t m;
            hl_cycle_snapshot(c, &m);
            hl_cycle_saved(c, true, "");
        }
        if (scans % 16 == 0) {
            save.seq++;
            int len = hl_bus_encode_command(&save, req, sizeof req);
            hl_cycle_on_message(c, HL_CH_COMMAND, req, (size_t)len, 0);
        }
    }
    hl_cycle_flush_map(c);
    counting = false;

    assert_int_equal(scans, 128);
    assert_int_equal(hl_cycle_counts(c)->scans, 128);
    assert_true(hl_cycle_counts(c)->saves >= 12);
    assert_true(emitted > 128 * HL_BUS_POSE_BYTES);
    assert_int_equal(allocations, 0);
    hl_cycle_destroy(c);

    /* the counter works: creating a cycle allocates */
    counting = true;
    c = hl_cycle_create(&p, &io);
    counting = false;
    assert_true(allocations > 0);
    hl_cycle_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_allocation_per_cycle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
