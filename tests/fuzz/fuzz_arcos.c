/*
 * fuzz_arcos.c - the ARCOS codec (include/robot/houghloc/arcos.h): the input is a byte stream
 * from the robot's serial line.
 *
 * It goes through the streaming parser twice: whole, and cut at points drawn from the
 * input itself (some reads empty, some one byte, some long). arcos.h promises that the
 * stream may be cut anywhere, so both must deliver the same packets and the same
 * counters, and that every byte fed ends up in exactly one of a packet, garbage_bytes or
 * the pending buffer. Every packet then goes through each decoder (SIP, client command,
 * SYNC2 reply); what decodes must encode again and decode to the same thing.
 */
#include <string.h>

#include "fuzz.h"
#include "houghloc/arcos.h"

/* What a parser run delivered: packet count, a hash of the packets' bytes, and the
 * bytes they took on the wire. */
typedef struct run {
    uint64_t packets, hash, wire_bytes;
} run_t;

static void sip_round_trip(const hl_arcos_packet_t *pkt, const hl_arcos_sip_t *sip)
{
    FUZZ_CHECK(sip->sonar_count <= HL_ARCOS_SONAR_MAX);
    size_t body = HL_ARCOS_SIP_FIXED + 3u * sip->sonar_count;
    FUZZ_CHECK(body + sip->extra_len == pkt->len);
    for (size_t i = 0; i < sip->sonar_count; i++)
        FUZZ_CHECK(sip->sonar[i].transducer < HL_ARCOS_SONAR_MAX);
    /* The encoder writes exactly the bytes the decoder read, then extra_len zeros. */
    uint8_t frame[HL_ARCOS_PACKET_MAX];
    size_t len = 0;
    FUZZ_CHECK(hl_arcos_encode_sip(frame, sizeof frame, sip, &len) == HL_OK);
    FUZZ_CHECK(len == pkt->len + 5u && frame[2] == pkt->len + 2u);
    FUZZ_CHECK(memcmp(frame + 3, pkt->data, body) == 0);
    for (size_t i = body; i < pkt->len; i++)
        FUZZ_CHECK(frame[3 + i] == 0);
    /* Odometry unwrapping takes any SIP. */
    hl_arcos_odom_t odom;
    hl_arcos_odom_init(&odom, 4096);
    FUZZ_CHECK(hl_arcos_odom_unwrap(&odom, sip) == HL_OK);
    hl_arcos_conv_t conv = HL_ARCOS_CONV_PIONEER;
    (void)hl_arcos_angle_to_bam(&conv, odom.th);
}

/* Reparses a frame the encoder wrote: exactly one packet, all bytes used. */
static void reparse(const uint8_t *frame, size_t len, hl_arcos_packet_t *out)
{
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    size_t used = 0;
    FUZZ_CHECK(hl_arcos_parse(&p, frame, len, &used, out) == HL_OK);
    FUZZ_CHECK(used == len && p.fill == 0 && p.garbage_bytes == 0);
}

static void cmd_round_trip(const hl_arcos_cmd_t *cmd)
{
    const hl_arcos_cmd_spec_t *spec = hl_arcos_spec_of(cmd->number);
    FUZZ_CHECK(spec != NULL);
    if (cmd->arg_kind != spec->arg_kind)
        return;     /* the lenient case (an integer on OPEN): accepted, never sent */
    uint8_t frame[HL_ARCOS_PACKET_MAX];
    size_t len = 0;
    FUZZ_CHECK(hl_arcos_encode_cmd(frame, sizeof frame, cmd, &len) == HL_OK);
    hl_arcos_packet_t again;
    reparse(frame, len, &again);
    hl_arcos_cmd_t back;
    FUZZ_CHECK(hl_arcos_decode_cmd(&again, &back) == HL_OK);
    FUZZ_CHECK(back.number == cmd->number && back.arg_kind == cmd->arg_kind);
    FUZZ_CHECK(back.arg == cmd->arg && back.str_len == cmd->str_len);
    FUZZ_CHECK(memcmp(back.str, cmd->str, cmd->str_len) == 0);
}

static void sync2_round_trip(const hl_arcos_robot_id_t *id)
{
    const char *fields[3] = { id->name, id->cls, id->subclass };
    for (int f = 0; f < 3; f++)
        FUZZ_CHECK(memchr(fields[f], '\0', HL_ARCOS_ID_MAX) != NULL);
    uint8_t frame[HL_ARCOS_PACKET_MAX];
    size_t len = 0;
    /* Three strings of at most 63 characters and their NULs always fit one packet. */
    FUZZ_CHECK(hl_arcos_encode_sync2(frame, sizeof frame, id, &len) == HL_OK);
    hl_arcos_packet_t again;
    reparse(frame, len, &again);
    hl_arcos_robot_id_t back;
    FUZZ_CHECK(hl_arcos_decode_sync2(&again, &back) == HL_OK);
    FUZZ_CHECK(memcmp(&back, id, sizeof back) == 0);
}

static void check_packet(const hl_arcos_packet_t *pkt)
{
    FUZZ_CHECK(pkt->len >= 1 && pkt->len <= HL_ARCOS_PAYLOAD_MAX);
    hl_arcos_sip_t sip;
    hl_status_t st = hl_arcos_decode_sip(pkt, &sip);
    FUZZ_CHECK(st == HL_OK || st == HL_ERR_PARSE);
    FUZZ_CHECK(st != HL_OK || hl_arcos_is_sip(pkt));
    if (st == HL_OK)
        sip_round_trip(pkt, &sip);

    hl_arcos_cmd_t cmd;
    st = hl_arcos_decode_cmd(pkt, &cmd);
    FUZZ_CHECK(st == HL_OK || st == HL_ERR_PARSE || st == HL_ERR_RANGE);
    if (st == HL_OK)
        cmd_round_trip(&cmd);

    hl_arcos_robot_id_t id;
    st = hl_arcos_decode_sync2(pkt, &id);
    FUZZ_CHECK(st == HL_OK || st == HL_ERR_PARSE);
    if (st == HL_OK)
        sync2_round_trip(&id);
    for (uint8_t s = 0; s <= HL_ARCOS_SYNC2; s++)
        FUZZ_CHECK(hl_arcos_is_sync_echo(pkt, s) == (pkt->len == 1 && pkt->data[0] == s));
}

/* Feeds @p n bytes (NULL allowed when n is 0) until the parser wants more. */
static void feed(hl_arcos_parser_t *p, const uint8_t *in, size_t n, run_t *r, bool decode)
{
    size_t off = 0;
    for (;;) {
        size_t used = n + 1;
        hl_arcos_packet_t pkt;
        hl_status_t st = hl_arcos_parse(p, n > off ? in + off : NULL, n - off, &used, &pkt);
        if (st == HL_ERR_EMPTY) {
            FUZZ_CHECK(used == n - off);
            return;
        }
        FUZZ_CHECK(st == HL_OK && used <= n - off);
        off += used;
        r->packets++;
        r->wire_bytes += pkt.len + 5u;
        r->hash = fuzz_seed(pkt.data, pkt.len) ^ (r->hash * 31u + pkt.len);
        if (decode)
            check_packet(&pkt);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hl_arcos_parser_t whole, cut;
    run_t rw = { 0, 0, 0 }, rc = { 0, 0, 0 };

    hl_arcos_parser_init(&whole);
    feed(&whole, data, size, &rw, true);

    hl_arcos_parser_init(&cut);
    uint64_t state = fuzz_seed(data, size);
    size_t off = 0;
    while (off < size) {
        size_t n = fuzz_cut(&state, size - off);
        feed(&cut, data + off, n, &rc, false);
        off += n;
    }
    feed(&cut, NULL, 0, &rc, false);

    /* Every byte in exactly one place. */
    FUZZ_CHECK(rw.wire_bytes + whole.garbage_bytes + whole.fill == size);
    FUZZ_CHECK(rw.packets == whole.packets);
    /* The cuts change nothing. */
    FUZZ_CHECK(rc.packets == rw.packets && rc.hash == rw.hash);
    FUZZ_CHECK(cut.garbage_bytes == whole.garbage_bytes && cut.fill == whole.fill);
    FUZZ_CHECK(cut.bad_checksums == whole.bad_checksums);
    FUZZ_CHECK(cut.bad_lengths == whole.bad_lengths);
    FUZZ_CHECK(memcmp(cut.buf, whole.buf, whole.fill) == 0);

    /* A discard forgets the pending bytes and nothing else. */
    hl_arcos_parser_discard(&whole);
    FUZZ_CHECK(whole.fill == 0 && whole.packets == rw.packets);
    return 0;
}
