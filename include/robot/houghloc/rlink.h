/*
 * rlink.h - an ARCOS connection over any byte stream: the SYNC handshake, OPEN, motors and
 * sonar on, keep-alive pulses, and the silence that means the link is lost.
 *
 * Pure, like the codec under it (arcos.h): bytes and the time come in, standard SIPs go
 * to a callback, and bytes to send collect in an out-buffer the caller writes to its
 * transport (a serial port or the simulator's TCP socket: src/daemon owns those). Time
 * here is the caller's monotonic clock in milliseconds, not robot time: a link is lost by
 * the wall clock, however fast a simulated robot runs. Keep-alive pulses are the one
 * exception: the robot's watchdog counts its own time, so they follow robot time
 * (hl_rlink_keepalive).
 *
 * Handshake (docs/manual/arcos.md): SYNC0, SYNC1 and SYNC2 each echoed by the robot, SYNC2's
 * echo carrying its name, class and subclass; then OPEN, ENABLE 1 and SONAR 1. A robot
 * that is already streaming SIPs from an earlier connection is sent CLOSE first.
 */
#ifndef HOUGHLOC_RLINK_H
#define HOUGHLOC_RLINK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/arcos.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_rlink_params {
    int32_t sync_timeout_ms;    /* resend a SYNC not answered within this (default 500) */
    int32_t sync_tries;         /* give up after this many sends of one SYNC (default 6) */
    int32_t silence_ms;         /* no packet this long: the link is lost (default 2000) */
    int32_t pulse_ms;           /* send PULSE when nothing was sent for this much robot
                                   time (default 500; ARCOS's watchdog is 2 s) */
} hl_rlink_params_t;

void hl_rlink_params_default(hl_rlink_params_t *p);
const char *hl_rlink_params_error(const hl_rlink_params_t *p);

typedef enum hl_rlink_state {
    HL_RLINK_DOWN = 0,          /* not started, or lost: hl_rlink_why says why */
    HL_RLINK_SYNCING,
    HL_RLINK_UP,                /* SIPs flow */
} hl_rlink_state_t;

#define HL_RLINK_OUT_MAX 1024

typedef struct hl_rlink {
    hl_rlink_params_t p;
    hl_rlink_state_t state;
    int32_t sync_stage;         /* the SYNC awaited: 0, 1 or 2 */
    int32_t tries;
    int64_t sent_ms, last_rx_ms, last_tx_ms;
    int64_t pulse_ref_ms;       /* robot time of the last command or pulse */
    hl_arcos_parser_t parser;
    hl_arcos_robot_id_t id;     /* from SYNC2's echo */
    uint8_t out[HL_RLINK_OUT_MAX];
    size_t out_len;
    uint64_t sips;              /* SIPs delivered */
    uint64_t bad_packets;       /* packets dropped: undecodable SIPs, unknown types */
    uint64_t garbage_runs;      /* reads that held bytes belonging to no packet */
    uint64_t out_overflows;     /* commands dropped because the out-buffer was full */
    bool stop_queued;           /* lost to silence: STOP and CLOSE wait in the out-buffer */
    char why[128];
} hl_rlink_t;

/** @return HL_OK, or HL_ERR_ARG for NULL or invalid parameters. The link is DOWN. */
hl_status_t hl_rlink_init(hl_rlink_t *l, const hl_rlink_params_t *p);

/** A fresh connection: forgets partial input and queued output, sends SYNC0. */
void hl_rlink_begin(hl_rlink_t *l, int64_t now_ms);

/** Marks the link lost with @p why (the transport failed, say). */
void hl_rlink_lost(hl_rlink_t *l, const char *why);

typedef void (*hl_rlink_sip_fn)(void *ctx, const hl_arcos_sip_t *sip);

/**
 * Takes @p n bytes from the robot; every standard SIP they complete goes to @p on_sip
 * (only while UP). Replies to the handshake are answered in the out-buffer.
 */
void hl_rlink_feed(hl_rlink_t *l, const uint8_t *in, size_t n, int64_t now_ms,
                   hl_rlink_sip_fn on_sip, void *ctx);

/**
 * Resends unanswered SYNCs and gives up on a silent robot (wall clock). A robot silent
 * for silence_ms while UP may still hear commands (a one-way loss): STOP and CLOSE are
 * queued as the link goes DOWN (hl_rlink_stop_queued), for the caller to write before it
 * closes the transport.
 */
void hl_rlink_tick(hl_rlink_t *l, int64_t now_ms);
/** Whether the link was lost with STOP queued for the robot (until hl_rlink_begin). */
static inline bool hl_rlink_stop_queued(const hl_rlink_t *l) { return l->stop_queued; }

/** Queues a PULSE when nothing was sent for pulse_ms of robot time; call once per SIP. */
void hl_rlink_keepalive(hl_rlink_t *l, int64_t robot_ms);
/** The client holds the robot's clock (a lockstep simulator waits for STEP, arcos.h):
 *  no SIP comes, and that silence is no fault. Call while holding; the silence counts
 *  from the last call. */
void hl_rlink_hold(hl_rlink_t *l, int64_t now_ms);
/** Notes that a command went out at @p robot_ms (no pulse is due before pulse_ms). */
void hl_rlink_sent_at(hl_rlink_t *l, int64_t robot_ms);

/** Queues a command without argument / with an integer one / with a string of @p n bytes
 *  (POLLING). @return false (and counts an overflow) when the link is not UP, the
 *  out-buffer is full or the command does not encode. */
bool hl_rlink_send(hl_rlink_t *l, uint8_t number, int64_t now_ms);
bool hl_rlink_send_int(hl_rlink_t *l, uint8_t number, int32_t arg, int64_t now_ms);
bool hl_rlink_send_str(hl_rlink_t *l, uint8_t number, const uint8_t *s, size_t n,
                       int64_t now_ms);

/** Queues CLOSE (motors stop, the robot ends the connection) and marks the link DOWN. */
void hl_rlink_close(hl_rlink_t *l, const char *why, int64_t now_ms);

/** Bytes waiting to be written, and how many the transport took. */
static inline const uint8_t *hl_rlink_pending(const hl_rlink_t *l, size_t *n)
{
    *n = l->out_len;
    return l->out;
}
void hl_rlink_sent(hl_rlink_t *l, size_t n);

static inline hl_rlink_state_t hl_rlink_state(const hl_rlink_t *l) { return l->state; }
static inline const char *hl_rlink_why(const hl_rlink_t *l) { return l->why; }
/** What went wrong on the way in: parser rejects (checksum, length), bad_packets and
 *  garbage_runs; STATUS reports it as bad_packets. */
uint64_t hl_rlink_bad_packets(const hl_rlink_t *l);

#ifdef __cplusplus
}
#endif
#endif
