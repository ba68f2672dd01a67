/* The codecs never allocate: every encoder and decoder, on good and bad input, from
 * the very first call (when the generated code computes and caches the fingerprints),
 * runs while AddressSanitizer's allocation hook counts every malloc, calloc and realloc
 * in the process, libc's own included. The bus tests always run under ASan
 * (src/bus/bus.mk), which provides the hook; GCC 12 ships no header for it. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc_scan_t.h"

int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void *, size_t),
                                              void (*free_hook)(const volatile void *));

static volatile long allocations;

static void on_malloc(const volatile void *p, size_t n)
{
    (void)p;
    (void)n;
    allocations++;
}

static void on_free(const volatile void *p)
{
    (void)p;
}

/* Storage made before counting starts. */
typedef struct fixture {
    hl_bus_scan_t scan, scan_out;
    hl_vector_t vectors[64], vectors_out[64];
    uint8_t buf[8][HL_BUS_SCAN_MAX_BYTES];
    int len[8];
} fixture_t;

static void encode_all(fixture_t *f)
{
    f->scan.utime = 1;
    f->scan.scan.count = 128;
    for (int i = 0; i < 128; i++)
        f->scan.scan.readings[i] = (hl_reading_t){ 1000 + i, (hl_bam_t)(i * 512), 3, true, 0 };
    hl_bus_odometry_t odo = { 2, { 10, 20, 30 }, 5, true };
    hl_bus_pose_t pose = { 3, 4, { 1, 2, 3 }, 1, 0.5f, 100, 50, 1000, 0.5f, { 4, 5, 6 }, 0.25f };
    for (int i = 0; i < 64; i++)
        f->vectors[i] = (hl_vector_t){ i, -i, (hl_bam_t)i, 500 };
    hl_bus_map_t map = { 4, 5, 100, 64, f->vectors, 0 };
    hl_bus_status_t status = { .utime = 5, .state = HL_BUS_STATE_IDLE, .destination_seq = -1 };
    strcpy(status.last_error, "map save failed: disk full");
    hl_bus_destination_t dest = { 6, 7, 100, 200, true, 1000, { 1, 2, 3 } };
    hl_bus_command_t cmd = { 7, 8, HL_BUS_COMMAND_SAVE, { 0, 0, 0 }, { 0 } };
    hl_bus_reply_t reply = { 8, 9, HL_BUS_REPLY_FAILED, "no robot link", { 0 } };
    size_t cap = sizeof f->buf[0];
    f->len[0] = hl_bus_encode_scan(&f->scan, f->buf[0], cap);
    f->len[1] = hl_bus_encode_odometry(&odo, f->buf[1], cap);
    f->len[2] = hl_bus_encode_pose(&pose, f->buf[2], cap);
    f->len[3] = hl_bus_encode_map(&map, f->buf[3], cap);
    f->len[4] = hl_bus_encode_status(&status, f->buf[4], cap);
    f->len[5] = hl_bus_encode_destination(&dest, f->buf[5], cap);
    f->len[6] = hl_bus_encode_command(&cmd, f->buf[6], cap);
    f->len[7] = hl_bus_encode_reply(&reply, f->buf[7], cap);
}

/* Decodes message @p k of @p len bytes (maybe altered); returns the status. */
static hl_status_t decode_one(fixture_t *f, int k, size_t len, char *why)
{
    const uint8_t *b = f->buf[k];
    hl_bus_odometry_t odo;
    hl_bus_pose_t pose;
    hl_bus_map_t map = { .vectors = f->vectors_out, .max_vectors = 64 };
    hl_bus_status_t status;
    hl_bus_destination_t dest;
    hl_bus_command_t cmd;
    hl_bus_reply_t reply;
    switch (k) {
    case 0: return hl_bus_decode_scan(b, len, &f->scan_out, why);
    case 1: return hl_bus_decode_odometry(b, len, &odo, why);
    case 2: return hl_bus_decode_pose(b, len, &pose, why);
    case 3: return hl_bus_decode_map(b, len, &map, why);
    case 4: return hl_bus_decode_status(b, len, &status, why);
    case 5: return hl_bus_decode_destination(b, len, &dest, why);
    case 6: return hl_bus_decode_command(b, len, &cmd, why);
    default: return hl_bus_decode_reply(b, len, &reply, why);
    }
}

static void test_codecs_do_not_allocate(void **state)
{
    (void)state;
    fixture_t *f = calloc(1, sizeof *f);
    assert_non_null(f);
    char why[HL_BUS_WHY_LEN];

    allocations = 0;
    encode_all(f);                      /* the first codec calls of this program */
    for (int k = 0; k < 8; k++) {
        why[0] = '\0';
        hl_status_t good = decode_one(f, k, (size_t)f->len[k], why);
        hl_status_t truncated = decode_one(f, k, (size_t)f->len[k] - 1, why);
        f->buf[k][8] ^= 0x80;           /* every message's utime turns negative */
        hl_status_t damaged = decode_one(f, k, (size_t)f->len[k], why);
        f->buf[k][0] ^= 1;
        hl_status_t bad_hash = decode_one(f, k, (size_t)f->len[k], why);
        long seen = allocations;

        assert_true(f->len[k] > 0);
        assert_int_equal(good, HL_OK);
        assert_int_equal(truncated, HL_ERR_PARSE);
        assert_int_equal(damaged, HL_ERR_RANGE);
        assert_int_equal(bad_hash, HL_ERR_PARSE);
        if (seen != 0)
            fail_msg("message %d: %ld allocations while decoding", k, seen);
    }
    char chan[HL_BUS_CHANNEL_MAX];
    assert_true(hl_bus_channel("r1_", HL_CHANNEL_POSE, chan));
    assert_int_equal(allocations, 0);
    free(f);
}

/* The counter sees allocations, including those made inside a library: a plain malloc
 * and lcm-gen's own decoder (which mallocs its arrays). */
static void test_the_counter_counts(void **state)
{
    (void)state;
    allocations = 0;
    void *p = malloc(16);
    assert_non_null(p);
    assert_int_equal(allocations, 1);
    free(p);

    static uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
    hl_bus_scan_t *s = calloc(1, sizeof *s);
    assert_non_null(s);
    s->scan.count = 4;
    int len = hl_bus_encode_scan(s, buf, sizeof buf);
    assert_true(len > 0);
    houghloc_scan_t g;
    allocations = 0;
    assert_int_equal(houghloc_scan_t_decode(buf, 0, len, &g), len);
    assert_true(allocations >= 4);
    houghloc_scan_t_decode_cleanup(&g);
    free(s);
}

int main(void)
{
    if (!__sanitizer_install_malloc_and_free_hooks(on_malloc, on_free)) {
        fprintf(stderr, "test_codec_noalloc: cannot install the allocation hook\n");
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_codecs_do_not_allocate),
        cmocka_unit_test(test_the_counter_counts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
