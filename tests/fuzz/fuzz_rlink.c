/*
 * fuzz_rlink.c - the ARCOS connection (include/robot/houghloc/rlink.h) as houghlocd drives it:
 * the input is what the robot sends, in reads cut at points drawn from the input, with
 * the wall clock moving on between reads.
 *
 * As src/daemon/robot.c does, each SIP advances robot time and keeps the link alive, and
 * some SIPs answer with a command; a lost link is begun again; what the link queues is
 * written out whole or in part. Checked: the out-buffer never overflows its storage,
 * what it holds is only well-formed commands of the supported subset, and every SIP the
 * callback gets was counted.
 */
#include <string.h>

#include "fuzz.h"
#include "houghloc/rlink.h"

typedef struct ctx {
    hl_rlink_t *l;
    int64_t robot_ms, now_ms;
    uint64_t sips;
} ctx_t;

static void on_sip(void *user, const hl_arcos_sip_t *sip)
{
    ctx_t *c = user;
    FUZZ_CHECK(sip->type == HL_ARCOS_SIP_STOPPED || sip->type == HL_ARCOS_SIP_MOVING);
    FUZZ_CHECK(hl_rlink_state(c->l) == HL_RLINK_UP);
    c->sips++;
    c->robot_ms += 100;
    hl_rlink_keepalive(c->l, c->robot_ms);
    /* The drive and the sounder answer some SIPs with a command. */
    if (sip->flags & 1u) {
        (void)hl_rlink_send_int(c->l, HL_ARCOS_HEAD, sip->th % 360, c->now_ms);
        hl_rlink_sent_at(c->l, c->robot_ms);
    } else if (sip->flags & 2u) {
        (void)hl_rlink_send(c->l, HL_ARCOS_STOP, c->now_ms);
        hl_rlink_sent_at(c->l, c->robot_ms);
    }
}

/* The queued bytes, from the start of a packet: nothing but whole, valid commands. */
static void check_out(const hl_rlink_t *l)
{
    size_t n = 0;
    const uint8_t *out = hl_rlink_pending(l, &n);
    FUZZ_CHECK(n <= HL_RLINK_OUT_MAX);
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    size_t off = 0, used = 0;
    hl_arcos_packet_t pkt;
    while (hl_arcos_parse(&p, n > off ? out + off : NULL, n - off, &used, &pkt) == HL_OK) {
        off += used;
        hl_arcos_cmd_t cmd;
        FUZZ_CHECK(hl_arcos_decode_cmd(&pkt, &cmd) == HL_OK);
    }
    FUZZ_CHECK(p.fill == 0 && p.garbage_bytes == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_rlink_params_t params;
    hl_rlink_params_default(&params);
    hl_rlink_t link;
    FUZZ_CHECK(hl_rlink_init(&link, &params) == HL_OK);
    ctx_t c = { .l = &link };
    hl_rlink_begin(&link, 0);

    uint64_t state = fuzz_seed(data, size);
    bool aligned = true;    /* the out-buffer starts at a packet */
    size_t off = 0;
    int begins = 1;
    while (off < size) {
        size_t n = fuzz_cut(&state, size - off);
        hl_rlink_feed(&link, data + off, n, c.now_ms, on_sip, &c);
        off += n;
        if (aligned)
            check_out(&link);
        /* Time passes between reads: usually a SIP period, sometimes a stall. */
        size_t step = fuzz_cut(&state, 300);
        c.now_ms += step > 250 ? 2500 : (int64_t)step;
        hl_rlink_tick(&link, c.now_ms);
        /* The transport takes everything, part, or nothing. */
        size_t pending = 0;
        (void)hl_rlink_pending(&link, &pending);
        size_t put = fuzz_cut(&state, pending + 1);
        hl_rlink_sent(&link, put > pending ? pending : put);
        if (put >= pending)
            aligned = true;
        else if (put > 0)
            aligned = false;
        if (hl_rlink_state(&link) == HL_RLINK_DOWN && begins < 64) {
            FUZZ_CHECK(hl_rlink_why(&link)[0] != '\0');
            hl_rlink_begin(&link, c.now_ms);
            aligned = true;
            begins++;
        }
    }
    FUZZ_CHECK(c.sips == link.sips);
    FUZZ_CHECK(memchr(link.why, '\0', sizeof link.why) != NULL);
    (void)hl_rlink_bad_packets(&link);
    hl_rlink_close(&link, "fuzz input ended", c.now_ms);
    FUZZ_CHECK(hl_rlink_state(&link) == HL_RLINK_DOWN);
    return 0;
}
