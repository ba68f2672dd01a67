/* Tests for src/bus/scan_codec.c: round trips, the byte layout the pre-check relies on,
 * and hostile input (truncation, bad counts, bad hash, out-of-range fields, noise). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/rng.h"
#include "houghloc_pose_t.h"
#include "houghloc_scan_t.h"

static hl_bus_scan_t *sample_scan(int n)
{
    hl_bus_scan_t *s = calloc(1, sizeof *s);
    s->utime = 1234567890123;
    s->seq = 42;
    s->odometry = (hl_pose_t){ -1500, 2500, 40000 };
    for (int i = 0; i < n; i++)
        hl_scan_add(&s->scan, (hl_bam_t)(i * 512), 300 + i * 7, (int8_t)(i % 16), i % 5 != 0);
    return s;
}

static void test_round_trip(void **state)
{
    (void)state;
    static uint8_t buf[16384];
    hl_bus_scan_t *in = sample_scan(128), *out = calloc(1, sizeof *out);
    int len = hl_bus_encode_scan(in, buf, sizeof buf);
    assert_true(len > 0);
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_scan(buf, (size_t)len, out, why), HL_OK);
    assert_int_equal(out->seq, 42);
    assert_int_equal(out->utime, 1234567890123);
    assert_int_equal(out->odometry.x_mm, -1500);
    assert_int_equal(out->odometry.theta, 40000);
    assert_int_equal(out->scan.count, 128);
    for (int i = 0; i < 128; i++) {
        assert_int_equal(out->scan.readings[i].bearing, in->scan.readings[i].bearing);
        assert_int_equal(out->scan.readings[i].valid, in->scan.readings[i].valid);
        if (in->scan.readings[i].valid)
            assert_int_equal(out->scan.readings[i].range_mm, in->scan.readings[i].range_mm);
    }
    assert_int_equal(hl_bus_encode_scan(in, buf, 100), -1);   /* buffer too small */
    free(in);
    free(out);
}

/* The decoder's pre-check computes the length from nreadings; it must agree with the
 * generated code for every count, or a change to the .lcm file has broken it. */
static void test_layout_matches_generated_size(void **state)
{
    (void)state;
    static uint8_t buf[16384];
    const int counts[] = { 0, 1, 2, 128, 1024 };
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        hl_bus_scan_t *in = sample_scan(counts[k]);
        int len = hl_bus_encode_scan(in, buf, sizeof buf);
        assert_int_equal(len, 43 + 8 * counts[k]);
        hl_bus_scan_t *out = calloc(1, sizeof *out);
        assert_int_equal(hl_bus_decode_scan(buf, (size_t)len, out, NULL), HL_OK);
        assert_int_equal(out->scan.count, (uint32_t)counts[k]);
        free(in);
        free(out);
    }
}

static void test_hostile_bytes_rejected(void **state)
{
    (void)state;
    static uint8_t buf[16384];
    hl_bus_scan_t *in = sample_scan(16), *out = calloc(1, sizeof *out);
    int len = hl_bus_encode_scan(in, buf, sizeof buf);
    char why[HL_BUS_WHY_LEN];

    assert_int_equal(hl_bus_decode_scan(buf, 10, out, why), HL_ERR_PARSE);
    assert_string_equal(why, "scan message truncated");
    assert_int_equal(hl_bus_decode_scan(buf, (size_t)len - 1, out, why), HL_ERR_PARSE);
    assert_string_equal(why, "scan message length does not match nreadings");

    uint8_t bad[16384];
    memcpy(bad, buf, (size_t)len);
    bad[41] = 0xFF;     /* nreadings = -something */
    assert_int_equal(hl_bus_decode_scan(bad, (size_t)len, out, why), HL_ERR_RANGE);
    assert_string_equal(why, "scan nreadings outside 0..1024");

    memcpy(bad, buf, (size_t)len);
    bad[0] ^= 0x55;     /* type hash */
    assert_int_equal(hl_bus_decode_scan(bad, (size_t)len, out, why), HL_ERR_PARSE);

    /* a valid reading with a range beyond 32767 mm */
    hl_bus_scan_t *far = sample_scan(4);
    len = hl_bus_encode_scan(far, buf, sizeof buf);
    int range0 = 43 + 4 * 1 + 4 * 2 + 4;    /* second reading's range (the first is invalid) */
    buf[range0] = 0x00; buf[range0 + 1] = 0x01; buf[range0 + 2] = 0x00; buf[range0 + 3] = 0x00;
    assert_int_equal(hl_bus_decode_scan(buf, (size_t)len, out, why), HL_ERR_RANGE);
    assert_string_equal(why, "scan reading marked valid with range outside 0..32767 mm");
    free(far);

    /* random noise of every length: rejected or accepted, never a crash or a leak */
    hl_rng_t rng;
    hl_rng_seed(&rng, 99);
    for (int trial = 0; trial < 3000; trial++) {
        size_t n = hl_rng_below(&rng, 400);
        for (size_t i = 0; i < n; i++)
            bad[i] = (uint8_t)hl_rng_next(&rng);
        if (trial % 2 && n > 43) {  /* give half of them a plausible count */
            size_t k = (n - 43) / 8;
            bad[41] = (uint8_t)(k >> 8);
            bad[42] = (uint8_t)k;
            n = 43 + 8 * k;
        }
        (void)hl_bus_decode_scan(bad, n, out, why);
        hl_bus_pose_t p;
        (void)hl_bus_decode_pose(bad, n, &p, why);
    }
    free(in);
    free(out);
}

static void test_pose_decode(void **state)
{
    (void)state;
    uint8_t buf[256];
    houghloc_pose_t m = { .utime = 5, .scan_seq = 7, .x_mm = 100, .y_mm = -200,
                          .heading_bam = -16384, .status = HOUGHLOC_POSE_T_ACCEPTED };
    int len = houghloc_pose_t_encode(buf, 0, sizeof buf, &m);
    hl_bus_pose_t p;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_pose(buf, (size_t)len, &p, why), HL_OK);
    assert_int_equal(p.pose.theta, 49152);
    assert_int_equal(p.scan_seq, 7);
    assert_int_equal(hl_bus_decode_pose(buf, (size_t)len + 3, &p, why), HL_ERR_PARSE);
    assert_int_equal(hl_bus_decode_pose(buf, (size_t)len - 1, &p, why), HL_ERR_PARSE);
    m.x_mm = HL_COORD_MAX_MM + 1;
    len = houghloc_pose_t_encode(buf, 0, sizeof buf, &m);
    assert_int_equal(hl_bus_decode_pose(buf, (size_t)len, &p, why), HL_ERR_RANGE);
    m.x_mm = 0;
    m.status = 9;
    len = houghloc_pose_t_encode(buf, 0, sizeof buf, &m);
    assert_int_equal(hl_bus_decode_pose(buf, (size_t)len, &p, why), HL_ERR_RANGE);
    assert_string_equal(why, "pose status is not one of the defined constants");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_layout_matches_generated_size),
        cmocka_unit_test(test_hostile_bytes_rejected),
        cmocka_unit_test(test_pose_decode),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
