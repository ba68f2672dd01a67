/* Tests for tools/console/destreq.c: the body of POST /destination. Good bodies give
 * the exact message; every malformed one is refused with a reason and writes nothing. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "destreq.h"
#include "houghloc/fixed.h"

static hl_status_t parse(const char *text, destreq_t *out, char *why)
{
    return destreq_parse(text, strlen(text), out, why);
}

static void test_good_bodies(void **state)
{
    (void)state;
    destreq_t r;
    char why[DESTREQ_WHY_LEN];
    assert_int_equal(parse("{\"x_m\":1.5,\"y_m\":-2}", &r, why), HL_OK);
    assert_true(r.x_m == 1.5 && r.y_m == -2.0 && !r.has_heading);
    hl_bus_destination_t d = destreq_message(&r);
    assert_int_equal(d.x_mm, 1500);
    assert_int_equal(d.y_mm, -2000);
    assert_false(d.has_heading);

    assert_int_equal(parse(" {\n\t\"heading_deg\" : 450 , \"y_m\": 0.0004 ,\"x_m\":-0.0006}\r\n",
                           &r, why), HL_OK);
    d = destreq_message(&r);
    assert_int_equal(d.x_mm, -1);
    assert_int_equal(d.y_mm, 0);
    assert_true(d.has_heading);
    assert_int_equal(d.heading, hl_bam_from_deg(90.0));

    assert_int_equal(parse("{\"x_m\":4194.304,\"y_m\":-4194.304,\"heading_deg\":null}", &r, why),
                     HL_OK);
    assert_false(r.has_heading);
    d = destreq_message(&r);
    assert_int_equal(d.x_mm, HL_COORD_MAX_MM);
    assert_int_equal(d.y_mm, -HL_COORD_MAX_MM);
    assert_int_equal(parse("{\"x_m\":1E2,\"y_m\":-0e-3,\"heading_deg\":-90.5e0}", &r, why), HL_OK);
    assert_true(r.x_m == 100.0 && r.has_heading && r.heading_deg == -90.5);
}

static void test_malformed_bodies(void **state)
{
    (void)state;
    static const struct { const char *body; hl_status_t st; const char *why; } bad[] = {
        { "", HL_ERR_PARSE, "not a JSON object" },
        { "[1,2]", HL_ERR_PARSE, "not a JSON object" },
        { "{}", HL_ERR_PARSE, "x_m and y_m are required" },
        { "{\"x_m\":1}", HL_ERR_PARSE, "x_m and y_m are required" },
        { "{\"x_m\":1,\"y_m\":2", HL_ERR_PARSE, "expected ',' or '}'" },
        { "{\"x_m\":1,\"y_m\":2}}", HL_ERR_PARSE, "bytes after the object" },
        { "{\"x_m\":1,\"y_m\":2} x", HL_ERR_PARSE, "bytes after the object" },
        { "{\"x_m\":1,\"x_m\":2,\"y_m\":3}", HL_ERR_PARSE, "appears twice" },
        { "{\"x_m\":1,\"y_m\":2,\"z\":3}", HL_ERR_PARSE, "unknown member" },
        { "{\"x\\u005fm\":1,\"y_m\":2}", HL_ERR_PARSE, "unknown member" },
        { "{\"x_m\":\"1\",\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":+1,\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":01,\"y_m\":2}", HL_ERR_PARSE, "expected ',' or '}'" },
        { "{\"x_m\":1.,\"y_m\":2}", HL_ERR_PARSE, "no digit after its '.'" },
        { "{\"x_m\":.5,\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":1e,\"y_m\":2}", HL_ERR_PARSE, "no digit in its exponent" },
        { "{\"x_m\":0x10,\"y_m\":2}", HL_ERR_PARSE, "expected ',' or '}'" },
        { "{\"x_m\":NaN,\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":Infinity,\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":null,\"y_m\":2}", HL_ERR_PARSE, "not a number" },
        { "{\"x_m\":1e999,\"y_m\":2}", HL_ERR_RANGE, "not finite" },
        { "{\"x_m\":1,\"y_m\":2,\"heading_deg\":-1e400}", HL_ERR_RANGE, "not finite" },
        { "{\"x_m\":4194.3045,\"y_m\":0}", HL_ERR_RANGE, "x_m is outside" },
        { "{\"x_m\":0,\"y_m\":-5000}", HL_ERR_RANGE, "y_m is outside" },
        { "{\"x_m\" 1,\"y_m\":2}", HL_ERR_PARSE, "expected ':'" },
        { "{\"x_m\":1,,\"y_m\":2}", HL_ERR_PARSE, "member name" },
        { "{\"x_m\":1,\"y_m\":2,}", HL_ERR_PARSE, "member name" },
        { "{\"x_m", HL_ERR_PARSE, "not closed" },
        { "{\"x_m\":1000000000000000000000000000000000000000000000000000000000000000,\"y_m\":1}",
          HL_ERR_PARSE, "longer than 63" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        destreq_t r = { .x_m = 123.0 };
        char why[DESTREQ_WHY_LEN] = "";
        hl_status_t st = parse(bad[i].body, &r, why);
        if (st != bad[i].st || !strstr(why, bad[i].why))
            fail_msg("body %s: status %d, why \"%s\" (wanted %d, \"%s\")", bad[i].body, st, why,
                     bad[i].st, bad[i].why);
        assert_true(r.x_m == 123.0); /* nothing written */
    }
}

/* Length-delimited: a NUL inside, bytes past len, and the size bound. */
static void test_bounds(void **state)
{
    (void)state;
    destreq_t r;
    char why[DESTREQ_WHY_LEN];
    static const char nul[] = "{\"x_m\":1,\"y_m\":2}\0{";
    assert_int_equal(destreq_parse(nul, sizeof nul - 1, &r, why), HL_ERR_PARSE);
    /* only the first len bytes count: "{"x_m":1,"y_m":2}" cut before its '}' */
    assert_int_equal(destreq_parse(nul, 16, &r, why), HL_ERR_PARSE);
    assert_int_equal(destreq_parse(nul, 17, &r, why), HL_OK);
    char big[DESTREQ_MAX_BYTES + 2];
    memset(big, ' ', sizeof big);
    memcpy(big, "{\"x_m\":1,\"y_m\":2}", 17);
    assert_int_equal(destreq_parse(big, DESTREQ_MAX_BYTES, &r, why), HL_OK);
    assert_int_equal(destreq_parse(big, DESTREQ_MAX_BYTES + 1, &r, why), HL_ERR_ARG);
    assert_int_equal(destreq_parse(NULL, 0, &r, NULL), HL_ERR_ARG);
    assert_int_equal(destreq_parse("{}", 2, NULL, NULL), HL_ERR_ARG);
    /* every prefix of a good body is refused (and read within its length: ASan) */
    static const char good[] = "{\"x_m\":-12.5e-1,\"y_m\":3,\"heading_deg\":null}";
    for (size_t n = 0; n < sizeof good - 1; n++)
        assert_int_not_equal(destreq_parse(good, n, &r, NULL), HL_OK);
    assert_int_equal(destreq_parse(good, sizeof good - 1, &r, NULL), HL_OK);
    assert_true(r.x_m == -1.25);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_bodies),
        cmocka_unit_test(test_malformed_bodies),
        cmocka_unit_test(test_bounds),
    };
    return cmocka_run_group_tests_name("console_destreq", tests, NULL, NULL);
}
