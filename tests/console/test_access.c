/* Tests for tools/console/access.c: token generation, checking, loading and saving, the
 * Host check against DNS rebinding, the session cookie the token is exchanged for, and
 * the verdict for requests under both bind modes: every route needs the token or the
 * cookie (the event stream too, on loopback too), a POST proven by the cookie only from
 * the console's own page. */
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
    access_policy_t p;
    assert_true(access_policy_init(&p, loopback, 8047, loopback ? "127.0.0.1" : "10.0.0.5",
                                   TOKEN));
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

/* The verdict's status and its one-line reason. */
static void expect(const access_policy_t *p, access_request_t r, access_verdict_t want)
{
    access_verdict_t v = access_decide(p, &r);
    assert_int_equal(v, want);
    const char *why = access_reason(v);
    assert_non_null(why);
    assert_null(strchr(why, '\n'));
}

static void test_decide(void **state)
{
    (void)state;
    access_policy_t lo = policy(true), open = policy(false);
    const char *h = "127.0.0.1:8047", *origin = "http://127.0.0.1:8047";
    const char *cookie = lo.session;
    /* loopback: nothing without a credential, the page and the event stream included */
    expect(&lo, (access_request_t){ .host = h, .page = true }, ACCESS_NEED_TOKEN);
    expect(&lo, (access_request_t){ .host = h }, ACCESS_NEED_TOKEN); /* GET /events */
    expect(&lo, (access_request_t){ .host = "evil:8047" }, ACCESS_BAD_HOST);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h }, ACCESS_NEED_TOKEN);
    /* the token in a header: Authorization: Bearer, or X-Houghloc-Token */
    expect(&lo, (access_request_t){ .host = h, .authorization = "Bearer " TOKEN }, ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .host = h, .authorization = "bearer  " TOKEN }, ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .host = h, .authorization = "Bearer wrong" },
           ACCESS_BAD_TOKEN);
    expect(&lo, (access_request_t){ .host = h, .authorization = "Basic " TOKEN },
           ACCESS_NEED_TOKEN);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .header_token = TOKEN },
           ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .header_token = "wrong" },
           ACCESS_BAD_TOKEN);
    /* the URL's token only signs the page in; elsewhere it is no credential */
    expect(&lo, (access_request_t){ .host = h, .page = true, .query_token = TOKEN },
           ACCESS_EXCHANGE);
    expect(&lo, (access_request_t){ .host = h, .page = true, .query_token = TOKEN "0" },
           ACCESS_BAD_TOKEN);
    expect(&lo, (access_request_t){ .host = h, .query_token = TOKEN }, ACCESS_NEED_TOKEN);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .query_token = TOKEN },
           ACCESS_NEED_TOKEN);
    /* the cookie: a GET; a POST only with this console's Origin */
    expect(&lo, (access_request_t){ .host = h, .cookie = cookie }, ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .host = h, .page = true, .cookie = cookie }, ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .host = h, .cookie = TOKEN }, ACCESS_BAD_COOKIE);
    expect(&lo, (access_request_t){ .host = h, .cookie = "" }, ACCESS_BAD_COOKIE);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .cookie = cookie,
                                    .origin = origin },
           ACCESS_ALLOW);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .cookie = cookie },
           ACCESS_BAD_ORIGIN);
    /* a page of another port of this host is same-site, not same-origin */
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .cookie = cookie,
                                    .origin = "http://127.0.0.1:9000" },
           ACCESS_BAD_ORIGIN);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .cookie = cookie,
                                    .origin = "null" },
           ACCESS_BAD_ORIGIN);
    expect(&lo, (access_request_t){ .changes_state = true, .host = h, .header_token = TOKEN,
                                    .origin = "http://evil.example" },
           ACCESS_BAD_ORIGIN);
    /* the Host check comes first, even with the token */
    expect(&lo, (access_request_t){ .changes_state = true, .host = "evil:8047",
                                    .header_token = TOKEN },
           ACCESS_BAD_HOST);
    /* open bind: the same rules, any Host */
    const char *oh = "robot.local:8047";
    expect(&open, (access_request_t){ .host = oh }, ACCESS_NEED_TOKEN);
    expect(&open, (access_request_t){ .host = oh, .page = true, .query_token = "x" },
           ACCESS_BAD_TOKEN);
    expect(&open, (access_request_t){ .host = oh, .page = true, .query_token = TOKEN },
           ACCESS_EXCHANGE);
    expect(&open, (access_request_t){ .host = oh, .header_token = TOKEN }, ACCESS_ALLOW);
    expect(&open, (access_request_t){ .changes_state = true, .host = oh, .cookie = open.session,
                                      .origin = "http://robot.local:8047" },
           ACCESS_ALLOW);
    expect(&open, (access_request_t){ .changes_state = true, .cookie = open.session,
                                      .origin = "http://robot.local:8047" },
           ACCESS_BAD_ORIGIN); /* no Host to compare with */
    assert_int_equal(access_status(ACCESS_NEED_TOKEN), 401);
    assert_int_equal(access_status(ACCESS_BAD_COOKIE), 401);
    assert_int_equal(access_status(ACCESS_BAD_ORIGIN), 403);
    assert_int_equal(access_status(ACCESS_BAD_HOST), 403);
    assert_int_equal(access_status(ACCESS_EXCHANGE), 303);
}

/* The exchange: the cookie's value is not the token, is the same for the same token (a
 * restart with --token-file keeps the pages signed in) and differs for another; its name
 * carries the port; the browser keeps it from scripts and from other sites. */
static void test_cookie(void **state)
{
    (void)state;
    access_policy_t a = policy(true), b = policy(false), c;
    assert_true(access_policy_init(&c, true, 9000, "127.0.0.1", "another-token-0123456789"));
    assert_int_equal(strlen(a.session), ACCESS_SESSION_LEN);
    assert_int_equal(strspn(a.session, "0123456789abcdef"), ACCESS_SESSION_LEN);
    assert_null(strstr(a.session, TOKEN));
    assert_string_equal(a.session, b.session);
    assert_string_not_equal(a.session, c.session);
    assert_string_equal(a.cookie_name, "houghloc_8047");
    assert_string_equal(c.cookie_name, "houghloc_9000");
    char set[ACCESS_SET_COOKIE_LEN];
    access_set_cookie(&a, set);
    char want[ACCESS_SET_COOKIE_LEN];
    snprintf(want, sizeof want, "houghloc_8047=%s; Path=/; HttpOnly; SameSite=Strict", a.session);
    assert_string_equal(set, want);
    assert_null(strstr(set, TOKEN));
    /* the other console's cookie is no credential here */
    expect(&a, (access_request_t){ .host = "127.0.0.1:8047", .cookie = c.session },
           ACCESS_BAD_COOKIE);
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

/* --token-out: a new file of mode 0600 renamed over the old one, which a reader that
 * opened it before keeps seeing (without the new token); a file --token-file reads. */
static void test_save(void **state)
{
    (void)state;
    char dir[] = "/tmp/hl_console_saveXXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128], out[ACCESS_TOKEN_MAX + 1] = "", why[ACCESS_WHY_LEN] = "";
    snprintf(path, sizeof path, "%s/token", dir);
    write_file(path, "old\n", 0644);
    FILE *before = fopen(path, "r");
    assert_non_null(before);
    assert_int_equal(access_token_save(path, TOKEN, why), HL_OK);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0600);
    assert_int_equal(access_token_load(path, out, why), HL_OK);
    assert_string_equal(out, TOKEN);
    char old[16] = "";
    assert_non_null(fgets(old, sizeof old, before));
    assert_string_equal(old, "old\n");
    fclose(before);
    unlink(path);
    snprintf(path, sizeof path, "%s/no/such/dir/token", dir);
    assert_int_equal(access_token_save(path, TOKEN, why), HL_ERR_OS);
    assert_non_null(strstr(why, "No such file"));
    assert_null(strchr(why, '\n'));
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_generate),
        cmocka_unit_test(test_valid_and_matches),
        cmocka_unit_test(test_host),
        cmocka_unit_test(test_decide),
        cmocka_unit_test(test_cookie),
        cmocka_unit_test(test_save),
        cmocka_unit_test(test_load),
    };
    return cmocka_run_group_tests_name("console_access", tests, NULL, NULL);
}
