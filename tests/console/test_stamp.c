/* Tests for tools/console/stamp.c: the requests as they leave the console. A STOP
 * decodes as a COMMAND of kind STOP with the seq and time stamped, unsigned without a
 * key and signed with one; destinations share the same seq; the seq always increases. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "stamp.h"

static const uint8_t zero_mac[HL_BUS_MAC_BYTES];

static hl_auth_key_t test_key(uint8_t fill)
{
    hl_auth_key_t k;
    memset(k.bytes, fill, sizeof k.bytes);
    return k;
}

static void test_stop_unsigned(void **state)
{
    (void)state;
    uint8_t buf[STAMP_MAX_BYTES];
    hl_bus_command_t c;
    memset(&c, 0x5a, sizeof c); /* every field written */
    int len = stamp_stop(&c, 1700000000123456, 1700000000123457, NULL, "", buf, sizeof buf);
    assert_int_equal(len, HL_BUS_COMMAND_BYTES);
    hl_bus_command_t got;
    char why[HL_BUS_WHY_LEN] = "";
    assert_int_equal(hl_bus_decode_command(buf, (size_t)len, &got, why), HL_OK);
    assert_int_equal(got.kind, HL_BUS_COMMAND_STOP);
    assert_int_equal(got.seq, 1700000000123457);
    assert_int_equal(got.utime, 1700000000123456);
    assert_int_equal(got.pose.x_mm, 0);
    assert_int_equal(got.pose.y_mm, 0);
    assert_int_equal(got.pose.theta, 0);
    assert_memory_equal(got.mac, zero_mac, sizeof zero_mac);
    assert_memory_equal(&c.mac, zero_mac, sizeof zero_mac);
    assert_int_equal(c.seq, got.seq);
}

static void test_stop_signed(void **state)
{
    (void)state;
    assert_true(hl_auth_init());
    const hl_auth_key_t key = test_key(7), other = test_key(8);
    uint8_t buf[STAMP_MAX_BYTES];
    hl_bus_command_t c;
    int len = stamp_stop(&c, 42, 43, &key, "robot1/", buf, sizeof buf);
    assert_int_equal(len, HL_BUS_COMMAND_BYTES);
    hl_bus_command_t got;
    assert_int_equal(hl_bus_decode_command(buf, (size_t)len, &got, NULL), HL_OK);
    assert_int_equal(got.kind, HL_BUS_COMMAND_STOP);
    assert_int_equal(got.seq, 43);
    assert_int_equal(got.utime, 42);
    assert_memory_not_equal(got.mac, zero_mac, sizeof zero_mac);
    assert_true(hl_auth_check_command(&key, "robot1/", &got));
    assert_false(hl_auth_check_command(&other, "robot1/", &got));
    /* the MAC covers the prefix it was made for */
    assert_false(hl_auth_check_command(&key, "", &got));
    /* the MAC covers the seq */
    got.seq++;
    assert_false(hl_auth_check_command(&key, "robot1/", &got));
}

static void test_stop_does_not_fit(void **state)
{
    (void)state;
    uint8_t buf[STAMP_MAX_BYTES];
    hl_bus_command_t c;
    assert_int_equal(stamp_stop(&c, 1, 2, NULL, "", buf, HL_BUS_COMMAND_BYTES - 1), -1);
    /* a seq the bus refuses (not positive) does not encode either */
    assert_int_equal(stamp_stop(&c, 1, 0, NULL, "", buf, sizeof buf), -1);
}

static void test_destination(void **state)
{
    (void)state;
    assert_true(hl_auth_init());
    const hl_auth_key_t key = test_key(1);
    uint8_t buf[STAMP_MAX_BYTES];
    hl_bus_destination_t d = { .x_mm = 1250, .y_mm = -2000, .has_heading = true,
                               .heading = 16384 };
    int len = stamp_destination(&d, 100, 101, &key, "", buf, sizeof buf);
    assert_int_equal(len, HL_BUS_DESTINATION_BYTES);
    hl_bus_destination_t got;
    assert_int_equal(hl_bus_decode_destination(buf, (size_t)len, &got, NULL), HL_OK);
    assert_int_equal(got.seq, 101);
    assert_int_equal(got.utime, 100);
    assert_int_equal(got.x_mm, 1250);
    assert_int_equal(got.y_mm, -2000);
    assert_true(hl_auth_check_destination(&key, "", &got));
    len = stamp_destination(&d, 100, 102, NULL, "", buf, sizeof buf);
    assert_int_equal(hl_bus_decode_destination(buf, (size_t)len, &got, NULL), HL_OK);
    assert_memory_equal(got.mac, zero_mac, sizeof zero_mac);
}

/* The clock when it is ahead, else one above the last: destinations and stops share it. */
static void test_seq(void **state)
{
    (void)state;
    assert_int_equal(stamp_seq(1000, 0), 1000);
    assert_int_equal(stamp_seq(1000, 999), 1000);
    assert_int_equal(stamp_seq(1000, 1000), 1001);   /* two requests in one microsecond */
    assert_int_equal(stamp_seq(500, 1000), 1001);    /* the clock stepped back */
    assert_int_equal(stamp_seq(0, 0), 1);            /* never below 1 */
    assert_int_equal(stamp_seq(-5, -1), 1);
    int64_t last = 0;
    for (int i = 0; i < 100; i++) {
        int64_t s = stamp_seq(7, last);
        assert_true(s > last);
        last = s;
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stop_unsigned),
        cmocka_unit_test(test_stop_signed),
        cmocka_unit_test(test_stop_does_not_fit),
        cmocka_unit_test(test_destination),
        cmocka_unit_test(test_seq),
    };
    return cmocka_run_group_tests_name("console_stamp", tests, NULL, NULL);
}
