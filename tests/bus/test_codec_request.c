/* Tests for the DESTINATION and COMMAND halves of src/bus/codec_request.c against the
 * lcm-gen code both ways, their hostile bytes and noise; and src/bus/channel.c. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "codec_testkit.h"
#include "houghloc_command_t.h"
#include "houghloc_destination_t.h"

static hl_status_t dec_dest(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_destination(d, n, o, why);
}
static int enc_dest(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_destination(in, buf, cap);
}
static hl_status_t dec_cmd(const void *d, size_t n, void *o, char *why)
{
    return hl_bus_decode_command(d, n, o, why);
}
static int enc_cmd(const void *in, void *buf, size_t cap)
{
    return hl_bus_encode_command(in, buf, cap);
}

static int32_t coord(hl_rng_t *rng)
{
    return (int32_t)tk_range(rng, -HL_COORD_MAX_MM, HL_COORD_MAX_MM);
}

static void random_mac(hl_rng_t *rng, uint8_t *mac)
{
    bool unsigned_msg = hl_rng_below(rng, 4) == 0;
    for (int i = 0; i < HL_BUS_MAC_BYTES; i++)
        mac[i] = unsigned_msg ? 0 : (uint8_t)hl_rng_next(rng);
}

/* ---- DESTINATION ------------------------------------------------------------------- */

static hl_bus_destination_t random_destination(hl_rng_t *rng)
{
    hl_bus_destination_t d = {
        .utime = tk_range(rng, 0, INT64_MAX),
        .seq = tk_range(rng, 1, INT64_MAX),
        .x_mm = coord(rng), .y_mm = coord(rng),
        .has_heading = hl_rng_below(rng, 2),
        .heading = (hl_bam_t)hl_rng_next(rng),
    };
    random_mac(rng, d.mac);
    return d;
}

static void assert_destination_matches(const hl_bus_destination_t *d,
                                       const houghloc_destination_t *g)
{
    assert_int_equal(g->utime, d->utime);
    assert_int_equal(g->seq, d->seq);
    assert_int_equal(g->x_mm, d->x_mm);
    assert_int_equal(g->y_mm, d->y_mm);
    assert_int_equal(g->has_heading, d->has_heading);
    assert_int_equal((hl_bam_t)g->heading_bam, d->heading);
    assert_memory_equal(g->mac, d->mac, HL_BUS_MAC_BYTES);
}

static void test_destination_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_DESTINATION_BYTES], b[HL_BUS_DESTINATION_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 71);
    for (int it = 0; it < 500; it++) {
        hl_bus_destination_t d = random_destination(&rng), back;
        int len = hl_bus_encode_destination(&d, a, sizeof a);
        assert_int_equal(len, HL_BUS_DESTINATION_BYTES);
        houghloc_destination_t g;
        assert_int_equal(houghloc_destination_t_decode(a, 0, len, &g), len);
        assert_destination_matches(&d, &g);
        assert_int_equal(houghloc_destination_t_encoded_size(&g), len);
        assert_int_equal(houghloc_destination_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, sizeof a);

        g.seq = tk_range(&rng, 1, INT64_MAX);
        g.mac[5] = (int8_t)hl_rng_next(&rng);
        assert_int_equal(houghloc_destination_t_encode(b, 0, sizeof b, &g), len);
        assert_int_equal(hl_bus_decode_destination(b, sizeof b, &back, NULL), HL_OK);
        assert_destination_matches(&back, &g);
        assert_int_equal(hl_bus_encode_destination(&back, a, sizeof a), len);
        assert_memory_equal(a, b, sizeof a);
    }
}

static void test_destination_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_DESTINATION_BYTES], b[HL_BUS_DESTINATION_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 72);
    hl_bus_destination_t d = random_destination(&rng), out;
    tk_codec_t c = { "destination", dec_dest, enc_dest, NULL, &out };
    assert_int_equal(hl_bus_encode_destination(&d, a, sizeof a), HL_BUS_DESTINATION_BYTES);
    tk_check_truncations(&c, a, sizeof a);
    tk_check_bad_hash(&c, a, sizeof a);
    tk_check_small_buffers(&c, &d, sizeof a);
    /* offsets: 8 utime 16 seq 24 x 28 y 32 has_heading 33 heading 35 mac */
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)INT64_MIN, 8, "utime" },
        { 16, 0, 8, "seq" },
        { 16, (uint64_t)-1, 8, "seq" },
        { 24, HL_COORD_MAX_MM + 1, 4, "position" },
        { 28, 0x80000000u, 4, "position" },
        { 32, 2, 1, "has_heading" },
        { 32, 0xff, 1, "has_heading" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, sizeof a);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, sizeof b, HL_ERR_RANGE, bad[k].field);
    }
    hl_bus_destination_t q = d;
    q.seq = 0;
    assert_int_equal(hl_bus_encode_destination(&q, b, sizeof b), -1);
    q = d;
    q.x_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_destination(&q, b, sizeof b), -1);
    q = d;
    q.utime = -1;
    assert_int_equal(hl_bus_encode_destination(&q, b, sizeof b), -1);
    assert_in_range(tk_fuzz(&c, a, sizeof a, 5000, 73), 1, 4999);
}

/* ---- COMMAND ----------------------------------------------------------------------- */

static hl_bus_command_t random_command(hl_rng_t *rng)
{
    hl_bus_command_t m = {
        .utime = tk_range(rng, 0, INT64_MAX),
        .seq = tk_range(rng, 1, INT64_MAX),
        .kind = (int8_t)tk_range(rng, HL_BUS_COMMAND_SET_POSE, HL_BUS_COMMAND_STOP),
        .pose = { coord(rng), coord(rng), (hl_bam_t)hl_rng_next(rng) },
    };
    random_mac(rng, m.mac);
    return m;
}

static void assert_command_matches(const hl_bus_command_t *m, const houghloc_command_t *g)
{
    assert_int_equal(g->utime, m->utime);
    assert_int_equal(g->seq, m->seq);
    assert_int_equal(g->kind, m->kind);
    assert_int_equal(g->x_mm, m->pose.x_mm);
    assert_int_equal(g->y_mm, m->pose.y_mm);
    assert_int_equal((hl_bam_t)g->heading_bam, m->pose.theta);
    assert_memory_equal(g->mac, m->mac, HL_BUS_MAC_BYTES);
}

static void test_command_matches_generated_code(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_COMMAND_BYTES], b[HL_BUS_COMMAND_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 81);
    for (int it = 0; it < 500; it++) {
        hl_bus_command_t m = random_command(&rng), back;
        int len = hl_bus_encode_command(&m, a, sizeof a);
        assert_int_equal(len, HL_BUS_COMMAND_BYTES);
        houghloc_command_t g;
        assert_int_equal(houghloc_command_t_decode(a, 0, len, &g), len);
        assert_command_matches(&m, &g);
        assert_int_equal(houghloc_command_t_encoded_size(&g), len);
        assert_int_equal(houghloc_command_t_encode(b, 0, sizeof b, &g), len);
        assert_memory_equal(a, b, sizeof a);

        g.kind = (int8_t)tk_range(&rng, 1, 3);
        assert_int_equal(houghloc_command_t_encode(b, 0, sizeof b, &g), len);
        assert_int_equal(hl_bus_decode_command(b, sizeof b, &back, NULL), HL_OK);
        assert_command_matches(&back, &g);
        assert_int_equal(hl_bus_encode_command(&back, a, sizeof a), len);
        assert_memory_equal(a, b, sizeof a);
    }
}

static void test_command_hostile_bytes(void **state)
{
    (void)state;
    uint8_t a[HL_BUS_COMMAND_BYTES], b[HL_BUS_COMMAND_BYTES];
    hl_rng_t rng;
    hl_rng_seed(&rng, 82);
    hl_bus_command_t m = random_command(&rng), out;
    tk_codec_t c = { "command", dec_cmd, enc_cmd, NULL, &out };
    assert_int_equal(hl_bus_encode_command(&m, a, sizeof a), HL_BUS_COMMAND_BYTES);
    tk_check_truncations(&c, a, sizeof a);
    tk_check_bad_hash(&c, a, sizeof a);
    tk_check_small_buffers(&c, &m, sizeof a);
    /* offsets: 8 utime 16 seq 24 kind 25 x 29 y 33 heading 35 mac */
    struct { size_t off; uint64_t v; size_t n; const char *field; } bad[] = {
        { 8, (uint64_t)-1, 8, "utime" },
        { 16, 0, 8, "seq" },
        { 16, (uint64_t)INT64_MIN, 8, "seq" },
        { 24, 0, 1, "kind" },
        { 24, 5, 1, "kind" },
        { 24, 0x80, 1, "kind" },
        { 25, (uint32_t)-HL_COORD_MAX_MM - 1, 4, "position" },
        { 29, HL_COORD_MAX_MM + 1, 4, "position" },
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memcpy(b, a, sizeof a);
        tk_put_be(b, bad[k].off, bad[k].v, bad[k].n);
        tk_refused(&c, b, sizeof b, HL_ERR_RANGE, bad[k].field);
    }
    hl_bus_command_t q = m;
    q.kind = 0;
    assert_int_equal(hl_bus_encode_command(&q, b, sizeof b), -1);
    q.kind = 5;
    assert_int_equal(hl_bus_encode_command(&q, b, sizeof b), -1);
    q = m;
    q.seq = -5;
    assert_int_equal(hl_bus_encode_command(&q, b, sizeof b), -1);
    q = m;
    q.pose.y_mm = HL_COORD_MAX_MM + 1;
    assert_int_equal(hl_bus_encode_command(&q, b, sizeof b), -1);
    assert_in_range(tk_fuzz(&c, a, sizeof a, 5000, 83), 1, 4999);
}

/* ---- channel names ----------------------------------------------------------------- */

static void test_channel_names(void **state)
{
    (void)state;
    char out[HL_BUS_CHANNEL_MAX];
    assert_true(hl_bus_channel("", HL_CHANNEL_POSE, out));
    assert_string_equal(out, "POSE");
    assert_true(hl_bus_channel(NULL, HL_CHANNEL_SONAR, out));
    assert_string_equal(out, "SONAR");
    assert_true(hl_bus_channel("robot-2/lab.A_", HL_CHANNEL_MAP, out));
    assert_string_equal(out, "robot-2/lab.A_MAP");

    char prefix[HL_BUS_PREFIX_MAX + 2];
    memset(prefix, 'p', HL_BUS_PREFIX_MAX);
    prefix[HL_BUS_PREFIX_MAX] = '\0';
    assert_true(hl_bus_channel(prefix, HL_CHANNEL_GROUND_TRUTH, out));
    assert_int_equal(strlen(out), HL_BUS_PREFIX_MAX + strlen(HL_CHANNEL_GROUND_TRUTH));
    prefix[HL_BUS_PREFIX_MAX] = 'p';
    prefix[HL_BUS_PREFIX_MAX + 1] = '\0';
    strcpy(out, "untouched");
    assert_false(hl_bus_channel(prefix, HL_CHANNEL_POSE, out));
    assert_string_equal(out, "untouched");

    const char *bad[] = { "a b", "a\nb", "a*", "a;", "x$", "\xc3\xa9" };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_false(hl_bus_channel(bad[k], HL_CHANNEL_POSE, out));
    assert_false(hl_bus_channel("", "", out));
    assert_false(hl_bus_channel("", NULL, out));
    assert_false(hl_bus_channel("", "POSE", NULL));
    assert_false(hl_bus_channel("", "PO SE", out));

    /* the whole name must fit: 63 characters and the NUL */
    char base[HL_BUS_CHANNEL_MAX + 1];
    memset(base, 'B', sizeof base);
    base[HL_BUS_CHANNEL_MAX - 1 - 3] = '\0';
    assert_true(hl_bus_channel("abc", base, out));
    assert_int_equal(strlen(out), HL_BUS_CHANNEL_MAX - 1);
    base[HL_BUS_CHANNEL_MAX - 1 - 3] = 'B';
    base[HL_BUS_CHANNEL_MAX - 3] = '\0';
    assert_false(hl_bus_channel("abc", base, out));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_destination_matches_generated_code),
        cmocka_unit_test(test_destination_hostile_bytes),
        cmocka_unit_test(test_command_matches_generated_code),
        cmocka_unit_test(test_command_hostile_bytes),
        cmocka_unit_test(test_channel_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
