/* Tests for src/bus/auth.c: sign/check round trips for DESTINATION, COMMAND and REPLY,
 * the MAC's coverage (the channel prefix, every bit of every field, on the struct and on
 * the wire), wrong keys, unsigned messages, and key text parsing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include <sodium.h>

#include "houghloc/auth.h"

/* The channel prefix most tests sign for (lcm.prefix). */
#define P "robot1/"

static hl_auth_key_t key_a(void)
{
    hl_auth_key_t k;
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        k.bytes[i] = (uint8_t)(i * 7 + 1);
    return k;
}

static hl_auth_key_t key_b(void)
{
    hl_auth_key_t k = key_a();
    k.bytes[31] ^= 0x80; /* one bit apart */
    return k;
}

static hl_bus_destination_t sample_destination(void)
{
    hl_bus_destination_t d;
    memset(&d, 0, sizeof d);
    d.utime = 1700000000123456;
    d.seq = 1700000000123457;
    d.x_mm = -12345;
    d.y_mm = 67890;
    d.has_heading = true;
    d.heading = 12000;
    return d;
}

static hl_bus_command_t sample_command(void)
{
    hl_bus_command_t c;
    memset(&c, 0, sizeof c);
    c.utime = 1700000000223456;
    c.seq = 1700000000223457;
    c.kind = HL_BUS_COMMAND_SET_POSE;
    c.pose = (hl_pose_t){ 2500, -3500, 40000 };
    return c;
}

static int setup(void **state)
{
    (void)state;
    return hl_auth_init() ? 0 : -1;
}

static void test_destination_round_trip(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_destination_t d = sample_destination();
    assert_true(hl_auth_sign_destination(&k, P, &d));
    assert_false(sodium_is_zero(d.mac, sizeof d.mac));
    assert_true(hl_auth_check_destination(&k, P, &d));

    /* The MAC is crypto_auth over the prefix's length and bytes, then the encoded
     * message with its mac zeroed. */
    hl_bus_destination_t z = d;
    memset(z.mac, 0, sizeof z.mac);
    uint8_t buf[HL_BUS_DESTINATION_BYTES], mac[crypto_auth_BYTES];
    uint8_t signed_bytes[1 + sizeof P - 1 + HL_BUS_DESTINATION_BYTES] = { sizeof P - 1 };
    memcpy(signed_bytes + 1, P, sizeof P - 1);
    int len = hl_bus_encode_destination(&z, signed_bytes + sizeof P, HL_BUS_DESTINATION_BYTES);
    assert_int_equal(len, HL_BUS_DESTINATION_BYTES);
    crypto_auth(mac, signed_bytes, sizeof signed_bytes, k.bytes);
    assert_memory_equal(mac, d.mac, sizeof mac);

    /* Through the wire: encoded, decoded, still good. */
    len = hl_bus_encode_destination(&d, buf, sizeof buf);
    assert_int_equal(len, HL_BUS_DESTINATION_BYTES);
    hl_bus_destination_t got;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_destination(buf, (size_t)len, &got, why), HL_OK);
    assert_true(hl_auth_check_destination(&k, P, &got));

    /* Signing again gives the same MAC (deterministic, mac field ignored). */
    hl_bus_destination_t again = d;
    assert_true(hl_auth_sign_destination(&k, P, &again));
    assert_memory_equal(again.mac, d.mac, sizeof d.mac);
}

static void test_command_round_trip(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_command_t c = sample_command();
    assert_true(hl_auth_sign_command(&k, P, &c));
    assert_true(hl_auth_check_command(&k, P, &c));

    hl_bus_command_t z = c;
    memset(z.mac, 0, sizeof z.mac);
    uint8_t buf[HL_BUS_COMMAND_BYTES], mac[crypto_auth_BYTES];
    uint8_t signed_bytes[1 + sizeof P - 1 + HL_BUS_COMMAND_BYTES] = { sizeof P - 1 };
    memcpy(signed_bytes + 1, P, sizeof P - 1);
    int len = hl_bus_encode_command(&z, signed_bytes + sizeof P, HL_BUS_COMMAND_BYTES);
    assert_int_equal(len, HL_BUS_COMMAND_BYTES);
    crypto_auth(mac, signed_bytes, sizeof signed_bytes, k.bytes);
    assert_memory_equal(mac, c.mac, sizeof mac);

    len = hl_bus_encode_command(&c, buf, sizeof buf);
    hl_bus_command_t got;
    char why[HL_BUS_WHY_LEN];
    assert_int_equal(hl_bus_decode_command(buf, (size_t)len, &got, why), HL_OK);
    assert_true(hl_auth_check_command(&k, P, &got));
}

/* Flip every bit of every field, one at a time: the check must fail each time (either
 * the MAC disagrees or the flipped field no longer encodes). */
#define FLIP_ALL(type, msg, field, check)                                                  \
    do {                                                                                   \
        for (size_t byte = 0; byte < sizeof(msg).field; byte++) {                          \
            for (int bit = 0; bit < 8; bit++) {                                            \
                type m = (msg);                                                            \
                ((uint8_t *)&m.field)[byte] ^= (uint8_t)(1u << bit);                       \
                assert_false(check(&k, P, &m));                                               \
                flips++;                                                                   \
            }                                                                              \
        }                                                                                  \
    } while (0)

static void test_destination_any_flipped_bit_fails(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_destination_t d = sample_destination();
    assert_true(hl_auth_sign_destination(&k, P, &d));
    int flips = 0;
    FLIP_ALL(hl_bus_destination_t, d, utime, hl_auth_check_destination);
    FLIP_ALL(hl_bus_destination_t, d, seq, hl_auth_check_destination);
    FLIP_ALL(hl_bus_destination_t, d, x_mm, hl_auth_check_destination);
    FLIP_ALL(hl_bus_destination_t, d, y_mm, hl_auth_check_destination);
    FLIP_ALL(hl_bus_destination_t, d, heading, hl_auth_check_destination);
    FLIP_ALL(hl_bus_destination_t, d, mac, hl_auth_check_destination);
    assert_int_equal(flips, 8 * (8 + 8 + 4 + 4 + 2 + HL_BUS_MAC_BYTES));
    hl_bus_destination_t m = d;
    m.has_heading = !m.has_heading;
    assert_false(hl_auth_check_destination(&k, P, &m));
    assert_true(hl_auth_check_destination(&k, P, &d));
}

static void test_command_any_flipped_bit_fails(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_command_t c = sample_command();
    assert_true(hl_auth_sign_command(&k, P, &c));
    int flips = 0;
    FLIP_ALL(hl_bus_command_t, c, utime, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, seq, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, kind, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, pose.x_mm, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, pose.y_mm, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, pose.theta, hl_auth_check_command);
    FLIP_ALL(hl_bus_command_t, c, mac, hl_auth_check_command);
    assert_int_equal(flips, 8 * (8 + 8 + 1 + 4 + 4 + 2 + HL_BUS_MAC_BYTES));
    assert_true(hl_auth_check_command(&k, P, &c));
}

/* On the wire: every bit of the encoded message, fingerprint included. A flip either
 * breaks decoding or fails the check; it never yields a message that passes. */
static void test_wire_any_flipped_bit_fails(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_destination_t d = sample_destination();
    assert_true(hl_auth_sign_destination(&k, P, &d));
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = hl_bus_encode_destination(&d, buf, sizeof buf);
    assert_int_equal(len, HL_BUS_DESTINATION_BYTES);
    int decoded = 0;
    for (int i = 0; i < len * 8; i++) {
        uint8_t m[HL_BUS_DESTINATION_BYTES];
        memcpy(m, buf, sizeof m);
        m[i / 8] ^= (uint8_t)(1u << (i % 8));
        hl_bus_destination_t got;
        if (hl_bus_decode_destination(m, sizeof m, &got, NULL) == HL_OK) {
            decoded++;
            assert_false(hl_auth_check_destination(&k, P, &got));
        }
    }
    /* Most flips decode (low bits of every field): the MAC is what catches them. */
    assert_true(decoded > 8 * (8 + HL_BUS_MAC_BYTES));

    hl_bus_command_t c = sample_command();
    assert_true(hl_auth_sign_command(&k, P, &c));
    uint8_t cbuf[HL_BUS_COMMAND_BYTES];
    len = hl_bus_encode_command(&c, cbuf, sizeof cbuf);
    assert_int_equal(len, HL_BUS_COMMAND_BYTES);
    for (int i = 0; i < len * 8; i++) {
        uint8_t m[HL_BUS_COMMAND_BYTES];
        memcpy(m, cbuf, sizeof m);
        m[i / 8] ^= (uint8_t)(1u << (i % 8));
        hl_bus_command_t got;
        if (hl_bus_decode_command(m, sizeof m, &got, NULL) == HL_OK)
            assert_false(hl_auth_check_command(&k, P, &got));
    }
}

static void test_wrong_key_and_unsigned_fail(void **state)
{
    (void)state;
    hl_auth_key_t a = key_a(), b = key_b();
    hl_bus_destination_t d = sample_destination();
    assert_true(hl_auth_sign_destination(&a, P, &d));
    assert_false(hl_auth_check_destination(&b, P, &d));
    hl_bus_command_t c = sample_command();
    assert_true(hl_auth_sign_command(&a, P, &c));
    assert_false(hl_auth_check_command(&b, P, &c));

    /* Unsigned: the mac all zero. */
    memset(d.mac, 0, sizeof d.mac);
    assert_false(hl_auth_check_destination(&a, P, &d));
    memset(c.mac, 0, sizeof c.mac);
    assert_false(hl_auth_check_command(&a, P, &c));

    /* A destination's MAC does not carry over to a command with the same numbers. */
    d = sample_destination();
    assert_true(hl_auth_sign_destination(&a, P, &d));
    c = sample_command();
    c.utime = d.utime;
    c.seq = d.seq;
    memcpy(c.mac, d.mac, sizeof c.mac);
    assert_false(hl_auth_check_command(&a, P, &c));
}

static void test_sign_refuses_what_does_not_encode(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    hl_bus_destination_t d = sample_destination();
    d.x_mm = HL_COORD_MAX_MM + 1;
    assert_false(hl_auth_sign_destination(&k, P, &d));
    assert_false(hl_auth_check_destination(&k, P, &d));
    hl_bus_command_t c = sample_command();
    c.pose.y_mm = -HL_COORD_MAX_MM - 1;
    assert_false(hl_auth_sign_command(&k, P, &c));
    assert_false(hl_auth_sign_destination(NULL, P, &d));
    assert_false(hl_auth_sign_destination(&k, P, NULL));
    assert_false(hl_auth_check_command(NULL, P, &c));
    assert_false(hl_auth_check_command(&k, P, NULL));
}

/* The MAC covers the channel prefix: a request signed for one robot's channels is refused
 * by a robot on another prefix that shares the key, whatever the prefixes. */
static void test_prefix_in_mac(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a();
    static const char *const others[] = { "", "robot2/", "robot1", "robot1//", "Robot1/",
                                           "/robot1/" };
    hl_bus_destination_t d = sample_destination();
    hl_bus_command_t c = sample_command();
    hl_bus_reply_t r = { .utime = 5, .seq = 7, .result = HL_BUS_REPLY_ARRIVED };
    assert_true(hl_auth_sign_destination(&k, P, &d));
    assert_true(hl_auth_sign_command(&k, P, &c));
    assert_true(hl_auth_sign_reply(&k, P, &r));
    for (size_t i = 0; i < sizeof others / sizeof others[0]; i++) {
        assert_false(hl_auth_check_destination(&k, others[i], &d));
        assert_false(hl_auth_check_command(&k, others[i], &c));
        assert_false(hl_auth_check_reply(&k, others[i], &r));
    }
    assert_true(hl_auth_check_destination(&k, P, &d));
    assert_true(hl_auth_check_command(&k, P, &c));
    assert_true(hl_auth_check_reply(&k, P, &r));

    /* The empty prefix is a prefix like any other: signed for "", refused on "robot1/". */
    hl_bus_destination_t e = sample_destination();
    assert_true(hl_auth_sign_destination(&k, "", &e));
    assert_memory_not_equal(e.mac, d.mac, sizeof e.mac);
    assert_true(hl_auth_check_destination(&k, "", &e));
    assert_false(hl_auth_check_destination(&k, P, &e));

    /* The length goes in first: "ab" + a message never signs as "a" + 'b' + ... */
    hl_bus_command_t ab = sample_command(), a = sample_command();
    assert_true(hl_auth_sign_command(&k, "ab", &ab));
    assert_true(hl_auth_sign_command(&k, "a", &a));
    assert_memory_not_equal(ab.mac, a.mac, sizeof a.mac);

    /* No prefix, or one longer than any channel may have: refused, mac left alone. */
    char long_prefix[HL_BUS_PREFIX_MAX + 2];
    memset(long_prefix, 'p', sizeof long_prefix - 1);
    long_prefix[sizeof long_prefix - 1] = '\0';
    hl_bus_destination_t u = sample_destination();
    assert_false(hl_auth_sign_destination(&k, NULL, &u));
    assert_false(hl_auth_sign_destination(&k, long_prefix, &u));
    assert_true(sodium_is_zero(u.mac, sizeof u.mac));
    assert_false(hl_auth_check_destination(&k, NULL, &d));
    assert_false(hl_auth_check_reply(&k, long_prefix, &r));
    long_prefix[HL_BUS_PREFIX_MAX] = '\0';    /* exactly the longest: fine */
    assert_true(hl_auth_sign_destination(&k, long_prefix, &u));
    assert_true(hl_auth_check_destination(&k, long_prefix, &u));
}

/* REPLY: signed by the daemon over prefix and message; a forged one (unsigned, another
 * key, any field changed, a MAC moved from another reply) fails. */
static void test_reply_mac(void **state)
{
    (void)state;
    hl_auth_key_t k = key_a(), b = key_b();
    hl_bus_reply_t r = { .utime = 1700000000123456, .seq = 1700000000123400,
                         .result = HL_BUS_REPLY_FAILED };
    strcpy(r.message, "the robot could not get there");
    assert_true(hl_auth_sign_reply(&k, P, &r));
    assert_false(sodium_is_zero(r.mac, sizeof r.mac));
    assert_true(hl_auth_check_reply(&k, P, &r));

    /* the signed bytes: prefix, then the reply encoded with its mac zeroed */
    hl_bus_reply_t z = r;
    memset(z.mac, 0, sizeof z.mac);
    uint8_t signed_bytes[1 + sizeof P - 1 + HL_BUS_REPLY_MAX_BYTES] = { sizeof P - 1 };
    memcpy(signed_bytes + 1, P, sizeof P - 1);
    int len = hl_bus_encode_reply(&z, signed_bytes + sizeof P, HL_BUS_REPLY_MAX_BYTES);
    assert_true(len > 0);
    uint8_t mac[crypto_auth_BYTES];
    crypto_auth(mac, signed_bytes, (unsigned long long)(sizeof P + (size_t)len), k.bytes);
    assert_memory_equal(mac, r.mac, sizeof mac);

    /* through the wire */
    uint8_t buf[HL_BUS_REPLY_MAX_BYTES];
    len = hl_bus_encode_reply(&r, buf, sizeof buf);
    hl_bus_reply_t got;
    assert_int_equal(hl_bus_decode_reply(buf, (size_t)len, &got, NULL), HL_OK);
    assert_memory_equal(got.mac, r.mac, sizeof r.mac);
    assert_true(hl_auth_check_reply(&k, P, &got));

    /* forged: the result turned into ARRIVED, another seq, another text, unsigned, the
     * wrong key */
    hl_bus_reply_t f = r;
    f.result = HL_BUS_REPLY_ARRIVED;
    assert_false(hl_auth_check_reply(&k, P, &f));
    f = r;
    f.seq++;
    assert_false(hl_auth_check_reply(&k, P, &f));
    f = r;
    f.message[0] = 'T';
    assert_false(hl_auth_check_reply(&k, P, &f));
    f = r;
    f.utime--;
    assert_false(hl_auth_check_reply(&k, P, &f));
    f = r;
    memset(f.mac, 0, sizeof f.mac);
    assert_false(hl_auth_check_reply(&k, P, &f));
    assert_false(hl_auth_check_reply(&b, P, &r));
    f = r;
    assert_true(hl_auth_sign_reply(&b, P, &f));
    assert_false(hl_auth_check_reply(&k, P, &f));

    /* every bit of the encoded reply: a flip never yields one that passes */
    for (int i = 0; i < len * 8; i++) {
        uint8_t m[HL_BUS_REPLY_MAX_BYTES];
        memcpy(m, buf, (size_t)len);
        m[i / 8] ^= (uint8_t)(1u << (i % 8));
        if (hl_bus_decode_reply(m, (size_t)len, &got, NULL) == HL_OK)
            assert_false(hl_auth_check_reply(&k, P, &got));
    }
    /* a request's MAC does not make a reply with the same numbers */
    hl_bus_command_t c = sample_command();
    assert_true(hl_auth_sign_command(&k, P, &c));
    f = (hl_bus_reply_t){ .utime = c.utime, .seq = c.seq, .result = HL_BUS_REPLY_ACCEPTED };
    memcpy(f.mac, c.mac, sizeof f.mac);
    assert_false(hl_auth_check_reply(&k, P, &f));
    assert_false(hl_auth_sign_reply(NULL, P, &r));
    assert_false(hl_auth_check_reply(&k, P, NULL));
}

static const char good_hex[] =
    "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f";

static void test_parse_key_good(void **state)
{
    (void)state;
    hl_auth_key_t k;
    char why[HL_BUS_WHY_LEN];
    memset(&k, 0xAA, sizeof k);
    assert_true(hl_auth_parse_key(good_hex, 64, &k, why));
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        assert_int_equal(k.bytes[i], i);

    char text[80];
    snprintf(text, sizeof text, "%s\n", good_hex);
    memset(&k, 0, sizeof k);
    assert_true(hl_auth_parse_key(text, 65, &k, why));
    assert_int_equal(k.bytes[31], 0x1f);

    /* Upper case too. */
    const char upper[] = "FFEEDDCCBBAA99887766554433221100FFEEDDCCBBAA99887766554433221100\n";
    assert_true(hl_auth_parse_key(upper, strlen(upper), &k, NULL));
    assert_int_equal(k.bytes[0], 0xff);
    assert_int_equal(k.bytes[15], 0x00);
}

static void bad_key(const char *text, size_t len, const char *reason)
{
    hl_auth_key_t k;
    memset(&k, 0x55, sizeof k);
    char why[HL_BUS_WHY_LEN] = "";
    assert_false(hl_auth_parse_key(text, len, &k, why));
    if (!strstr(why, reason))
        fail_msg("reason \"%s\" does not say \"%s\"", why, reason);
    assert_null(strchr(why, '\n'));
    assert_null(strstr(why, "0a0b0c")); /* never echoes the key */
    for (int i = 0; i < HL_AUTH_KEY_BYTES; i++)
        assert_int_equal(k.bytes[i], 0x55); /* untouched */
}

static void test_parse_key_bad(void **state)
{
    (void)state;
    char text[160];
    bad_key("", 0, "empty");
    bad_key(good_hex, 63, "63 hexadecimal digits");
    snprintf(text, sizeof text, "%.63s\n", good_hex);
    bad_key(text, 64, "63 hexadecimal digits");
    snprintf(text, sizeof text, "%s0", good_hex);
    bad_key(text, 65, "more than 64");
    snprintf(text, sizeof text, "%s\r\n", good_hex);
    bad_key(text, 66, "extra bytes");
    snprintf(text, sizeof text, "%s\n\n", good_hex);
    bad_key(text, 66, "extra bytes");
    snprintf(text, sizeof text, "%s ", good_hex);
    bad_key(text, 65, "extra bytes");
    snprintf(text, sizeof text, " %s", good_hex);
    bad_key(text, 65, "at byte 1");
    snprintf(text, sizeof text, "0x%s", good_hex);
    bad_key(text, 66, "at byte 2");
    snprintf(text, sizeof text, "%s", good_hex);
    text[10] = 'g';
    bad_key(text, 64, "at byte 11");
    text[10] = '\0';
    bad_key(text, 64, "at byte 11");
    bad_key("00000000000000000000000000000000000000000000000000000000000000000", 64,
            "all zeros");
    hl_auth_key_t k;
    assert_false(hl_auth_parse_key(NULL, 64, &k, NULL));
    assert_false(hl_auth_parse_key(good_hex, 64, NULL, NULL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_destination_round_trip),
        cmocka_unit_test(test_command_round_trip),
        cmocka_unit_test(test_destination_any_flipped_bit_fails),
        cmocka_unit_test(test_command_any_flipped_bit_fails),
        cmocka_unit_test(test_wire_any_flipped_bit_fails),
        cmocka_unit_test(test_wrong_key_and_unsigned_fail),
        cmocka_unit_test(test_sign_refuses_what_does_not_encode),
        cmocka_unit_test(test_prefix_in_mac),
        cmocka_unit_test(test_reply_mac),
        cmocka_unit_test(test_parse_key_good),
        cmocka_unit_test(test_parse_key_bad),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
