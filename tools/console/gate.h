/*
 * gate.h - who holds the console's connections (private to tools/console). Pure: the
 * HTTP layer accepts each connection, asks here, and shuts down the one it is told to;
 * times are the caller's monotonic milliseconds.
 *
 * The rule (docs/manual/houghloc-console.md, "Limits"):
 *   - at most GATE_MAX_LIVE connections at once, at most GATE_PER_ADDR from one address;
 *   - a connection is WAITING until a request proves the token (a new one, or one idle
 *     between requests), and must then deliver a whole request within GATE_HEADER_MS,
 *     or it is closed: dribbling a header byte by byte buys nothing;
 *   - a newcomer that finds its address, or the console, full closes the oldest
 *     WAITING connection (of its address, or of any) to take its place. A connection
 *     SERVING a request that proved the token is never closed for a newcomer; when every
 *     place is taken by such, the newcomer is refused.
 * So a slowloris attacker, who never completes a request, holds WAITING connections
 * only, and the operator's next connection takes one of them, even on loopback, where
 * the attacker has the operator's address; the operator's event streams, once they
 * proved the token, are not taken back.
 *
 * Why these numbers: 128 connections serve a handful of operators with a few streams
 * and reloads each (a page holds one stream), the per-address bound of 96 leaves a
 * third to the others when one address floods, and 5 s lets a request header cross a
 * slow radio link but not be dribbled forever.
 */
#ifndef HOUGHLOC_TOOLS_CONSOLE_GATE_H
#define HOUGHLOC_TOOLS_CONSOLE_GATE_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/socket.h>

#define GATE_MAX_LIVE 128
#define GATE_PER_ADDR 96
#define GATE_HEADER_MS 5000
/* Room also for the connections told to close that the server has not closed yet. */
#define GATE_SLOTS (2 * GATE_MAX_LIVE)

typedef enum gate_state {
    GATE_FREE = 0,
    GATE_WAITING,           /* no request with the token under way: may be displaced */
    GATE_SERVING,           /* a request that proved the token: kept */
    GATE_CLOSING,           /* told to close: the server has not closed it yet */
} gate_state_t;

/** A client's address: IPv4 as IPv4-mapped IPv6. */
typedef struct gate_addr {
    uint8_t b[16];
} gate_addr_t;

typedef struct gate_conn {
    gate_state_t state;
    gate_addr_t addr;
    int fd;                 /* the caller's socket */
    int64_t since_ms;       /* when it began WAITING */
} gate_conn_t;

typedef struct gate {
    gate_conn_t conn[GATE_SLOTS];
    unsigned live;          /* WAITING or SERVING */
    uint64_t displaced;     /* WAITING connections closed for a newcomer */
    uint64_t expired;       /* WAITING connections past GATE_HEADER_MS */
    uint64_t refused;       /* newcomers turned away: every place SERVING */
} gate_t;

/** An empty gate. */
void gate_init(gate_t *g);

/** @return @p sa's address (AF_INET or AF_INET6; anything else all zeros). */
gate_addr_t gate_addr_of(const struct sockaddr *sa);

/**
 * Admits a new connection (socket @p fd) from @p a, WAITING from @p now_ms.
 * @param[out] victim  a slot the caller must shut down (already CLOSING), or -1.
 * @return its slot, or -1 when refused (the caller closes @p fd; *victim is then -1).
 */
int gate_open(gate_t *g, const gate_addr_t *a, int fd, int64_t now_ms, int *victim);

/** A request on @p slot proved the token: SERVING until gate_waiting. */
void gate_serving(gate_t *g, int slot);
/** The request on @p slot ended; the connection stays open, WAITING from @p now_ms. */
void gate_waiting(gate_t *g, int slot, int64_t now_ms);
/** The server closed @p slot's connection: the slot is free. */
void gate_closed(gate_t *g, int slot);

/** @return a WAITING slot past its deadline (now CLOSING, for the caller to shut
 *  down), or -1 when there is none. */
int gate_expire(gate_t *g, int64_t now_ms);
/** @return milliseconds until the next deadline (0 when one is past), -1 for none. */
long gate_timeout_ms(const gate_t *g, int64_t now_ms);

#endif
