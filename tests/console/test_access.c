/* Tests for tools/console/access.c: token generation, checking and loading, the Host
 * check against DNS rebinding, and the verdict for requests under both bind modes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "access.h"

#define TOKEN "0123456789abcdef0123456789abcdef"

static access_policy_t policy(bool loopback)
{
    access_policy_t p = { .loopback = loopback, .port = 8047, .token = TOKEN,
                          .token_len = sizeof TOKEN - 1 };
    snprintf(p.bound_host, sizeof p.bound_host, "%s", loopback ? "127.0.0.1" : "10.0.0.5");
    return p;
}

static void test_generate(void **state)
{
    (void)state;
    char a[ACCESS_TOKEN_MAX + 1], b[ACCESS_TOKEN_MAX + 1];
    assert_true(access_token_generate(a));
    assert_true(access_token_generate(b));
    assert_int_equal(strlen(a), 32);
    assert_int_equal(strspn(a, "0123456789abcdef"), 32);
    assert_true(access_token_valid(a, strlen(a)));
    assert_string_not_equal(a, b);
}

static void test_valid_and_matches(void **state)
{
    (void)state;
    assert_true(access_token_valid("abcdefghijklmnop", 16));
    assert_false(access_token_valid("abcdefghijklmno", 15));
    assert_true(access_token_valid("A-_.~bcdefghijklmnop", 20));
    assert_false(access_token_valid("abcdefgh ijklmnop", 17));
    assert_false(access_token_valid("abcdefgh&ijklmnop", 17));
    char long_token[ACCESS_TOKEN_MAX + 2];
    memset(long_token, 'a', sizeof long_token);
    assert_true(access_token_valid(long_token, ACCESS_TOKEN_MAX));
    assert_false(access_token_valid(long_token, ACCESS_TOKEN_MAX + 1));

    access_policy_t p = policy(false);
    assert_true(access_token_matches(&p, TOKEN));
    assert_false(access_token_matches(&p, NULL));
    assert_false(access_token_matches(&p, ""));
    assert_false(access_token_matches(&p, TOKEN "0"));
    assert_false(access_token_matches(&p, "0123456789abcdef0123456789abcdeF"));
    assert_false(access_token_matches(&p, "0123456789abcdef0123456789abcde"));
    p.token_len = 0; /* no token set: nothing matches, not even "" */
    p.token[0] = '\0';
    assert_false(access_token_matches(&p, ""));
}

static void test_host(void **state)
{
    (void)state;
    access_policy_t p = policy(true);
    assert_true(access_host_ok(&p, "127.0.0.1:8047"));
    assert_true(access_host_ok(&p, "localhost:8047"));
    assert_true(access_host_ok(&p, "LOCALHOST:8047"));
    assert_true(access_host_ok(&p, "[::1]:8047"));
    assert_false(access_host_ok(&p, NULL));
    assert_false(access_host_ok(&p, "evil.example:8047"));     /* DNS rebinding */
    assert_false(access_host_ok(&p, "localhost.evil.example:8047"));
    assert_false(access_host_ok(&p, "127.0.0.1:80470"));
    assert_false(access_host_ok(&p, "127.0.0.1:8048"));
    assert_false(access_host_ok(&p, "127.0.0.1"));              /* port 80 only */
    p.port = 80;
    assert_true(access_host_ok(&p, "localhost"));
    access_policy_t open = policy(false);
    assert_true(access_host_ok(&open, "robot.local:8047")); /* the token guards it */
}

static void test_decide(void **state)
{
    (void)state;
    access_policy_t lo = policy(true), open = policy(false);
    const char *h = "127.0.0.1:8047";
    /* loopback: viewing needs no token; a POST needs it in the header, never the URL */
    assert_int_equal(access_decide(&lo, &(access_request_t){ .host = h }), ACCESS_ALLOW);
    assert_int_equal(access_decide(&lo, &(access_request_t){ .host = "evil:8047" }),
                     ACCESS_BAD_HOST);
    assert_int_equal(access_decide(&lo, &(access_request_t){ .changes_state = true, .host = h }),
                     ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&lo, &(access_request_t){ .changes_state = true, .host = h,
                                                             .query_token = TOKEN }),
                     ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&lo, &(access_request_t){ .changes_state = true, .host = h,
                                                             .header_token = "wrong" }),
                     ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&lo, &(access_request_t){ .changes_state = true, .host = h,
                                                             .header_token = TOKEN }),
                     ACCESS_ALLOW);
    /* the Host check comes first, even with the token */
    assert_int_equal(access_decide(&lo, &(access_request_t){ .changes_state = true,
                                                             .host = "evil:8047",
                                                             .header_token = TOKEN }),
                     ACCESS_BAD_HOST);
    /* open bind: everything needs the token; a GET may carry it in the URL */
    const char *oh = "10.0.0.5:8047";
    assert_int_equal(access_decide(&open, &(access_request_t){ .host = oh }), ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&open, &(access_request_t){ .host = oh, .query_token = "x" }),
                     ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&open, &(access_request_t){ .host = oh, .query_token = TOKEN }),
                     ACCESS_ALLOW);
    assert_int_equal(access_decide(&open, &(access_request_t){ .host = oh, .header_token = TOKEN }),
                     ACCESS_ALLOW);
    assert_int_equal(access_decide(&open, &(access_request_t){ .changes_state = true, .host = oh,
                                                               .query_token = TOKEN }),
                     ACCESS_NEED_TOKEN);
    assert_int_equal(access_decide(&open, &(access_request_t){ .changes_state = true, .host = oh,
                                                               .header_token = TOKEN }),
                     ACCESS_ALLOW);
}

static void write_file(const char *path, const char *text, mode_t mode)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    assert_int_equal(chmod(path, mode), 0);
}

static void test_load(void **state)
{
    (void)state;
    char dir[] = "/tmp/hl_console_tokXXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128], out[ACCESS_TOKEN_MAX + 1] = "", why[ACCESS_WHY_LEN] = "";
    snprintf(path, sizeof path, "%s/token", dir);
    write_file(path, "s3cret-token_for.the~console\n", 0600);
    assert_int_equal(access_token_load(path, out, why), HL_OK);
    assert_string_equal(out, "s3cret-token_for.the~console");
    write_file(path, "s3cret-token_for.the~console\r\n", 0400);
    assert_int_equal(access_token_load(path, out, why), HL_OK);
    assert_string_equal(out, "s3cret-token_for.the~console");
    chmod(path, 0600);
    write_file(path, "s3cret-token_for.the~console\n", 0644);
    assert_int_equal(access_token_load(path, out, why), HL_ERR_RANGE);
    assert_non_null(strstr(why, "chmod 600"));
    write_file(path, "short\n", 0600);
    assert_int_equal(access_token_load(path, out, why), HL_ERR_PARSE);
    assert_non_null(strstr(why, "holds no token"));
    write_file(path, "two lines of token\nsecond\n", 0600);
    assert_int_equal(access_token_load(path, out, why), HL_ERR_PARSE);
    char big[400];
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    write_file(path, big, 0600);
    assert_int_equal(access_token_load(path, out, why), HL_ERR_RANGE);
    assert_non_null(strstr(why, "longer than 256"));
    assert_int_equal(access_token_load(dir, out, why), HL_ERR_RANGE);
    assert_non_null(strstr(why, "not a regular file"));
    unlink(path);
    assert_int_equal(access_token_load(path, out, why), HL_ERR_OS);
    assert_non_null(strstr(why, "No such file"));
    rmdir(dir);
    assert_string_equal(out, "s3cret-token_for.the~console"); /* untouched by failures */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_generate),
        cmocka_unit_test(test_valid_and_matches),
        cmocka_unit_test(test_host),
        cmocka_unit_test(test_decide),
        cmocka_unit_test(test_load),
    };
    return cmocka_run_group_tests_name("console_access", tests, NULL, NULL);
}
