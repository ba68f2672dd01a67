/* test_cycle_save.c - when the map is saved (src/daemon/cycle_save.c): SAVE requests write
 * at most once per HL_CYCLE_SAVE_MIN_INTERVAL_MS; inside it an unchanged map is answered
 * at once with the last write's age, a changed one waits for the interval's end and is
 * answered when written, surplus requests superseded meanwhile. The test plays the loop
 * (loop.c's save: the map file's side of "changed" is maplock's) with a fake clock. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>

#include "support.h"

#define S 1000000   /* one second on the fake clock, us */

static void send_save(hl_cycle_t *c, int64_t seq)
{
    hl_bus_command_t m = { .utime = 1, .seq = seq, .kind = HL_BUS_COMMAND_SAVE };
    uint8_t buf[HL_BUS_COMMAND_BYTES];
    int len = hl_bus_encode_command(&m, buf, sizeof buf);
    assert_true(len > 0);
    hl_cycle_on_message(c, HL_CH_COMMAND, buf, (size_t)len, 0);
}

static size_t replies(const capture_t *cap)
{
    return capture_count(cap, HL_CH_REPLY);
}

static hl_bus_reply_t reply(const capture_t *cap, size_t k)
{
    const out_msg_t *m = capture_nth(cap, HL_CH_REPLY, k);
    assert_non_null(m);
    hl_bus_reply_t r;
    assert_int_equal(hl_bus_decode_reply(m->data, m->len, &r, NULL), HL_OK);
    return r;
}

/* What loop.c does with a due save, the map having @p changed since the last write.
 * @return 'w' written, 'u' answered unchanged, 'h' held, '-' nothing due. */
static char loop_save(hl_cycle_t *c, bool changed)
{
    if (!hl_cycle_save_due(c))
        return '-';
    if (!changed) {
        hl_cycle_save_unchanged(c);
        return 'u';
    }
    if (hl_cycle_save_may_wait(c)) {
        hl_cycle_save_wait(c);
        return 'h';
    }
    hl_cycle_saved(c, true, "");
    return 'w';
}

static hl_cycle_t *fresh(capture_t **cap)
{
    *cap = calloc(1, sizeof **cap);
    (*cap)->clock_us = 100 * S;
    hl_cycle_params_t p = test_params();
    return capture_cycle(*cap, &p);
}

static void done(hl_cycle_t *c, capture_t *cap)
{
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* The first SAVE of a process is written at once, whenever it comes; so is the first after
 * the interval. */
static void test_first_save_and_after_the_interval_at_once(void **state)
{
    (void)state;
    capture_t *cap;
    hl_cycle_t *c = fresh(&cap);
    send_save(c, 1);
    assert_int_equal(loop_save(c, true), 'w');
    assert_int_equal(reply(cap, 0).seq, 1);
    assert_string_equal(reply(cap, 0).message, "map saved");
    cap->clock_us += HL_CYCLE_SAVE_MIN_INTERVAL_MS * 1000;
    send_save(c, 2);
    assert_int_equal(loop_save(c, true), 'w');
    assert_int_equal(replies(cap), 2);
    assert_string_equal(reply(cap, 1).message, "map saved");
    assert_int_equal(hl_cycle_counts(c)->saves, 2);
    done(c, cap);
}

/* Inside the interval, an unchanged map: ACCEPTED at once, saying when it was written. */
static void test_unchanged_inside_the_interval_answered_with_the_age(void **state)
{
    (void)state;
    capture_t *cap;
    hl_cycle_t *c = fresh(&cap);
    send_save(c, 1);
    assert_int_equal(loop_save(c, true), 'w');
    cap->clock_us += 1500000;
    send_save(c, 2);
    assert_int_equal(loop_save(c, false), 'u');
    hl_bus_reply_t r = reply(cap, 1);
    assert_int_equal(r.seq, 2);
    assert_int_equal(r.result, HL_BUS_REPLY_ACCEPTED);
    assert_string_equal(r.message, "map unchanged since the last save, 1.5 s ago: nothing "
                                   "written (the file holds it)");
    assert_false(hl_cycle_save_due(c));
    assert_int_equal(hl_cycle_save_wake_us(c), INT64_MAX);
    assert_int_equal(hl_cycle_counts(c)->saves, 1);
    done(c, cap);
}

/* Inside the interval, a changed map: the request waits, surplus requests are coalesced
 * into the newest, which is written and answered at the interval's end. */
static void test_changed_inside_the_interval_waits_then_is_written(void **state)
{
    (void)state;
    capture_t *cap;
    hl_cycle_t *c = fresh(&cap);
    send_save(c, 1);
    assert_int_equal(loop_save(c, true), 'w');
    int64_t written = cap->clock_us;
    cap->clock_us += 1 * S;
    send_save(c, 2);
    assert_int_equal(loop_save(c, true), 'h');
    assert_int_equal(replies(cap), 1);                  /* not answered yet */
    assert_true(hl_cycle_save_wake_us(c) == written + HL_CYCLE_SAVE_MIN_INTERVAL_MS * 1000);
    /* 1,000 more inside the interval: each supersedes the one before, nothing written */
    for (int64_t seq = 3; seq <= 1002; seq++) {
        cap->clock_us += 3000;
        send_save(c, seq);
        assert_int_equal(loop_save(c, true), '-');
    }
    assert_int_equal(replies(cap), 1 + 1000);
    hl_bus_reply_t r = reply(cap, 1);
    assert_int_equal(r.seq, 2);
    assert_int_equal(r.result, HL_BUS_REPLY_ACCEPTED);
    assert_string_equal(r.message, "superseded by SAVE request 3, which the next save answers");
    assert_int_equal(hl_cycle_counts(c)->saves, 1);
    cap->clock_us = written + HL_CYCLE_SAVE_MIN_INTERVAL_MS * 1000 - 1;
    assert_int_equal(loop_save(c, true), '-');
    cap->clock_us += 1;
    assert_int_equal(loop_save(c, true), 'w');
    r = reply(cap, replies(cap) - 1);
    assert_int_equal(r.seq, 1002);
    assert_string_equal(r.message, "map saved");
    assert_int_equal(replies(cap), 1 + 1000 + 1);       /* one answer for every request */
    assert_int_equal(hl_cycle_counts(c)->saves, 2);
    assert_int_equal(hl_cycle_save_wake_us(c), INT64_MAX);
    done(c, cap);
}

/* daemon.save_every's saves are not held back; one due answers a waiting request. */
static void test_save_every_is_not_held(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    cap->clock_us = 100 * S;
    hl_cycle_params_t p = test_params();
    p.save_every = 2;
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 2);
    assert_true(hl_cycle_save_due(c));
    assert_false(hl_cycle_save_may_wait(c));
    assert_int_equal(loop_save(c, true), 'w');
    cap->clock_us += S;
    send_save(c, 5);
    assert_int_equal(loop_save(c, true), 'h');
    load_tour();
    size_t scans = 0;
    for (size_t i = 0; i < n_tour && scans < 4; i++) {  /* scans 3 and 4: save_every due */
        scans += tour[i].ch == HL_CH_SONAR;
        if (scans > 2)
            hl_cycle_on_message(c, tour[i].ch, tour[i].data, tour[i].len, tour[i].utime);
    }
    assert_true(hl_cycle_save_due(c));
    assert_false(hl_cycle_save_may_wait(c));
    assert_int_equal(loop_save(c, true), 'w');
    hl_bus_reply_t r = reply(cap, replies(cap) - 1);
    assert_int_equal(r.seq, 5);
    assert_string_equal(r.message, "map saved");
    done(c, cap);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_save_and_after_the_interval_at_once),
        cmocka_unit_test(test_unchanged_inside_the_interval_answered_with_the_age),
        cmocka_unit_test(test_changed_inside_the_interval_waits_then_is_written),
        cmocka_unit_test(test_save_every_is_not_held),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
