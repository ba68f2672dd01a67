/* Tests for tools/console/bridge.c and jbuf.c: every message the console forwards as the
 * exact JSON the page reads (empty and full maps and paths, every field, names of every
 * state and result, escaping of hostile text), and the buffer's bound. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bridge.h"
#include "houghloc/fixed.h"
#include "houghloc/slam.h"

static void test_map_empty(void **state)
{
    (void)state;
    jbuf_t b;
    jbuf_init(&b, 0);
    hl_bus_map_t m = { .utime = 5, .version = 0, .capacity = 1500, .count = 0 };
    bridge_map(&b, &m);
    assert_false(b.failed);
    assert_string_equal(b.data, "{\"utime\":5,\"version\":0,\"capacity\":1500,\"count\":0,\"v\":[]}");
    jbuf_free(&b);
}

static void test_map_two_vectors(void **state)
{
    (void)state;
    hl_vector_t v[2] = { { .x_mm = -4194304, .y_mm = 4194304, .normal = 65535, .range_mm = 32767 },
                         { .x_mm = 12, .y_mm = -7, .normal = 16384, .range_mm = 0 } };
    /* a version past 32 bits (64-bit on the bus): whole */
    hl_bus_map_t m = { .utime = 1, .version = (INT64_C(1) << 40) + 9, .capacity = 2, .count = 2,
                       .vectors = v };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_map(&b, &m);
    assert_string_equal(b.data, "{\"utime\":1,\"version\":1099511627785,\"capacity\":2,"
                                "\"count\":2,"
                                "\"v\":[-4194304,4194304,65535,32767,12,-7,16384,0]}");
    jbuf_free(&b);
}

/* A full 15,000-vector map: every vector there, in order, and compact (< 30 bytes each). */
/* The largest map the wire allows (2^20 vectors): thinned to every 16th vector, the
 * JSON at most 30 bytes a vector kept (about 2 MB), and it says so. */
static void test_map_thinned(void **state)
{
    (void)state;
    const uint32_t n = HL_MAP_MAX_CAPACITY;
    hl_vector_t *v = calloc(n, sizeof *v);
    assert_non_null(v);
    for (uint32_t i = 0; i < n; i++) /* the longest numbers there are */
        v[i] = (hl_vector_t){ .x_mm = -HL_COORD_MAX_MM, .y_mm = -(int32_t)i, .normal = 65535,
                              .range_mm = HL_RANGE_MAX_MM };
    hl_bus_map_t m = { .utime = 1, .version = 2, .capacity = (int32_t)n, .count = n,
                       .vectors = v };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_map(&b, &m);
    assert_false(b.failed);
    assert_true(b.len <= 30u * BRIDGE_MAP_MAX_VECTORS + 100);
    assert_non_null(strstr(b.data, "\"count\":1048576,\"stride\":16,\"v\":[-4194304,0,65535,"));
    assert_non_null(strstr(b.data, ",-4194304,-1048560,65535,32767]}")); /* the last kept */
    /* one vector past the bound: a stride of 2, so 32,769 vectors */
    m.count = BRIDGE_MAP_MAX_VECTORS + 1;
    jbuf_reset(&b);
    bridge_map(&b, &m);
    assert_non_null(strstr(b.data, "\"stride\":2,"));
    size_t commas = 0;
    for (const char *c = strstr(b.data, "\"v\":["); *c; c++)
        commas += *c == ',';
    assert_int_equal(commas, 4 * (BRIDGE_MAP_MAX_VECTORS / 2 + 1) - 1);
    /* at the bound: every vector, no stride */
    m.count = BRIDGE_MAP_MAX_VECTORS;
    jbuf_reset(&b);
    bridge_map(&b, &m);
    assert_null(strstr(b.data, "stride"));
    jbuf_free(&b);
    free(v);
}

static void test_map_full(void **state)
{
    (void)state;
    enum { N = 15000 };
    hl_vector_t *v = calloc(N, sizeof *v);
    assert_non_null(v);
    for (int i = 0; i < N; i++)
        v[i] = (hl_vector_t){ .x_mm = i - 7000, .y_mm = 3 * i, .normal = (hl_bam_t)(i * 7),
                              .range_mm = (uint16_t)(i % 5000) };
    hl_bus_map_t m = { .utime = 2, .version = 3, .capacity = N, .count = N, .vectors = v };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_map(&b, &m);
    assert_false(b.failed);
    assert_true(b.len < 30u * N);
    const char *p = strstr(b.data, "\"v\":[");
    assert_non_null(p);
    p += 5;
    for (int i = 0; i < N; i++) {
        long f[4];
        for (int k = 0; k < 4; k++) {
            char *end;
            f[k] = strtol(p, &end, 10);
            assert_true(*end == ',' || *end == ']');
            p = end + 1;
        }
        assert_int_equal(f[0], i - 7000);
        assert_int_equal(f[1], 3 * i);
        assert_int_equal(f[2], (hl_bam_t)(i * 7));
        assert_int_equal(f[3], i % 5000);
    }
    assert_string_equal(p - 1, "]}");
    jbuf_free(&b);
    free(v);
}

static void test_pose(void **state)
{
    (void)state;
    hl_bus_pose_t p = { .utime = 1000, .scan_seq = 42,
                        .pose = { .x_mm = 1500, .y_mm = -2000, .theta = 16384 },
                        .status = HL_BUS_POSE_REJECTED_WILD, .confidence = 0.75f, .peak = 300,
                        .second_peak = 120, .votes = 9000, .search_score = 0.5f,
                        .runner_up = { .x_mm = -1, .y_mm = 2, .theta = 32768 },
                        .runner_up_score = 0.25f };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_pose(&b, &p);
    assert_string_equal(b.data,
                        "{\"utime\":1000,\"scan_seq\":42,\"x_mm\":1500,\"y_mm\":-2000,"
                        "\"heading_deg\":90.00,\"status\":\"REJECTED_WILD\",\"confidence\":0.7500,"
                        "\"peak\":300,\"second_peak\":120,\"votes\":9000,\"search_score\":0.5000,"
                        "\"runner_up\":{\"x_mm\":-1,\"y_mm\":2,\"heading_deg\":180.00},"
                        "\"runner_up_score\":0.2500}");
    jbuf_free(&b);
}

static void test_pose_status_and_state_names(void **state)
{
    (void)state;
    assert_string_equal(bridge_pose_status_name(HL_BUS_POSE_ACCEPTED), "ACCEPTED");
    assert_string_equal(bridge_pose_status_name(HL_BUS_POSE_ODOMETRY_ONLY), "ODOMETRY_ONLY");
    assert_string_equal(bridge_pose_status_name(HL_BUS_POSE_RELOCALIZED), "RELOCALIZED");
    assert_string_equal(bridge_pose_status_name(HL_BUS_POSE_LOST), "LOST");
    assert_string_equal(bridge_pose_status_name(5), "UNKNOWN");
    assert_string_equal(bridge_pose_status_name(-1), "UNKNOWN");
    static const char *const states[] = { "STARTING", "SOUNDING", "LOCALIZING", "MOVING",
                                          "IDLE", "FAULT", "STOPPING", "LOST" };
    for (int8_t s = 0; s < 8; s++)
        assert_string_equal(bridge_state_name(s), states[s]);
    assert_string_equal(bridge_state_name(8), "UNKNOWN");
    assert_string_equal(bridge_state_name(-128), "UNKNOWN");
}

static void test_status(void **state)
{
    (void)state;
    hl_bus_status_t s = { .utime = 7, .state = HL_BUS_STATE_MOVING, .destination_seq = -1,
                          .scans = 10, .accepted = 8, .rejected_wild = 1, .odometry_only = 1,
                          .bad_packets = 2, .bad_messages = 3, .rejected_requests = 4,
                          .map_vectors = 1500, .map_version = 77, .saves = 5,
                          .pose = { .x_mm = 1, .y_mm = 2, .theta = 0 },
                          .compute_median_us = 1700, .compute_p99_us = 2500,
                          .compute_samples = 128 };
    snprintf(s.last_error, sizeof s.last_error, "fence: (50, 0) \"outside\" \\ here");
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_status(&b, &s);
    assert_string_equal(b.data,
                        "{\"utime\":7,\"state\":\"MOVING\",\"destination_seq\":null,\"scans\":10,"
                        "\"accepted\":8,\"rejected_wild\":1,\"odometry_only\":1,"
                        "\"relocalized\":0,\"lost\":0,\"bad_packets\":2,"
                        "\"bad_messages\":3,\"rejected_requests\":4,\"map_vectors\":1500,"
                        "\"map_version\":77,\"saves\":5,\"x_mm\":1,\"y_mm\":2,\"heading_deg\":0,"
                        "\"compute_median_us\":1700,\"compute_p99_us\":2500,\"compute_samples\":128,"
                        "\"last_error\":\"fence: (50, 0) \\\"outside\\\" \\\\ here\"}");
    /* a destination under way: its seq as a string, beyond 2^53 exactly */
    s.destination_seq = INT64_MAX;
    jbuf_reset(&b);
    bridge_status(&b, &s);
    assert_non_null(strstr(b.data, "\"destination_seq\":\"9223372036854775807\""));
    /* counters past 32 bits (64-bit on the bus) go out whole, as numbers */
    s.map_version = (INT64_C(1) << 32) + 5;
    s.bad_messages = (INT64_C(1) << 31) + 1;
    jbuf_reset(&b);
    bridge_status(&b, &s);
    assert_non_null(strstr(b.data, "\"map_version\":4294967301,"));
    assert_non_null(strstr(b.data, "\"bad_messages\":2147483649,"));
    jbuf_free(&b);
}

static void test_reply_and_sent(void **state)
{
    (void)state;
    hl_bus_reply_t r = { .utime = 3, .seq = -5, .result = HL_BUS_REPLY_REJECTED_FENCE };
    /* bytes a network could carry: high bytes become \u00XX, so the JSON stays ASCII */
    snprintf(r.message, sizeof r.message, "%s", "caf\xc3\xa9 <b>");
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_reply(&b, &r, true);
    assert_string_equal(b.data, "{\"utime\":3,\"seq\":\"-5\",\"result\":\"REJECTED_FENCE\","
                                "\"message\":\"caf\\u00c3\\u00a9 <b>\",\"mine\":true}");
    jbuf_reset(&b);
    r.result = 99;
    r.message[0] = '\0';
    bridge_reply(&b, &r, false);
    assert_string_equal(b.data, "{\"utime\":3,\"seq\":\"-5\",\"result\":\"?\",\"message\":\"\","
                                "\"mine\":false}");
    hl_bus_destination_t d = { .utime = 11, .seq = 12, .x_mm = -1500, .y_mm = 2500 };
    jbuf_reset(&b);
    bridge_sent(&b, &d, false);
    assert_string_equal(b.data, "{\"utime\":11,\"seq\":\"12\",\"x_mm\":-1500,\"y_mm\":2500,"
                                "\"heading_deg\":null,\"signed\":false}");
    d.has_heading = true;
    d.heading = hl_bam_from_deg(270.0);
    jbuf_reset(&b);
    bridge_sent(&b, &d, true);
    assert_non_null(strstr(b.data, "\"heading_deg\":270.00,\"signed\":true}"));
    jbuf_free(&b);
}

/* PATH: the points flat, x then y, in order; the destination's seq as a string. */
static void test_path(void **state)
{
    (void)state;
    hl_bus_path_t p = { .utime = 9, .destination_seq = 1700000000123456789, .npoints = 3,
                        .x_mm = { 100, -4194304, 2500 }, .y_mm = { -200, 4194304, 0 } };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_path(&b, &p);
    assert_false(b.failed);
    assert_string_equal(b.data, "{\"utime\":9,\"seq\":\"1700000000123456789\","
                                "\"points\":[100,-200,-4194304,4194304,2500,0]}");
    /* beyond 2^53 exactly, and the largest */
    p.destination_seq = INT64_MAX;
    p.npoints = 1;
    jbuf_reset(&b);
    bridge_path(&b, &p);
    assert_string_equal(b.data, "{\"utime\":9,\"seq\":\"9223372036854775807\","
                                "\"points\":[100,-200]}");
    jbuf_free(&b);
}

/* The destination has ended: no points, and no seq when there is none. */
static void test_path_empty(void **state)
{
    (void)state;
    hl_bus_path_t p = { .utime = 0, .destination_seq = -1, .npoints = 0, .x_mm = { 1 },
                        .y_mm = { 2 } };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_path(&b, &p);
    assert_string_equal(b.data, "{\"utime\":0,\"seq\":null,\"points\":[]}");
    /* ended, but still naming the destination that ended */
    p.destination_seq = 5;
    jbuf_reset(&b);
    bridge_path(&b, &p);
    assert_string_equal(b.data, "{\"utime\":0,\"seq\":\"5\",\"points\":[]}");
    jbuf_free(&b);
}

/* A full path: 64 points, 128 integers, in order. */
static void test_path_full(void **state)
{
    (void)state;
    hl_bus_path_t p = { .utime = 1, .destination_seq = 2, .npoints = HL_BUS_PATH_MAX_POINTS };
    for (int i = 0; i < HL_BUS_PATH_MAX_POINTS; i++) {
        p.x_mm[i] = 1000 * i;
        p.y_mm[i] = -i;
    }
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_path(&b, &p);
    const char *q = strstr(b.data, "\"points\":[");
    assert_non_null(q);
    q += 10;
    for (int i = 0; i < HL_BUS_PATH_MAX_POINTS; i++) {
        char *end;
        assert_int_equal(strtol(q, &end, 10), 1000 * i);
        assert_true(*end == ',');
        assert_int_equal(strtol(end + 1, &end, 10), -i);
        assert_true(*end == (i + 1 < HL_BUS_PATH_MAX_POINTS ? ',' : ']'));
        q = end + 1;
    }
    assert_string_equal(q, "}");
    jbuf_free(&b);
}

/* POST /stop's answer: the seq as a string. */
static void test_stop(void **state)
{
    (void)state;
    hl_bus_command_t c = { .utime = 4, .seq = INT64_MAX, .kind = HL_BUS_COMMAND_STOP };
    jbuf_t b;
    jbuf_init(&b, 0);
    bridge_stop(&b, &c, false);
    assert_string_equal(b.data, "{\"utime\":4,\"seq\":\"9223372036854775807\",\"signed\":false}");
    jbuf_reset(&b);
    bridge_stop(&b, &c, true);
    assert_non_null(strstr(b.data, "\"signed\":true}"));
    jbuf_free(&b);
}

/* A bounded buffer refuses to grow past its bound and says so once, for the caller. */
static void test_jbuf_bound(void **state)
{
    (void)state;
    jbuf_t b;
    jbuf_init(&b, 8);
    jbuf_puts(&b, "12345678");
    assert_false(b.failed);
    assert_int_equal(b.len, 8);
    jbuf_putc(&b, '9');
    assert_true(b.failed);
    assert_string_equal(b.data, "12345678");
    jbuf_consume(&b, 3);
    assert_string_equal(b.data, "45678");
    jbuf_reset(&b);
    assert_false(b.failed);
    jbuf_num(&b, -0.0001, 2);
    assert_string_equal(b.data, "0");
    jbuf_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_map_empty),
        cmocka_unit_test(test_map_two_vectors),
        cmocka_unit_test(test_map_full),
        cmocka_unit_test(test_map_thinned),
        cmocka_unit_test(test_pose),
        cmocka_unit_test(test_pose_status_and_state_names),
        cmocka_unit_test(test_status),
        cmocka_unit_test(test_reply_and_sent),
        cmocka_unit_test(test_path),
        cmocka_unit_test(test_path_empty),
        cmocka_unit_test(test_path_full),
        cmocka_unit_test(test_stop),
        cmocka_unit_test(test_jbuf_bound),
    };
    return cmocka_run_group_tests_name("console_bridge", tests, NULL, NULL);
}
