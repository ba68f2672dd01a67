/* rlink.c - the ARCOS connection: handshake, keep-alive, silence (see rlink.h). */
#include "houghloc/rlink.h"

#include <stdio.h>
#include <string.h>

void hl_rlink_params_default(hl_rlink_params_t *p)
{
    /* ARCOS answers a SYNC within a few of its 100 ms packet periods: six tries of 0.5 s
     * before the connection is dropped and retried; a keep-alive every 0.5 s stays well
     * inside the server's 2 s watchdog, and 2 s without a packet is a lost link (the
     * sync and pulse values are fixed for houghlocd: docs/design/expert-keys.md). */
    p->sync_timeout_ms = 500;
    p->sync_tries = 6;
    p->silence_ms = 2000;
    p->pulse_ms = 500;
}

const char *hl_rlink_params_error(const hl_rlink_params_t *p)
{
    if (!p)
        return "no link parameters";
    if (p->sync_timeout_ms < 10 || p->sync_timeout_ms > 60000)
        return "link sync timeout must be 10..60000 ms";
    if (p->sync_tries < 1 || p->sync_tries > 100)
        return "link sync tries must be 1..100";
    if (p->silence_ms < 100 || p->silence_ms > 600000)
        return "link silence must be 100..600000 ms";
    /* ARCOS stops the robot when no command came within its watchdog time (2 s by
     * default): the pulse must come well inside it. */
    if (p->pulse_ms < 10 || p->pulse_ms > 1500)
        return "link pulse period must be 10..1500 ms";
    return NULL;
}

hl_status_t hl_rlink_init(hl_rlink_t *l, const hl_rlink_params_t *p)
{
    if (!l || hl_rlink_params_error(p))
        return HL_ERR_ARG;
    memset(l, 0, sizeof *l);
    l->p = *p;
    hl_arcos_parser_init(&l->parser);
    snprintf(l->why, sizeof l->why, "not connected");
    return HL_OK;
}

uint64_t hl_rlink_bad_packets(const hl_rlink_t *l)
{
    return l->parser.bad_checksums + l->parser.bad_lengths + l->bad_packets + l->garbage_runs;
}

static bool queue(hl_rlink_t *l, hl_status_t st, size_t len, int64_t now_ms)
{
    if (st != HL_OK) {
        l->out_overflows++;
        return false;
    }
    l->out_len += len;
    l->last_tx_ms = now_ms;
    return true;
}

static bool queue_none(hl_rlink_t *l, uint8_t number, int64_t now_ms)
{
    size_t len = 0;
    hl_status_t st = hl_arcos_encode_none(l->out + l->out_len, sizeof l->out - l->out_len,
                                          number, &len);
    return queue(l, st, len, now_ms);
}

static bool queue_int(hl_rlink_t *l, uint8_t number, int32_t arg, int64_t now_ms)
{
    size_t len = 0;
    hl_status_t st = hl_arcos_encode_int(l->out + l->out_len, sizeof l->out - l->out_len,
                                         number, arg, &len);
    return queue(l, st, len, now_ms);
}

static bool queue_str(hl_rlink_t *l, uint8_t number, const uint8_t *s, size_t n,
                      int64_t now_ms)
{
    size_t len = 0;
    hl_status_t st = hl_arcos_encode_str(l->out + l->out_len, sizeof l->out - l->out_len,
                                         number, s, n, &len);
    return queue(l, st, len, now_ms);
}

static void send_sync(hl_rlink_t *l, int64_t now_ms)
{
    queue_none(l, (uint8_t)l->sync_stage, now_ms);
    l->sent_ms = now_ms;
    l->tries++;
}

void hl_rlink_begin(hl_rlink_t *l, int64_t now_ms)
{
    hl_arcos_parser_discard(&l->parser);
    l->out_len = 0;
    l->state = HL_RLINK_SYNCING;
    l->sync_stage = 0;
    l->tries = 0;
    l->last_rx_ms = now_ms;
    l->why[0] = '\0';
    l->stop_queued = false;
    send_sync(l, now_ms);
}

void hl_rlink_lost(hl_rlink_t *l, const char *why)
{
    l->state = HL_RLINK_DOWN;
    snprintf(l->why, sizeof l->why, "%s", why);
}

/* One packet during the handshake. */
static void on_handshake(hl_rlink_t *l, const hl_arcos_packet_t *pkt, int64_t now_ms)
{
    if (hl_arcos_is_sip(pkt)) {
        /* still open from an earlier client: end that connection, then start again */
        queue_none(l, HL_ARCOS_CLOSE, now_ms);
        l->sync_stage = 0;
        l->tries = 0;
        send_sync(l, now_ms);
        return;
    }
    if (l->sync_stage < 2 && hl_arcos_is_sync_echo(pkt, (uint8_t)l->sync_stage)) {
        l->sync_stage++;
        l->tries = 0;
        send_sync(l, now_ms);
        return;
    }
    if (l->sync_stage == 2 && hl_arcos_decode_sync2(pkt, &l->id) == HL_OK) {
        queue_none(l, HL_ARCOS_OPEN, now_ms);
        queue_int(l, HL_ARCOS_ENABLE, 1, now_ms);
        queue_int(l, HL_ARCOS_SONAR, 1, now_ms);
        l->state = HL_RLINK_UP;
        return;
    }
    l->bad_packets++;   /* a stale echo or noise: the timeout resends */
}

void hl_rlink_feed(hl_rlink_t *l, const uint8_t *in, size_t n, int64_t now_ms,
                   hl_rlink_sip_fn on_sip, void *ctx)
{
    if (l->state == HL_RLINK_DOWN)
        return;
    hl_arcos_packet_t pkt;
    hl_arcos_sip_t sip;
    size_t off = 0, used = 0;
    uint64_t garbage = l->parser.garbage_bytes;
    while (hl_arcos_parse(&l->parser, in ? in + off : NULL, n - off, &used, &pkt) == HL_OK) {
        off += used;
        l->last_rx_ms = now_ms;
        if (l->state == HL_RLINK_SYNCING) {
            on_handshake(l, &pkt, now_ms);
        } else if (hl_arcos_decode_sip(&pkt, &sip) == HL_OK) {
            l->sips++;
            if (on_sip)
                on_sip(ctx, &sip);
        } else {
            l->bad_packets++;   /* another packet type, or a malformed SIP */
        }
        if (l->state == HL_RLINK_DOWN)
            break;
    }
    /* bytes between packets that belong to none: counted once per read they spoil */
    l->garbage_runs += l->parser.garbage_bytes > garbage;
}

void hl_rlink_tick(hl_rlink_t *l, int64_t now_ms)
{
    if (l->state == HL_RLINK_SYNCING && now_ms - l->sent_ms >= l->p.sync_timeout_ms) {
        if (l->tries >= l->p.sync_tries) {
            snprintf(l->why, sizeof l->why, "no answer to SYNC%d after %d tries",
                     l->sync_stage, l->tries);
            l->state = HL_RLINK_DOWN;
            return;
        }
        send_sync(l, now_ms);
    }
    if (l->state == HL_RLINK_UP && now_ms - l->last_rx_ms >= l->p.silence_ms) {
        /* Silence may be one way only (a broken receive wire, a wedged reader): the
         * robot may still hear us, and it must not drive on until its own watchdog
         * notices. Tell it to stop and end the connection; the caller writes this before
         * it closes the link (hl_rlink_stop_queued). */
        l->stop_queued = queue_none(l, HL_ARCOS_STOP, now_ms);
        queue_none(l, HL_ARCOS_CLOSE, now_ms);
        snprintf(l->why, sizeof l->why, "no packet from the robot for %d ms",
                 (int)(now_ms - l->last_rx_ms));
        l->state = HL_RLINK_DOWN;
    }
}

void hl_rlink_keepalive(hl_rlink_t *l, int64_t robot_ms)
{
    if (l->state != HL_RLINK_UP || robot_ms - l->pulse_ref_ms < l->p.pulse_ms)
        return;
    queue_none(l, HL_ARCOS_PULSE, l->last_tx_ms);
    l->pulse_ref_ms = robot_ms;
}

void hl_rlink_hold(hl_rlink_t *l, int64_t now_ms)
{
    if (l->state == HL_RLINK_UP)
        l->last_rx_ms = now_ms;
}

void hl_rlink_sent_at(hl_rlink_t *l, int64_t robot_ms)
{
    l->pulse_ref_ms = robot_ms;
}

bool hl_rlink_send(hl_rlink_t *l, uint8_t number, int64_t now_ms)
{
    return l->state == HL_RLINK_UP && queue_none(l, number, now_ms);
}

bool hl_rlink_send_str(hl_rlink_t *l, uint8_t number, const uint8_t *s, size_t n,
                       int64_t now_ms)
{
    return l->state == HL_RLINK_UP && s && queue_str(l, number, s, n, now_ms);
}

bool hl_rlink_send_int(hl_rlink_t *l, uint8_t number, int32_t arg, int64_t now_ms)
{
    return l->state == HL_RLINK_UP && queue_int(l, number, arg, now_ms);
}

void hl_rlink_close(hl_rlink_t *l, const char *why, int64_t now_ms)
{
    if (l->state == HL_RLINK_UP)
        queue_none(l, HL_ARCOS_CLOSE, now_ms);
    hl_rlink_lost(l, why);
}

void hl_rlink_sent(hl_rlink_t *l, size_t n)
{
    if (n >= l->out_len) {
        l->out_len = 0;
        return;
    }
    memmove(l->out, l->out + n, l->out_len - n);
    l->out_len -= n;
}
