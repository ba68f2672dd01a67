/* test_cycle.c - the daemon's state machine, driven directly with a fake clock. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "houghloc/auth.h"
#include "support.h"

static hl_bus_pose_t pose_of(const out_msg_t *m)
{
    hl_bus_pose_t p;
    assert_non_null(m);
    assert_int_equal(hl_bus_decode_pose(m->data, m->len, &p, NULL), HL_OK);
    return p;
}

static hl_bus_reply_t reply_of(const out_msg_t *m)
{
    hl_bus_reply_t r;
    assert_non_null(m);
    assert_int_equal(hl_bus_decode_reply(m->data, m->len, &r, NULL), HL_OK);
    return r;
}

static hl_bus_status_t last_status(const capture_t *cap)
{
    size_t n = capture_count(cap, HL_CH_STATUS);
    assert_true(n > 0);
    hl_bus_status_t s;
    const out_msg_t *m = capture_nth(cap, HL_CH_STATUS, n - 1);
    assert_int_equal(hl_bus_decode_status(m->data, m->len, &s, NULL), HL_OK);
    return s;
}

/* Every scan is answered with exactly one POSE carrying its seq and time. */
static void test_one_pose_per_scan(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.start = (hl_pose_t){ 1000, -2000, 0x4000 };
    hl_cycle_t *c = capture_cycle(cap, &p);
    assert_non_null(c);
    feed_tour(c, 12);
    assert_int_equal(capture_count(cap, HL_CH_POSE), 12);
    size_t k = 0;
    for (size_t i = 0; i < n_tour && k < 12; i++) {
        if (tour[i].ch != HL_CH_SONAR)
            continue;
        hl_bus_scan_t *in = malloc(sizeof *in);
        assert_int_equal(hl_bus_decode_scan(tour[i].data, tour[i].len, in, NULL), HL_OK);
        hl_bus_pose_t out = pose_of(capture_nth(cap, HL_CH_POSE, k));
        assert_int_equal(out.scan_seq, in->seq);
        assert_true(out.utime == in->utime);
        if (k == 0) {   /* the first scan lands on the start pose: nothing to localize against */
            assert_int_equal(out.status, HL_BUS_POSE_ODOMETRY_ONLY);
            assert_int_equal(out.pose.x_mm, 1000);
            assert_int_equal(out.pose.y_mm, -2000);
            assert_int_equal(out.pose.theta, 0x4000);
        } else {
            assert_int_not_equal(out.status, HL_BUS_POSE_ODOMETRY_ONLY);
        }
        free(in);
        k++;
    }
    const hl_cycle_counts_t *n = hl_cycle_counts(c);
    assert_int_equal(n->scans, 12);
    assert_int_equal(n->accepted + n->rejected_wild + n->odometry_only + n->relocalized +
                     n->lost, 12);
    assert_true(n->accepted >= 9);
    hl_cycle_tick(c, 0);
    hl_bus_status_t s = last_status(cap);
    assert_int_equal(s.state, HL_BUS_STATE_LOCALIZING);
    assert_int_equal(s.scans, 12);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* The same input gives byte-identical POSE and MAP, whatever the clock says. */
static void test_output_is_deterministic(void **state)
{
    (void)state;
    capture_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    b->clock_step_us = 777;     /* compute times differ; POSE and MAP must not */
    hl_cycle_params_t p = test_params();
    hl_cycle_t *ca = capture_cycle(a, &p), *cb = capture_cycle(b, &p);
    feed_tour(ca, 20);
    feed_tour(cb, 20);
    hl_chan_t chans[] = { HL_CH_POSE, HL_CH_MAP };
    for (int j = 0; j < 2; j++) {
        size_t n = capture_count(a, chans[j]);
        assert_true(n > 0);
        assert_int_equal(n, capture_count(b, chans[j]));
        for (size_t i = 0; i < n; i++) {
            const out_msg_t *x = capture_nth(a, chans[j], i), *y = capture_nth(b, chans[j], i);
            assert_int_equal(x->len, y->len);
            assert_memory_equal(x->data, y->data, x->len);
        }
    }
    hl_cycle_destroy(ca);
    hl_cycle_destroy(cb);
    capture_clear(a);
    capture_clear(b);
    free(a);
    free(b);
}

/* Garbage, truncated and malformed messages between real scans change nothing. */
static void test_garbage_leaves_poses_unchanged(void **state)
{
    (void)state;
    capture_t *clean = calloc(1, sizeof *clean), *dirty = calloc(1, sizeof *dirty);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *a = capture_cycle(clean, &p), *b = capture_cycle(dirty, &p);
    feed_tour(a, 10);
    load_tour();
    uint32_t x = 12345;
    size_t scans = 0, injected = 0;
    uint8_t junk[600];
    for (size_t i = 0; i < n_tour && scans < 10; i++) {
        const event_t *e = &tour[i];
        hl_cycle_on_message(b, e->ch, e->data, e->len, e->utime);
        scans += e->ch == HL_CH_SONAR;
        if (i % 7 != 0)
            continue;
        for (size_t k = 0; k < sizeof junk; k++)
            junk[k] = (uint8_t)((x = x * 1103515245u + 12345u) >> 16);
        hl_chan_t ch = (hl_chan_t)(injected % 4);     /* every input channel */
        hl_cycle_on_message(b, ch, junk, (x >> 8) % sizeof junk, e->utime);
        hl_cycle_on_message(b, e->ch, e->data, e->len / 2, e->utime);     /* truncated */
        hl_cycle_on_message(b, e->ch, e->data, e->len, e->utime);         /* a replay */
        injected++;
    }
    assert_true(injected > 10);
    size_t n = capture_count(clean, HL_CH_POSE);
    assert_int_equal(n, 10);
    assert_int_equal(capture_count(dirty, HL_CH_POSE), n);
    for (size_t i = 0; i < n; i++) {
        const out_msg_t *u = capture_nth(clean, HL_CH_POSE, i), *v = capture_nth(dirty, HL_CH_POSE, i);
        assert_int_equal(u->len, v->len);
        assert_memory_equal(u->data, v->data, u->len);
    }
    assert_true(hl_cycle_counts(b)->bad_messages >= (int32_t)(2 * injected));
    assert_true(hl_cycle_last_error(b)[0] != '\0');
    assert_int_equal(hl_cycle_counts(a)->bad_messages, 0);
    hl_cycle_destroy(a);
    hl_cycle_destroy(b);
    capture_clear(clean);
    capture_clear(dirty);
    free(clean);
    free(dirty);
}

/* MAP goes out when the map changes, at most once per map_period_ms of message time. */
static void test_map_rate(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 10);
    size_t every = capture_count(cap, HL_CH_MAP);
    assert_true(every >= 9);    /* period 0: every change */
    hl_cycle_destroy(c);
    capture_clear(cap);

    p.map_period_ms = 3600000;  /* an hour: only the first, then the flush */
    c = capture_cycle(cap, &p);
    feed_tour(c, 10);
    assert_int_equal(capture_count(cap, HL_CH_MAP), 1);
    hl_cycle_flush_map(c);
    assert_int_equal(capture_count(cap, HL_CH_MAP), 2);
    hl_bus_map_t m = { .max_vectors = HL_MAP_MAX_CAPACITY };
    m.vectors = malloc(HL_MAP_MAX_CAPACITY * sizeof *m.vectors);
    const out_msg_t *last = capture_nth(cap, HL_CH_MAP, 1);
    assert_int_equal(hl_bus_decode_map(last->data, last->len, &m, NULL), HL_OK);
    assert_int_equal(m.count, hl_map_count(hl_slam_map(hl_cycle_slam(c))));
    assert_int_equal(m.version, hl_map_version(hl_slam_map(hl_cycle_slam(c))));
    hl_cycle_flush_map(c);      /* nothing new: nothing sent */
    assert_int_equal(capture_count(cap, HL_CH_MAP), 2);
    free(m.vectors);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

static void send_destination(hl_cycle_t *c, int64_t seq, double x_m, double y_m,
                             const hl_auth_key_t *key)
{
    hl_bus_destination_t d = { .utime = 1, .seq = seq, .x_mm = (int32_t)(x_m * 1000),
                               .y_mm = (int32_t)(y_m * 1000) };
    if (key)
        assert_true(hl_auth_sign_destination(key, "", &d));
    uint8_t buf[HL_BUS_DESTINATION_BYTES];
    int len = hl_bus_encode_destination(&d, buf, sizeof buf);
    assert_true(len > 0);
    hl_cycle_on_message(c, HL_CH_DESTINATION, buf, (size_t)len, 0);
}

static void send_command(hl_cycle_t *c, int64_t seq, int8_t kind, hl_pose_t pose,
                         const hl_auth_key_t *key)
{
    hl_bus_command_t m = { .utime = 1, .seq = seq, .kind = kind, .pose = pose };
    if (key)
        assert_true(hl_auth_sign_command(key, "", &m));
    uint8_t buf[HL_BUS_COMMAND_BYTES];
    int len = hl_bus_encode_command(&m, buf, sizeof buf);
    assert_true(len > 0);
    hl_cycle_on_message(c, HL_CH_COMMAND, buf, (size_t)len, 0);
}

static hl_bus_reply_t last_reply(const capture_t *cap)
{
    size_t n = capture_count(cap, HL_CH_REPLY);
    assert_true(n > 0);
    return reply_of(capture_nth(cap, HL_CH_REPLY, n - 1));
}

/* Destinations: the fence, replays, and no robot to drive. */
static void test_destinations(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    send_destination(c, 10, 2.0, 3.0, NULL);
    hl_bus_reply_t r = last_reply(cap);
    assert_true(r.seq == 10);
    assert_int_equal(r.result, HL_BUS_REPLY_NO_ROBOT);
    send_destination(c, 11, 12.0, 0.0, NULL);  /* the fence is +-10 m */
    r = last_reply(cap);
    assert_true(r.seq == 11);
    assert_int_equal(r.result, HL_BUS_REPLY_REJECTED_FENCE);
    send_destination(c, 11, 1.0, 1.0, NULL);   /* seq not above the last accepted */
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    send_destination(c, 5, 1.0, 1.0, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    assert_int_equal(capture_count(cap, HL_CH_REPLY), 4);
    assert_int_equal(hl_cycle_counts(c)->rejected_requests, 3);
    uint8_t junk[10] = { 1, 2, 3 };
    hl_cycle_on_message(c, HL_CH_DESTINATION, junk, sizeof junk, 0);
    assert_int_equal(capture_count(cap, HL_CH_REPLY), 4);   /* no seq to answer */
    assert_int_equal(hl_cycle_counts(c)->bad_messages, 1);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* With a key: unsigned and forged requests are refused and cannot advance the seq. */
static void test_authentication(void **state)
{
    (void)state;
    assert_true(hl_auth_init());
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.authenticate = true;
    memset(p.key.bytes, 0x5a, sizeof p.key.bytes);
    hl_auth_key_t wrong;
    memset(wrong.bytes, 0x5b, sizeof wrong.bytes);
    hl_cycle_t *c = capture_cycle(cap, &p);
    send_destination(c, 100, 1.0, 1.0, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_AUTH);
    send_destination(c, 1000, 1.0, 1.0, &wrong);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_AUTH);
    send_command(c, 1001, HL_BUS_COMMAND_SAVE, (hl_pose_t){ 0 }, &wrong);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_AUTH);
    assert_false(hl_cycle_save_due(c));
    /* the forged seq 1000 did not count: 101 is still fresh */
    send_destination(c, 101, 1.0, 1.0, &p.key);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_NO_ROBOT);
    send_destination(c, 101, 1.0, 1.0, &p.key);     /* a recorded, signed message again */
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_REJECTED_REPLAY);
    assert_int_equal(hl_cycle_counts(c)->rejected_requests, 4);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* SET_POSE before the first scan places it; after, it moves the estimate, map kept. */
static void test_set_pose(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *c = capture_cycle(cap, &p);
    hl_pose_t placed = { 3000, 4000, hl_bam_from_deg(90) };
    send_command(c, 1, HL_BUS_COMMAND_SET_POSE, placed, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_ACCEPTED);
    feed_tour(c, 1);
    hl_bus_pose_t first = pose_of(capture_nth(cap, HL_CH_POSE, 0));
    assert_int_equal(first.pose.x_mm, 3000);
    assert_int_equal(first.pose.y_mm, 4000);
    assert_int_equal(first.pose.theta, placed.theta);
    feed_tour(c, 0);
    uint32_t vectors = hl_map_count(hl_slam_map(hl_cycle_slam(c)));
    assert_true(vectors > 0);
    hl_pose_t moved = { -1000, 500, 0 };
    send_command(c, 2, HL_BUS_COMMAND_SET_POSE, moved, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_ACCEPTED);
    hl_pose_t now = hl_slam_pose(hl_cycle_slam(c));
    assert_int_equal(now.x_mm, -1000);
    assert_int_equal(now.y_mm, 500);
    assert_int_equal(hl_map_count(hl_slam_map(hl_cycle_slam(c))), vectors);
    send_command(c, 3, HL_BUS_COMMAND_RELOCALIZE, moved, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_ACCEPTED);
    assert_true(hl_cycle_lost(c));
    send_command(c, 4, HL_BUS_COMMAND_SET_POSE, moved, NULL);
    assert_int_equal(last_reply(cap).result, HL_BUS_REPLY_ACCEPTED);
    assert_false(hl_cycle_lost(c));
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* SAVE is answered once the loop reports the save; save_every counts integrations. */
static void test_saving(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.save_every = 3;
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 2);
    assert_false(hl_cycle_save_due(c));
    feed_tour(c, 0);
    send_command(c, 7, HL_BUS_COMMAND_SAVE, (hl_pose_t){ 0 }, NULL);
    assert_true(hl_cycle_save_due(c));
    assert_int_equal(capture_count(cap, HL_CH_REPLY), 0);
    hl_cycle_saved(c, true, "");
    hl_bus_reply_t r = last_reply(cap);
    assert_true(r.seq == 7);
    assert_int_equal(r.result, HL_BUS_REPLY_ACCEPTED);
    assert_false(hl_cycle_save_due(c));
    assert_int_equal(hl_cycle_counts(c)->saves, 1);
    hl_cycle_destroy(c);

    capture_clear(cap);
    c = capture_cycle(cap, &p);
    feed_tour(c, 3);    /* three scans that change the map */
    assert_true(hl_cycle_save_due(c));
    hl_cycle_saved(c, false, "disk full");
    assert_false(hl_cycle_save_due(c));
    assert_string_equal(hl_cycle_last_error(c), "disk full");
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* STATUS reports the median and 99th percentile of the last compute_window scans. */
static void test_compute_statistics(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.compute_window = 10;
    cap->clock_step_us = 500;   /* two reads per scan: 500 us each */
    hl_cycle_t *c = capture_cycle(cap, &p);
    feed_tour(c, 4);
    hl_cycle_tick(c, 0);
    hl_bus_status_t s = last_status(cap);
    assert_int_equal(s.compute_samples, 4);
    assert_int_equal(s.compute_median_us, 500);
    assert_int_equal(s.compute_p99_us, 500);
    hl_cycle_destroy(c);
    capture_clear(cap);
    free(cap);
}

/* A cycle restored from a snapshot answers the next scans exactly as the original. */
static void test_restore_continues_exactly(void **state)
{
    (void)state;
    capture_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    hl_cycle_params_t p = test_params();
    hl_cycle_t *whole = capture_cycle(a, &p), *first = capture_cycle(b, &p);
    load_tour();
    size_t split = 0, scans = 0;
    for (; split < n_tour && scans < 15; split++)
        scans += tour[split].ch == HL_CH_SONAR;
    for (size_t i = 0; i < split; i++) {
        hl_cycle_on_message(whole, tour[i].ch, tour[i].data, tour[i].len, 0);
        hl_cycle_on_message(first, tour[i].ch, tour[i].data, tour[i].len, 0);
    }
    hl_mapfile_t m;
    hl_cycle_snapshot(first, &m);
    capture_t *cc = calloc(1, sizeof *cc);
    hl_cycle_t *second = capture_cycle(cc, &p);
    assert_int_equal(hl_cycle_restore(second, &m), HL_OK);
    hl_cycle_destroy(first);
    size_t before = capture_count(a, HL_CH_POSE);
    for (size_t i = split, k = 0; i < n_tour && k < 15; i++) {
        hl_cycle_on_message(whole, tour[i].ch, tour[i].data, tour[i].len, 0);
        hl_cycle_on_message(second, tour[i].ch, tour[i].data, tour[i].len, 0);
        k += tour[i].ch == HL_CH_SONAR;
    }
    size_t n = capture_count(cc, HL_CH_POSE);
    assert_int_equal(n, 15);
    assert_int_equal(capture_count(a, HL_CH_POSE), before + n);
    for (size_t i = 0; i < n; i++) {
        const out_msg_t *u = capture_nth(a, HL_CH_POSE, before + i), *v = capture_nth(cc, HL_CH_POSE, i);
        assert_int_equal(u->len, v->len);
        assert_memory_equal(u->data, v->data, u->len);
    }
    hl_map_t *ma = hl_slam_map(hl_cycle_slam(whole)), *mb = hl_slam_map(hl_cycle_slam(second));
    assert_int_equal(hl_map_count(ma), hl_map_count(mb));
    assert_memory_equal(hl_map_vectors(ma), hl_map_vectors(mb),
                        hl_map_count(ma) * sizeof(hl_vector_t));
    hl_cycle_destroy(whole);
    hl_cycle_destroy(second);
    capture_clear(a);
    capture_clear(b);
    capture_clear(cc);
    free(a);
    free(b);
    free(cc);
}

/* A restored cycle saves after its first change: a daemon killed before every save would
 * otherwise never write a newer file (found by the power-cut trial, docs/results/reliability.md). */
static void test_restored_cycle_saves_first_change(void **state)
{
    (void)state;
    capture_t *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    hl_cycle_params_t p = test_params();
    p.save_every = 5;
    hl_cycle_t *first = capture_cycle(a, &p);
    load_tour();
    size_t i = 0, scans = 0;
    for (; i < n_tour && scans < 3; i++) {
        hl_cycle_on_message(first, tour[i].ch, tour[i].data, tour[i].len, 0);
        scans += tour[i].ch == HL_CH_SONAR;
    }
    assert_false(hl_cycle_save_due(first));
    hl_mapfile_t m;
    hl_cycle_snapshot(first, &m);
    hl_cycle_t *second = capture_cycle(b, &p);
    assert_int_equal(hl_cycle_restore(second, &m), HL_OK);
    hl_cycle_destroy(first);
    assert_false(hl_cycle_save_due(second));
    uint64_t version = hl_map_version(hl_slam_map(hl_cycle_slam(second)));
    for (; i < n_tour && hl_map_version(hl_slam_map(hl_cycle_slam(second))) == version; i++)
        hl_cycle_on_message(second, tour[i].ch, tour[i].data, tour[i].len, 0);
    assert_true(hl_cycle_save_due(second));
    hl_cycle_destroy(second);
    capture_clear(a);
    capture_clear(b);
    free(a);
    free(b);
}

/* Bad parameters are refused at creation. */
static void test_bad_params(void **state)
{
    (void)state;
    capture_t *cap = calloc(1, sizeof *cap);
    hl_cycle_params_t p = test_params();
    p.compute_window = 0;
    assert_null(capture_cycle(cap, &p));
    p = test_params();
    /* each key in range, together refused (a blur of more than ten cells) */
    assert_int_equal(hl_params_set(&p.params, "localize.cell_mm", "1"), HL_OK);
    assert_null(capture_cycle(cap, &p));
    p = test_params();
    p.start.x_mm = HL_COORD_MAX_MM + 1;
    assert_null(capture_cycle(cap, &p));
    hl_cycle_io_t io = { 0 };
    p = test_params();
    assert_null(hl_cycle_create(&p, &io));
    free(cap);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_pose_per_scan),
        cmocka_unit_test(test_output_is_deterministic),
        cmocka_unit_test(test_garbage_leaves_poses_unchanged),
        cmocka_unit_test(test_map_rate),
        cmocka_unit_test(test_destinations),
        cmocka_unit_test(test_authentication),
        cmocka_unit_test(test_set_pose),
        cmocka_unit_test(test_saving),
        cmocka_unit_test(test_compute_statistics),
        cmocka_unit_test(test_restore_continues_exactly),
        cmocka_unit_test(test_restored_cycle_saves_first_change),
        cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
