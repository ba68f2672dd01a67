/* Tests for the request path's defences (cycle_requests.c, request_state.c): the request
 * state file that keeps the replay window across a crash or a new map, seqs far ahead of
 * the clock, a state that cannot be written, the channel prefix in every MAC, and signed
 * REPLY messages. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "houghloc/seqfile.h"
#include "request_state.h"
#include "support.h"

#define NOW_US 1700000000000000LL   /* the fake wall clock: Nov 2023 */
#define AHEAD_US (300 * 1000000LL)  /* auth.max_ahead_s's default */
#define PREFIX "robot1/"

/* The test's io: captured output, a settable wall clock, and the request state kept in a
 * real file through the store (or refused, to test a full disk). */
typedef struct rig {
    capture_t cap;
    int64_t wall_us;
    char state_path[256];
    bool keep_fails;
    int kept;                   /* keep_seq calls that succeeded */
} rig_t;

static int64_t rig_wall(void *ctx)
{
    return ((rig_t *)ctx)->wall_us;
}

static bool rig_keep(void *ctx, int64_t seq, char *why, size_t cap)
{
    rig_t *r = ctx;
    if (r->keep_fails) {
        snprintf(why, cap, "%s: not saved: write failed: No space left on device",
                 r->state_path);
        return false;
    }
    char reason[HL_SEQFILE_WHY_LEN];
    if (hl_seqfile_save(r->state_path, seq, reason) != HL_OK) {
        snprintf(why, cap, "%s", reason);
        return false;
    }
    r->kept++;
    return true;
}

static hl_cycle_params_t keyed_params(void)
{
    hl_cycle_params_t p = test_params();
    p.authenticate = true;
    memset(p.key.bytes, 0x5a, sizeof p.key.bytes);
    snprintf(p.prefix, sizeof p.prefix, PREFIX);
    p.max_ahead_us = AHEAD_US;
    return p;
}

static hl_cycle_t *rig_cycle(rig_t *r, const hl_cycle_params_t *p)
{
    hl_cycle_io_t io = { .emit = capture_emit, .now_us = capture_clock, .wall_us = rig_wall,
                         .keep_seq = rig_keep, .ctx = r };
    return hl_cycle_create(p, &io);
}

static int setup(void **state)
{
    rig_t *r = calloc(1, sizeof *r);
    if (!r || !hl_auth_init())
        return -1;
    snprintf(r->state_path, sizeof r->state_path, "/tmp/hl-test-cycle-auth-%ld.seq",
             (long)getpid());
    unlink(r->state_path);
    r->wall_us = NOW_US;
    *state = r;
    return 0;
}

static int teardown(void **state)
{
    rig_t *r = *state;
    capture_clear(&r->cap);
    unlink(r->state_path);
    free(r);
    return 0;
}

static hl_bus_reply_t last_reply(const capture_t *cap)
{
    size_t n = capture_count(cap, HL_CH_REPLY);
    assert_true(n > 0);
    const out_msg_t *m = capture_nth(cap, HL_CH_REPLY, n - 1);
    hl_bus_reply_t r;
    assert_int_equal(hl_bus_decode_reply(m->data, m->len, &r, NULL), HL_OK);
    return r;
}

/* A destination (x, y) signed with @p key for @p prefix, as bytes. */
static int signed_destination(int64_t seq, const hl_auth_key_t *key, const char *prefix,
                              uint8_t *buf)
{
    hl_bus_destination_t d = { .utime = 1, .seq = seq, .x_mm = 1000, .y_mm = 2000 };
    assert_true(hl_auth_sign_destination(key, prefix, &d));
    int len = hl_bus_encode_destination(&d, buf, HL_BUS_DESTINATION_BYTES);
    assert_true(len > 0);
    return len;
}

static int signed_save(int64_t seq, const hl_auth_key_t *key, uint8_t *buf)
{
    hl_bus_command_t c = { .utime = 1, .seq = seq, .kind = HL_BUS_COMMAND_SAVE };
    assert_true(hl_auth_sign_command(key, PREFIX, &c));
    int len = hl_bus_encode_command(&c, buf, HL_BUS_COMMAND_BYTES);
    assert_true(len > 0);
    return len;
}

/* A signed request accepted before a crash is refused by a daemon started afresh on a new
 * map (no map file to restore from): the state file holds its seq. */
static void test_state_survives_fresh_map(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    uint8_t req[HL_BUS_DESTINATION_BYTES], cmd[HL_BUS_COMMAND_BYTES];
    int len = signed_destination(NOW_US - 5000000, &p.key, PREFIX, req);
    int clen = signed_save(NOW_US - 4000000, &p.key, cmd);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)clen, 0);
    assert_true(hl_cycle_save_due(c));
    assert_int_equal(r->kept, 2);
    int64_t kept = 0;
    assert_int_equal(hl_seqfile_load(r->state_path, &kept, NULL), HL_OK);
    assert_true(kept == NOW_US - 4000000);
    hl_cycle_destroy(c);    /* a kill -9: nothing saved on the way out */

    /* a new cycle on an empty map; the state file read at start */
    c = rig_cycle(r, &p);
    char why[HL_REQUEST_STATE_WHY_LEN];
    assert_true(hl_request_state_open(c, r->state_path, why));
    assert_true(hl_cycle_request_seq(c) == NOW_US - 4000000);
    capture_clear(&r->cap);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)clen, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    assert_false(hl_cycle_save_due(c));
    assert_int_equal(hl_cycle_counts(c)->rejected_requests, 2);
    /* a fresh one still goes */
    len = signed_destination(NOW_US, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    hl_cycle_destroy(c);
}

/* The map file's seq and the state file's: the higher holds, and the file catches up. */
static void test_state_merges_with_map(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    assert_int_equal(hl_seqfile_save(r->state_path, NOW_US - 9000000, NULL), HL_OK);
    hl_cycle_take_request_seq(c, NOW_US - 2000000, "the map file");
    char why[HL_REQUEST_STATE_WHY_LEN];
    assert_true(hl_request_state_open(c, r->state_path, why));
    assert_true(hl_cycle_request_seq(c) == NOW_US - 2000000);
    int64_t kept = 0;
    assert_int_equal(hl_seqfile_load(r->state_path, &kept, NULL), HL_OK);
    assert_true(kept == NOW_US - 2000000);
    hl_cycle_destroy(c);
}

/* A state file that does not parse stops the start with one line saying how to reset
 * it; it is left as it was. */
static void test_corrupt_state_is_a_start_error(void **state)
{
    rig_t *r = *state;
    static const char *const bad[] = { "", "hlseq 1 17000000", "hlseq 1 1700000000000000 "
                                       "00000000\n", "garbage\n" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        FILE *f = fopen(r->state_path, "w");
        assert_non_null(f);
        fputs(bad[i], f);
        fclose(f);
        hl_cycle_params_t p = keyed_params();
        hl_cycle_t *c = rig_cycle(r, &p);
        char why[HL_REQUEST_STATE_WHY_LEN] = "";
        assert_false(hl_request_state_check(r->state_path, why));
        assert_non_null(strstr(why, "remove the file"));
        why[0] = '\0';
        assert_false(hl_request_state_open(c, r->state_path, why));
        assert_non_null(strstr(why, r->state_path));
        assert_non_null(strstr(why, "remove the file"));
        assert_null(strchr(why, '\n'));
        assert_true(hl_cycle_request_seq(c) == 0);
        hl_cycle_destroy(c);
        char text[64] = "";
        f = fopen(r->state_path, "r");
        size_t n = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        assert_int_equal(n, strlen(bad[i]));
    }
    /* no file at all is an empty state, written at once */
    unlink(r->state_path);
    assert_true(hl_request_state_check(r->state_path, (char[HL_REQUEST_STATE_WHY_LEN]){ 0 }));
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    char why[HL_REQUEST_STATE_WHY_LEN];
    assert_true(hl_request_state_open(c, r->state_path, why));
    int64_t kept = -1;
    assert_int_equal(hl_seqfile_load(r->state_path, &kept, NULL), HL_OK);
    assert_true(kept == 0);
    hl_cycle_destroy(c);
}

/* A seq far ahead of the clock is refused and does not move the window; one behind it
 * (the other clients') still goes. */
static void test_far_ahead_refused(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    uint8_t req[HL_BUS_DESTINATION_BYTES];
    int64_t year = 365LL * 86400 * 1000000;
    int len = signed_destination(NOW_US + year, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    hl_bus_reply_t rep = last_reply(&r->cap);
    assert_int_equal(rep.result, HL_BUS_REPLY_REJECTED_REPLAY);
    assert_non_null(strstr(rep.message, "31536000 s ahead of the daemon's clock"));
    assert_true(hl_cycle_request_seq(c) == 0);
    assert_int_equal(r->kept, 0);   /* nothing written either */
    /* just beyond the bound: refused; just within: taken */
    len = signed_destination(NOW_US + AHEAD_US + 1, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    len = signed_destination(NOW_US - 1000000, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    len = signed_destination(NOW_US + AHEAD_US, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    assert_int_equal(hl_cycle_counts(c)->rejected_requests, 2);
    /* the clock moves on: what was ahead comes within the bound */
    r->wall_us += year;
    len = signed_destination(NOW_US + year, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    hl_cycle_destroy(c);

    /* small seqs (hl-forge's, a test's) are behind any clock: fine */
    r->wall_us = NOW_US;
    c = rig_cycle(r, &p);
    len = signed_destination(1, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    hl_cycle_destroy(c);
}

/* A stored seq far ahead (from a client whose clock was wrong, before the bound) is
 * clamped at start: the other clients are not locked out for a year. */
static void test_far_ahead_stored_clamped(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    int64_t year = 365LL * 86400 * 1000000;
    assert_int_equal(hl_seqfile_save(r->state_path, NOW_US + year, NULL), HL_OK);
    char why[HL_REQUEST_STATE_WHY_LEN];
    assert_true(hl_request_state_open(c, r->state_path, why));
    assert_true(hl_cycle_request_seq(c) == NOW_US + AHEAD_US);
    int64_t kept = 0;
    assert_int_equal(hl_seqfile_load(r->state_path, &kept, NULL), HL_OK);
    assert_true(kept == NOW_US + AHEAD_US);
    /* the map file's, likewise */
    hl_cycle_take_request_seq(c, INT64_MAX, "the map file");
    assert_true(hl_cycle_request_seq(c) == NOW_US + AHEAD_US);
    hl_cycle_destroy(c);
}

/* A state that cannot be written: the request is refused (FAILED, saying why) and not
 * carried out, and its seq is not taken. */
static void test_state_write_failure_refuses(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    uint8_t cmd[HL_BUS_COMMAND_BYTES], req[HL_BUS_DESTINATION_BYTES];
    r->keep_fails = true;
    int len = signed_save(NOW_US, &p.key, cmd);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)len, 0);
    hl_bus_reply_t rep = last_reply(&r->cap);
    assert_int_equal(rep.result, HL_BUS_REPLY_FAILED);
    assert_non_null(strstr(rep.message, "No space left on device"));
    assert_false(hl_cycle_save_due(c));
    len = signed_destination(NOW_US + 1, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_FAILED);
    assert_int_equal(capture_count(&r->cap, HL_CH_REPLY), 2);   /* no NO_ROBOT */
    assert_true(hl_cycle_request_seq(c) == 0);
    assert_int_equal(hl_cycle_counts(c)->rejected_requests, 2);
    /* the disk has room again: the same request goes */
    r->keep_fails = false;
    len = signed_save(NOW_US, &p.key, cmd);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)len, 0);
    assert_true(hl_cycle_save_due(c));
    assert_true(hl_cycle_request_seq(c) == NOW_US);
    hl_cycle_destroy(c);

    /* STOP needs no state: it stops whatever the disk says */
    r->keep_fails = true;
    c = rig_cycle(r, &p);
    capture_clear(&r->cap);
    hl_bus_command_t stop = { .utime = 1, .seq = 5, .kind = HL_BUS_COMMAND_STOP };
    len = hl_bus_encode_command(&stop, cmd, sizeof cmd);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_ACCEPTED);
    hl_cycle_destroy(c);
}

/* A request signed with the right key for another robot's prefix is refused. */
static void test_other_prefix_refused(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    uint8_t req[HL_BUS_DESTINATION_BYTES];
    static const char *const others[] = { "", "robot2/", "robot1" };
    for (size_t i = 0; i < 3; i++) {
        int len = signed_destination(NOW_US - 10 + (int64_t)i, &p.key, others[i], req);
        hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
        assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_REJECTED_AUTH);
    }
    assert_true(hl_cycle_request_seq(c) == 0);
    int len = signed_destination(NOW_US, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    assert_int_equal(last_reply(&r->cap).result, HL_BUS_REPLY_NO_ROBOT);
    hl_cycle_destroy(c);
}

/* With a key every REPLY is signed for the prefix, refusals and STOP's included; without
 * one, none is. */
static void test_replies_signed(void **state)
{
    rig_t *r = *state;
    hl_cycle_params_t p = keyed_params();
    hl_cycle_t *c = rig_cycle(r, &p);
    uint8_t req[HL_BUS_DESTINATION_BYTES], cmd[HL_BUS_COMMAND_BYTES];
    int len = signed_destination(NOW_US, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);    /* NO_ROBOT */
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);    /* replay */
    hl_bus_command_t stop = { .utime = 1, .seq = 5, .kind = HL_BUS_COMMAND_STOP };
    len = hl_bus_encode_command(&stop, cmd, sizeof cmd);
    hl_cycle_on_message(c, HL_CH_COMMAND, cmd, (size_t)len, 0);       /* ACCEPTED */
    hl_cycle_answer(c, NOW_US, HL_BUS_REPLY_ARRIVED, "arrived");       /* the robot's */
    size_t n = capture_count(&r->cap, HL_CH_REPLY);
    assert_int_equal(n, 4);
    for (size_t i = 0; i < n; i++) {
        const out_msg_t *m = capture_nth(&r->cap, HL_CH_REPLY, i);
        hl_bus_reply_t rep;
        assert_int_equal(hl_bus_decode_reply(m->data, m->len, &rep, NULL), HL_OK);
        assert_true(hl_auth_check_reply(&p.key, PREFIX, &rep));
        assert_false(hl_auth_check_reply(&p.key, "", &rep));
    }
    hl_cycle_destroy(c);
    capture_clear(&r->cap);

    p.authenticate = false;
    r->kept = 0;
    c = rig_cycle(r, &p);
    len = signed_destination(NOW_US, &p.key, PREFIX, req);
    hl_cycle_on_message(c, HL_CH_DESTINATION, req, (size_t)len, 0);
    hl_bus_reply_t rep = last_reply(&r->cap);
    assert_int_equal(rep.result, HL_BUS_REPLY_NO_ROBOT);
    for (size_t i = 0; i < sizeof rep.mac; i++)
        assert_int_equal(rep.mac[i], 0);
    assert_int_equal(r->kept, 0);   /* and no state is kept without a key */
    hl_cycle_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_state_survives_fresh_map, setup, teardown),
        cmocka_unit_test_setup_teardown(test_state_merges_with_map, setup, teardown),
        cmocka_unit_test_setup_teardown(test_corrupt_state_is_a_start_error, setup, teardown),
        cmocka_unit_test_setup_teardown(test_far_ahead_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_far_ahead_stored_clamped, setup, teardown),
        cmocka_unit_test_setup_teardown(test_state_write_failure_refuses, setup, teardown),
        cmocka_unit_test_setup_teardown(test_other_prefix_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_replies_signed, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
