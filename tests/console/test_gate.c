/* Tests for tools/console/gate.c: who holds the console's connections. Slowloris from the
 * operator's own address cannot lock the operator out (a newcomer displaces the oldest
 * connection that has not proven the token), a proven request is never displaced, the
 * per-address and total bounds, the header deadline, and the slots coming back. Times
 * are given, not measured. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <string.h>

#include "gate.h"

static gate_t g;

static gate_addr_t v4(const char *text)
{
    struct sockaddr_in a = { .sin_family = AF_INET };
    assert_int_equal(inet_pton(AF_INET, text, &a.sin_addr), 1);
    return gate_addr_of((const struct sockaddr *)&a);
}

static void test_addresses(void **state)
{
    (void)state;
    gate_addr_t a = v4("127.0.0.1");
    static const uint8_t mapped[16] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 127, 0, 0, 1 };
    assert_memory_equal(a.b, mapped, 16);
    struct sockaddr_in6 s6 = { .sin6_family = AF_INET6, .sin6_addr = IN6ADDR_LOOPBACK_INIT };
    gate_addr_t b = gate_addr_of((const struct sockaddr *)&s6);
    assert_int_equal(b.b[15], 1);
    assert_memory_not_equal(a.b, b.b, 16);
}

/* The attack of the Console trial: far more half-open connections from 127.0.0.1 than
 * there are places, each one opened again as soon as it is closed; the operator, also
 * 127.0.0.1, gets a place at once, proves the token and keeps it. */
static void test_slowloris_from_the_operators_address(void **state)
{
    (void)state;
    gate_init(&g);
    gate_addr_t lo = v4("127.0.0.1");
    int64_t t = 1000;
    int fd = 100, victim;
    for (int i = 0; i < 500; i++) {
        int slot = gate_open(&g, &lo, fd++, t, &victim);
        assert_true(slot >= 0);                     /* every newcomer gets in ... */
        assert_true(i < GATE_PER_ADDR ? victim < 0 : victim >= 0); /* ... past the bound by
                                                                     displacing one */
        if (victim >= 0)
            gate_closed(&g, victim);                /* the server closes it */
        t++;
    }
    assert_int_equal(g.live, GATE_PER_ADDR);
    assert_int_equal(g.displaced, 500 - GATE_PER_ADDR);
    /* the operator: a place at once, the oldest attacker out */
    int op = gate_open(&g, &lo, 7, t, &victim);
    assert_true(op >= 0);
    assert_true(victim >= 0);
    assert_int_equal(g.conn[victim].state, GATE_CLOSING);
    gate_closed(&g, victim);
    gate_serving(&g, op);                           /* its request proved the token */
    /* the attack goes on: the operator's stream is never the one displaced */
    for (int i = 0; i < 1000; i++) {
        assert_true(gate_open(&g, &lo, fd++, ++t, &victim) >= 0);
        assert_true(victim >= 0 && victim != op);
        gate_closed(&g, victim);
    }
    assert_int_equal(g.conn[op].state, GATE_SERVING);
    assert_int_equal(g.conn[op].fd, 7);
}

/* Proven requests hold their places; when all of an address's places are such, a
 * newcomer from it is refused, while another address still gets in. */
static void test_serving_kept_and_refusal(void **state)
{
    (void)state;
    gate_init(&g);
    gate_addr_t a = v4("10.0.0.1"), b = v4("10.0.0.2");
    int victim;
    for (int i = 0; i < GATE_PER_ADDR; i++) {
        int slot = gate_open(&g, &a, 10 + i, 0, &victim);
        assert_true(slot >= 0);
        gate_serving(&g, slot);
    }
    assert_int_equal(gate_open(&g, &a, 999, 1, &victim), -1);
    assert_int_equal(victim, -1);
    assert_int_equal(g.refused, 1);
    int other = gate_open(&g, &b, 998, 1, &victim);
    assert_true(other >= 0);
    assert_int_equal(victim, -1);
    /* a request over, the connection waits again: it may now be displaced */
    gate_waiting(&g, 0, 2);
    int slot = gate_open(&g, &a, 997, 3, &victim);
    assert_true(slot >= 0);
    assert_int_equal(victim, 0);
}

/* The console's total: when full, a newcomer from any address displaces the oldest
 * waiting connection of any address, not a serving one. */
static void test_total_bound(void **state)
{
    (void)state;
    gate_init(&g);
    int victim, n = 0;
    /* GATE_MAX_LIVE connections from many addresses, the first half proven */
    for (int i = 0; i < GATE_MAX_LIVE; i++) {
        char text[32];
        snprintf(text, sizeof text, "10.0.%d.%d", i / 200, i % 200 + 1);
        gate_addr_t a = v4(text);
        int slot = gate_open(&g, &a, 100 + i, i, &victim);
        assert_true(slot >= 0);
        assert_int_equal(victim, -1);
        if (i < GATE_MAX_LIVE / 2)
            gate_serving(&g, slot);
        n++;
    }
    gate_addr_t fresh = v4("192.168.1.1");
    int slot = gate_open(&g, &fresh, 5, 1000, &victim);
    assert_true(slot >= 0);
    assert_int_equal(g.conn[victim].fd, 100 + GATE_MAX_LIVE / 2); /* the oldest waiting */
    assert_int_equal(g.live, GATE_MAX_LIVE);
    /* the table holds the ones told to close until the server closes them */
    for (int i = 0; i < GATE_SLOTS - GATE_MAX_LIVE - 1; i++)
        assert_true(gate_open(&g, &fresh, 6 + i, 1001, &victim) >= 0);
    assert_int_equal(gate_open(&g, &fresh, 4, 1002, &victim), -1); /* no free slot left */
    assert_int_equal(victim, -1);
}

/* A connection that has not proven the token must deliver its request within
 * GATE_HEADER_MS; one idle between requests too. A serving one has no deadline. */
static void test_header_deadline(void **state)
{
    (void)state;
    gate_init(&g);
    gate_addr_t a = v4("127.0.0.1");
    int victim;
    assert_int_equal(gate_timeout_ms(&g, 0), -1);
    int slow = gate_open(&g, &a, 10, 1000, &victim);
    int op = gate_open(&g, &a, 11, 2000, &victim);
    gate_serving(&g, op);
    assert_int_equal(gate_timeout_ms(&g, 1000), GATE_HEADER_MS);
    assert_int_equal(gate_timeout_ms(&g, 3000), GATE_HEADER_MS - 2000);
    assert_int_equal(gate_expire(&g, 1000 + GATE_HEADER_MS - 1), -1);
    assert_int_equal(gate_expire(&g, 1000 + GATE_HEADER_MS), slow);
    assert_int_equal(g.conn[slow].state, GATE_CLOSING);
    assert_int_equal(gate_expire(&g, 1000 + GATE_HEADER_MS), -1);
    assert_int_equal(gate_timeout_ms(&g, 0), -1);   /* the serving one has no deadline */
    assert_int_equal(gate_expire(&g, 1000000), -1);
    gate_waiting(&g, op, 50000);                     /* its request over: idle */
    assert_int_equal(gate_expire(&g, 50000 + GATE_HEADER_MS), op);
    assert_int_equal(g.expired, 2);
    gate_closed(&g, slow);
    gate_closed(&g, op);
    assert_int_equal(g.live, 0);
    /* a closed slot is free again, and closing twice changes nothing */
    gate_closed(&g, op);
    gate_closed(&g, -1);
    gate_closed(&g, GATE_SLOTS);
    assert_int_equal(g.live, 0);
    assert_true(gate_open(&g, &a, 12, 0, &victim) >= 0);
    assert_int_equal(g.live, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_addresses),
        cmocka_unit_test(test_slowloris_from_the_operators_address),
        cmocka_unit_test(test_serving_kept_and_refusal),
        cmocka_unit_test(test_total_bound),
        cmocka_unit_test(test_header_deadline),
    };
    return cmocka_run_group_tests_name("console_gate", tests, NULL, NULL);
}
