/* gate.c - who holds the console's connections (gate.h). */
#include "gate.h"

#include <netinet/in.h>
#include <string.h>

void gate_init(gate_t *g)
{
    memset(g, 0, sizeof *g);
    for (int i = 0; i < GATE_SLOTS; i++)
        g->conn[i].fd = -1;
}

gate_addr_t gate_addr_of(const struct sockaddr *sa)
{
    gate_addr_t a = { { 0 } };
    if (sa->sa_family == AF_INET6) {
        memcpy(a.b, &((const struct sockaddr_in6 *)sa)->sin6_addr, 16);
    } else if (sa->sa_family == AF_INET) {
        a.b[10] = a.b[11] = 0xff;
        memcpy(a.b + 12, &((const struct sockaddr_in *)sa)->sin_addr, 4);
    }
    return a;
}

static bool live(const gate_conn_t *c)
{
    return c->state == GATE_WAITING || c->state == GATE_SERVING;
}

/* The oldest WAITING connection, of address @p a or (NULL) of any; -1 when none. */
static int oldest_waiting(const gate_t *g, const gate_addr_t *a)
{
    int best = -1;
    for (int i = 0; i < GATE_SLOTS; i++) {
        const gate_conn_t *c = &g->conn[i];
        if (c->state != GATE_WAITING || (a && memcmp(&c->addr, a, sizeof *a) != 0))
            continue;
        if (best < 0 || c->since_ms < g->conn[best].since_ms)
            best = i;
    }
    return best;
}

static void to_closing(gate_t *g, int slot)
{
    g->conn[slot].state = GATE_CLOSING;
    g->live--;
}

int gate_open(gate_t *g, const gate_addr_t *a, int fd, int64_t now_ms, int *victim)
{
    *victim = -1;
    unsigned from_addr = 0;
    int free_slot = -1;
    for (int i = 0; i < GATE_SLOTS; i++) {
        const gate_conn_t *c = &g->conn[i];
        if (live(c) && memcmp(&c->addr, a, sizeof *a) == 0)
            from_addr++;
        if (c->state == GATE_FREE && free_slot < 0)
            free_slot = i;
    }
    /* a full address gives up its own oldest waiting connection, a full console its
     * oldest waiting one of any address */
    int v = -1;
    if (from_addr >= GATE_PER_ADDR)
        v = oldest_waiting(g, a);
    else if (g->live >= GATE_MAX_LIVE)
        v = oldest_waiting(g, NULL);
    bool full = from_addr >= GATE_PER_ADDR || g->live >= GATE_MAX_LIVE;
    if ((full && v < 0) || free_slot < 0) {
        g->refused++;
        return -1;
    }
    if (v >= 0) {
        to_closing(g, v);
        g->displaced++;
        *victim = v;
    }
    g->conn[free_slot] = (gate_conn_t){ .state = GATE_WAITING, .addr = *a, .fd = fd,
                                        .since_ms = now_ms };
    g->live++;
    return free_slot;
}

void gate_serving(gate_t *g, int slot)
{
    if (slot >= 0 && slot < GATE_SLOTS && g->conn[slot].state == GATE_WAITING)
        g->conn[slot].state = GATE_SERVING;
}

void gate_waiting(gate_t *g, int slot, int64_t now_ms)
{
    if (slot < 0 || slot >= GATE_SLOTS || !live(&g->conn[slot]))
        return;
    g->conn[slot].state = GATE_WAITING;
    g->conn[slot].since_ms = now_ms;
}

void gate_closed(gate_t *g, int slot)
{
    if (slot < 0 || slot >= GATE_SLOTS || g->conn[slot].state == GATE_FREE)
        return;
    if (live(&g->conn[slot]))
        g->live--;
    g->conn[slot] = (gate_conn_t){ .state = GATE_FREE, .fd = -1 };
}

int gate_expire(gate_t *g, int64_t now_ms)
{
    for (int i = 0; i < GATE_SLOTS; i++) {
        const gate_conn_t *c = &g->conn[i];
        if (c->state == GATE_WAITING && now_ms - c->since_ms >= GATE_HEADER_MS) {
            to_closing(g, i);
            g->expired++;
            return i;
        }
    }
    return -1;
}

long gate_timeout_ms(const gate_t *g, int64_t now_ms)
{
    int i = oldest_waiting(g, NULL);
    if (i < 0)
        return -1;
    int64_t left = g->conn[i].since_ms + GATE_HEADER_MS - now_ms;
    return left > 0 ? (long)left : 0;
}
