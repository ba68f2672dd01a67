/* Tests for src/robot/rlink.c: the ARCOS connection against a scripted robot that answers
 * with the codec's server side. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "houghloc/rlink.h"

/* The commands the client queued, decoded in order; the out-buffer is emptied. */
static int drain(hl_rlink_t *l, hl_arcos_cmd_t *cmds, int max)
{
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    size_t n, off = 0, used;
    const uint8_t *out = hl_rlink_pending(l, &n);
    hl_arcos_packet_t pkt;
    int k = 0;
    while (k < max && hl_arcos_parse(&p, out + off, n - off, &used, &pkt) == HL_OK) {
        off += used;
        assert_int_equal(hl_arcos_decode_cmd(&pkt, &cmds[k]), HL_OK);
        k++;
    }
    assert_int_equal(p.garbage_bytes, 0);
    hl_rlink_sent(l, n);
    return k;
}

static void feed_payload(hl_rlink_t *l, const uint8_t *payload, size_t n, int64_t now,
                         hl_rlink_sip_fn fn, void *ctx)
{
    uint8_t buf[HL_ARCOS_PACKET_MAX];
    size_t len;
    assert_int_equal(hl_arcos_frame(buf, sizeof buf, payload, n, &len), HL_OK);
    hl_rlink_feed(l, buf, len, now, fn, ctx);
}

static void count_sip(void *ctx, const hl_arcos_sip_t *sip)
{
    int *n = ctx;
    assert_int_equal(sip->sonar_count, 1);
    (*n)++;
}

static void feed_sip(hl_rlink_t *l, int64_t now, int *count)
{
    hl_arcos_sip_t sip = { .type = HL_ARCOS_SIP_STOPPED, .x = 100, .sonar_count = 1,
                           .sonar = { { 3, 1500 } } };
    uint8_t buf[HL_ARCOS_PACKET_MAX];
    size_t len;
    assert_int_equal(hl_arcos_encode_sip(buf, sizeof buf, &sip, &len), HL_OK);
    hl_rlink_feed(l, buf, len, now, count_sip, count);
}

/* Takes @p l through the handshake at time 0; the robot is "bonnie". */
static void handshake(hl_rlink_t *l)
{
    hl_arcos_cmd_t c[8];
    hl_rlink_begin(l, 0);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_SYNCING);
    for (uint8_t k = 0; k < 2; k++) {
        assert_int_equal(drain(l, c, 8), 1);
        assert_int_equal(c[0].number, k);
        feed_payload(l, &k, 1, 10, NULL, NULL);
    }
    assert_int_equal(drain(l, c, 8), 1);
    assert_int_equal(c[0].number, HL_ARCOS_SYNC2);
    hl_arcos_robot_id_t id = { "bonnie", "Pioneer", "bonnie" };
    uint8_t buf[HL_ARCOS_PACKET_MAX];
    size_t len;
    assert_int_equal(hl_arcos_encode_sync2(buf, sizeof buf, &id, &len), HL_OK);
    hl_rlink_feed(l, buf, len, 20, NULL, NULL);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_UP);
    assert_string_equal(l->id.name, "bonnie");
    assert_int_equal(drain(l, c, 8), 3);
    assert_int_equal(c[0].number, HL_ARCOS_OPEN);
    assert_int_equal(c[1].number, HL_ARCOS_ENABLE);
    assert_int_equal(c[1].arg, 1);
    assert_int_equal(c[2].number, HL_ARCOS_SONAR);
    assert_int_equal(c[2].arg, 1);
}

static hl_rlink_t *fresh(void)
{
    static hl_rlink_t l;
    hl_rlink_params_t p;
    hl_rlink_params_default(&p);
    assert_int_equal(hl_rlink_init(&l, &p), HL_OK);
    return &l;
}

static void test_handshake_then_sips_flow(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    handshake(l);
    int sips = 0;
    feed_sip(l, 100, &sips);
    feed_sip(l, 200, &sips);
    assert_int_equal(sips, 2);
    assert_int_equal(l->sips, 2);
    hl_arcos_cmd_t c[4];
    assert_true(hl_rlink_send_int(l, HL_ARCOS_MOVE, -250, 210));
    assert_int_equal(drain(l, c, 4), 1);
    assert_int_equal(c[0].number, HL_ARCOS_MOVE);
    assert_int_equal(c[0].arg, -250);
}

static void test_unanswered_sync_is_resent_then_given_up(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    hl_arcos_cmd_t c[4];
    hl_rlink_begin(l, 0);
    int sends = drain(l, c, 4);
    for (int64_t t = 100; t <= 5000; t += 100) {
        hl_rlink_tick(l, t);
        sends += drain(l, c, 4);
    }
    assert_int_equal(sends, 6);     /* link.sync_tries */
    assert_int_equal(hl_rlink_state(l), HL_RLINK_DOWN);
    assert_string_equal(hl_rlink_why(l), "no answer to SYNC0 after 6 tries");
}

static void test_silence_loses_the_link_and_pulses_keep_it(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    handshake(l);
    hl_arcos_cmd_t c[4];
    int sips = 0;
    /* SIPs come every 100 ms of robot time (here the wall clock runs 10 times slower);
     * the client sends nothing: a PULSE every 500 ms of robot time */
    int pulses = 0;
    for (int64_t robot = 100; robot <= 2000; robot += 100) {
        feed_sip(l, robot * 10, &sips);
        hl_rlink_keepalive(l, robot);
        hl_rlink_tick(l, robot * 10);
        int n = drain(l, c, 4);
        pulses += n == 1 && c[0].number == HL_ARCOS_PULSE;
    }
    assert_int_equal(pulses, 4);    /* at 500, 1000, 1500 and 2000 ms of robot time */
    hl_rlink_sent_at(l, 2000);
    hl_rlink_keepalive(l, 2400);    /* a command went out at 2000: none due yet */
    assert_int_equal(drain(l, c, 4), 0);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_UP);
    hl_rlink_tick(l, 21999);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_UP);
    hl_rlink_tick(l, 22000);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_DOWN);
    assert_string_equal(hl_rlink_why(l), "no packet from the robot for 2000 ms");
    assert_false(hl_rlink_send(l, HL_ARCOS_STOP, 22001));
}

/* A silent robot may still hear us (a one-way loss): STOP, then CLOSE, wait for the caller
 * to write before it closes the transport; a loss during the handshake queues none. */
static void test_silence_queues_stop_and_close(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    handshake(l);
    hl_arcos_cmd_t c[4];
    assert_true(hl_rlink_send_int(l, HL_ARCOS_MOVE, 500, 30));   /* under way, unsent */
    assert_false(hl_rlink_stop_queued(l));
    hl_rlink_tick(l, 2019);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_UP);
    hl_rlink_tick(l, 2020);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_DOWN);
    assert_true(hl_rlink_stop_queued(l));
    assert_string_equal(hl_rlink_why(l), "no packet from the robot for 2000 ms");
    assert_int_equal(drain(l, c, 4), 3);
    assert_int_equal(c[0].number, HL_ARCOS_MOVE);
    assert_int_equal(c[1].number, HL_ARCOS_STOP);
    assert_int_equal(c[2].number, HL_ARCOS_CLOSE);
    hl_rlink_tick(l, 5000);                 /* DOWN: nothing more */
    assert_int_equal(drain(l, c, 4), 0);

    hl_rlink_begin(l, 6000);                /* a new connection forgets it */
    assert_false(hl_rlink_stop_queued(l));
    assert_int_equal(drain(l, c, 4), 1);
    assert_int_equal(c[0].number, HL_ARCOS_SYNC0);
    for (int64_t t = 6100; t <= 10000; t += 100)
        hl_rlink_tick(l, t);
    assert_int_equal(hl_rlink_state(l), HL_RLINK_DOWN);   /* SYNC0 never answered */
    assert_false(hl_rlink_stop_queued(l));
    hl_arcos_cmd_t syncs[8];
    for (int k = drain(l, syncs, 8); k > 0; k--)
        assert_int_equal(syncs[k - 1].number, HL_ARCOS_SYNC0);
}

static void test_a_robot_still_streaming_is_closed_first(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    hl_arcos_cmd_t c[4];
    hl_rlink_begin(l, 0);
    drain(l, c, 4);
    int sips = 0;
    feed_sip(l, 10, &sips);
    assert_int_equal(sips, 0);          /* not delivered during the handshake */
    assert_int_equal(drain(l, c, 4), 2);
    assert_int_equal(c[0].number, HL_ARCOS_CLOSE);
    assert_int_equal(c[1].number, HL_ARCOS_SYNC0);
}

static void test_garbage_and_bad_packets_are_counted(void **state)
{
    (void)state;
    hl_rlink_t *l = fresh();
    handshake(l);
    int sips = 0;
    static const uint8_t noise[] = { 0x13, 0xFA, 0x00, 0x99, 0xFA, 0xFB, 0x04, 0x32, 0x01,
                                     0x00, 0x00 };  /* a SIP frame with a wrong checksum */
    hl_rlink_feed(l, noise, sizeof noise, 300, count_sip, &sips);
    static const uint8_t other[] = { 0x90, 1, 2, 3 };   /* a packet type we do not read */
    feed_payload(l, other, sizeof other, 310, count_sip, &sips);
    feed_sip(l, 320, &sips);
    assert_int_equal(sips, 1);
    assert_true(hl_rlink_bad_packets(l) >= 2);
    assert_int_equal(l->bad_packets, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_handshake_then_sips_flow),
        cmocka_unit_test(test_unanswered_sync_is_resent_then_given_up),
        cmocka_unit_test(test_silence_loses_the_link_and_pulses_keep_it),
        cmocka_unit_test(test_silence_queues_stop_and_close),
        cmocka_unit_test(test_a_robot_still_streaming_is_closed_first),
        cmocka_unit_test(test_garbage_and_bad_packets_are_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
