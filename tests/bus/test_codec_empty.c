/* Tests for src/bus/codec_scan.c and codec_map.c on empty arrays: a SONAR scan with no
 * readings and a MAP with no vectors, against the lcm-gen encoder both ways, byte for
 * byte, with the generated code built under the sanitizers (the Makefile's test build).
 *
 * lcm_coretypes.h copies int8 and boolean arrays with memcpy, and memcpy must not be
 * given a NULL pointer even for zero bytes (UBSan: "null pointer passed as argument"). So
 * whoever fills a generated struct points an empty array at a one-element dummy, never at
 * NULL. The generated decoder cannot be helped (it gives an empty array NULL itself): our
 * codecs never call it, and these tests check its output through the encoder instead. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_map_t.h"
#include "houghloc_scan_t.h"

static void test_scan_with_no_readings(void **state)
{
    (void)state;
    uint8_t ours[64], theirs[64];
    int8_t no_transducer[1] = { 0 }, no_valid[1] = { 0 };
    int16_t no_bearing[1] = { 0 };
    int32_t no_range[1] = { 0 };
    hl_bus_scan_t *s = calloc(1, sizeof *s), *back = calloc(1, sizeof *back);
    assert_non_null(s);
    assert_non_null(back);
    *s = (hl_bus_scan_t){ .utime = 123456789, .seq = 42,
                          .odometry = { .x_mm = -1500, .y_mm = 2500, .theta = 16384 } };
    s->scan.count = 0;
    int len = hl_bus_encode_scan(s, ours, sizeof ours);
    assert_int_equal(len, 43);

    houghloc_scan_t g = {
        .utime = s->utime, .seq = s->seq,
        .odometry = { .utime = s->utime, .x_mm = -1500, .y_mm = 2500, .heading_bam = 16384,
                      .velocity_mm_s = 0, .stopped = 1 },
        .nreadings = 0, .transducer = no_transducer, .bearing_bam = no_bearing,
        .range_mm = no_range, .valid = no_valid,
    };
    assert_int_equal(houghloc_scan_t_encoded_size(&g), len);
    assert_int_equal(houghloc_scan_t_encode(theirs, 0, sizeof theirs, &g), len);
    assert_memory_equal(ours, theirs, (size_t)len);

    back->scan.count = 7;       /* stale: the decoder must set it */
    assert_int_equal(hl_bus_decode_scan(theirs, (size_t)len, back, NULL), HL_OK);
    assert_int_equal(back->scan.count, 0);
    assert_int_equal(back->utime, 123456789);
    assert_int_equal(back->seq, 42);
    assert_int_equal(back->odometry.x_mm, -1500);
    assert_int_equal(back->odometry.y_mm, 2500);
    assert_int_equal(back->odometry.theta, 16384);
    assert_int_equal(hl_bus_encode_scan(back, ours, sizeof ours), len);
    assert_memory_equal(ours, theirs, (size_t)len);
    free(s);
    free(back);
}

static void test_map_with_no_vectors(void **state)
{
    (void)state;
    uint8_t ours[40], theirs[40];
    int32_t no_x[1] = { 0 }, no_y[1] = { 0 };
    int16_t no_normal[1] = { 0 }, no_range[1] = { 0 };
    hl_vector_t storage[1];
    hl_bus_map_t m = { .utime = 987654321, .version = 3, .capacity = 1500, .count = 0,
                       .vectors = NULL };
    int len = hl_bus_encode_map(&m, ours, sizeof ours);
    assert_int_equal(len, 32);

    houghloc_map_t g = { .utime = m.utime, .version = 3, .capacity = 1500, .nvectors = 0,
                         .x_mm = no_x, .y_mm = no_y, .normal_bam = no_normal,
                         .range_mm = no_range };
    assert_int_equal(houghloc_map_t_encoded_size(&g), len);
    assert_int_equal(houghloc_map_t_encode(theirs, 0, sizeof theirs, &g), len);
    assert_memory_equal(ours, theirs, (size_t)len);

    hl_bus_map_t back = { .count = 5, .vectors = storage, .max_vectors = 1 };
    assert_int_equal(hl_bus_decode_map(theirs, (size_t)len, &back, NULL), HL_OK);
    assert_int_equal(back.count, 0);
    assert_int_equal(back.utime, 987654321);
    assert_int_equal(back.version, 3);
    assert_int_equal(back.capacity, 1500);
    assert_int_equal(hl_bus_encode_map(&back, ours, sizeof ours), len);
    assert_memory_equal(ours, theirs, (size_t)len);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan_with_no_readings),
        cmocka_unit_test(test_map_with_no_vectors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
