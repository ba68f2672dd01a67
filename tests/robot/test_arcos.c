/* Tests for src/robot/arcos_msg.c: checksums against the manuals' example packets, every
 * supported command and SIPs with 0..32 readings through encoder, parser and decoder,
 * the SYNC handshake's packets, odometry unwrapping. The stream tests are in
 * test_arcos_stream.c. */
#include "arcos_testkit.h"


static void test_checksum_manual_examples(void **state)
{
    (void)state;
    uint8_t b[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    /* The Pioneer manuals' handshake bytes, OPEN and ENABLE 1. */
    const uint8_t sync0[] = { 0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00 };
    const uint8_t sync1[] = { 0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01 };
    const uint8_t sync2[] = { 0xFA, 0xFB, 0x03, 0x02, 0x00, 0x02 };
    const uint8_t enable[] = { 0xFA, 0xFB, 0x06, 0x04, 0x3B, 0x01, 0x00, 0x05, 0x3B };
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_SYNC0, &n), HL_OK);
    assert_bytes(b, n, sync0, sizeof sync0);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_PULSE, &n), HL_OK);
    assert_bytes(b, n, sync0, sizeof sync0);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_SYNC1, &n), HL_OK);
    assert_bytes(b, n, sync1, sizeof sync1);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_OPEN, &n), HL_OK);
    assert_bytes(b, n, sync1, sizeof sync1);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_SYNC2, &n), HL_OK);
    assert_bytes(b, n, sync2, sizeof sync2);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_ENABLE, 1, &n), HL_OK);
    assert_bytes(b, n, enable, sizeof enable);
    /* Worked by hand from the rule: STOP; MOVE -300 (0x1B, magnitude 0x012C little-
     * endian; 0x081B + 0x2C01 = 0x341C); VEL 200 (0x0B3B + 0xC800 = 0xD33B). */
    const uint8_t stop[] = { 0xFA, 0xFB, 0x03, 0x1D, 0x00, 0x1D };
    const uint8_t move[] = { 0xFA, 0xFB, 0x06, 0x08, 0x1B, 0x2C, 0x01, 0x34, 0x1C };
    const uint8_t vel[] = { 0xFA, 0xFB, 0x06, 0x0B, 0x3B, 0xC8, 0x00, 0xD3, 0x3B };
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_STOP, &n), HL_OK);
    assert_bytes(b, n, stop, sizeof stop);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_MOVE, -300, &n), HL_OK);
    assert_bytes(b, n, move, sizeof move);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_VEL, 200, &n), HL_OK);
    assert_bytes(b, n, vel, sizeof vel);
    /* Odd length: the last byte XORed into the low byte; pairs wrap modulo 2^16. */
    const uint8_t odd[] = { 0x12, 0x34, 0x56 };
    const uint8_t ones[] = { 0xFF, 0xFF, 0xFF, 0xFF };
    const uint8_t one[] = { 0x80 };
    assert_int_equal(hl_arcos_checksum(odd, 3), 0x1262);
    assert_int_equal(hl_arcos_checksum(ones, 4), 0xFFFE);
    assert_int_equal(hl_arcos_checksum(ones, 3), 0xFF00);
    assert_int_equal(hl_arcos_checksum(one, 1), 0x0080);
    assert_int_equal(hl_arcos_checksum(one, 0), 0);
}

/* Encodes @p c, parses the bytes and decodes them back; returns the decoder's status. */
static hl_status_t through_the_wire(const hl_arcos_cmd_t *c, hl_arcos_cmd_t *back)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    size_t n = 0, used = 0;
    hl_arcos_parser_t p;
    hl_arcos_packet_t pk;
    hl_arcos_parser_init(&p);
    assert_int_equal(hl_arcos_encode_cmd(b, sizeof b, c, &n), HL_OK);
    assert_int_equal(hl_arcos_parse(&p, b, n, &used, &pk), HL_OK);
    assert_int_equal(used, n);
    return hl_arcos_decode_cmd(&pk, back);
}

static void test_every_command_round_trips(void **state)
{
    (void)state;
    int specs = 0;
    for (int number = 0; number < 256; number++) {
        const hl_arcos_cmd_spec_t *s = hl_arcos_spec_of((uint8_t)number);
        if (!s)
            continue;
        specs++;
        assert_int_equal(s->number, number);
        hl_arcos_cmd_t c = { .number = (uint8_t)number, .arg_kind = s->arg_kind }, back;
        if (s->arg_kind == HL_ARCOS_ARG_NONE) {
            assert_int_equal(through_the_wire(&c, &back), HL_OK);
            assert_int_equal(back.number, number);
            assert_int_equal(back.arg_kind, HL_ARCOS_ARG_NONE);
        } else if (s->arg_kind == HL_ARCOS_ARG_INT) {
            const int32_t args[] = { s->min, s->max, (s->min + s->max) / 2, s->min + 1 };
            for (size_t i = 0; i < 4; i++) {
                c.arg = args[i];
                assert_int_equal(through_the_wire(&c, &back), HL_OK);
                assert_int_equal(back.number, number);
                assert_int_equal(back.arg_kind, HL_ARCOS_ARG_INT);
                assert_int_equal(back.arg, args[i]);
            }
        } else {
            for (uint8_t len = 0; len <= s->max; len += 16) {
                c.str_len = len;
                for (uint8_t i = 0; i < len; i++)
                    c.str[i] = (uint8_t)(1 + (i * 7) % 32);
                assert_int_equal(through_the_wire(&c, &back), HL_OK);
                assert_int_equal(back.arg_kind, HL_ARCOS_ARG_STR);
                assert_int_equal(back.str_len, len);
                assert_memory_equal(back.str, c.str, len);
            }
        }
    }
    assert_int_equal(specs, 19);   /* 0..8, 10..13, 21, 23, 28, 29, 48, and STEP (250) */
    assert_string_equal(hl_arcos_spec_of(HL_ARCOS_SONAR)->name, "SONAR");
}

static void test_command_encoder_refuses(void **state)
{
    (void)state;
    uint8_t b[HL_ARCOS_PACKET_MAX], seq[65];
    size_t n = 0;
    memset(seq, 5, sizeof seq);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_ENABLE, 2, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_SETV, -1, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_SONARCYCLE, 1, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_SONARCYCLE, 121, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_VEL, 32768, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, HL_ARCOS_PULSE, 1, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, HL_ARCOS_VEL, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, 99, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_str(b, sizeof b, HL_ARCOS_POLLING, seq, 65, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_str(b, sizeof b, HL_ARCOS_POLLING, seq, 200, &n), HL_ERR_ARG);
    seq[3] = 33;    /* transducers are 1..32 */
    assert_int_equal(hl_arcos_encode_str(b, sizeof b, HL_ARCOS_POLLING, seq, 8, &n), HL_ERR_ARG);
    seq[3] = 0;
    assert_int_equal(hl_arcos_encode_str(b, sizeof b, HL_ARCOS_POLLING, seq, 8, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_str(b, sizeof b, HL_ARCOS_POLLING, seq, 3, &n), HL_OK);
    assert_int_equal(n, 11);
    assert_int_equal(hl_arcos_encode_int(b, 8, HL_ARCOS_VEL, 1, &n), HL_ERR_CAPACITY);
    assert_int_equal(hl_arcos_encode_int(b, 9, HL_ARCOS_VEL, 1, &n), HL_OK);
    assert_int_equal(hl_arcos_encode_int(NULL, 9, HL_ARCOS_VEL, 1, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_int(b, 9, HL_ARCOS_VEL, 1, NULL), HL_ERR_ARG);
    assert_int_equal(hl_arcos_encode_cmd(b, 9, NULL, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_frame(b, sizeof b, seq, 0, &n), HL_ERR_ARG);
    assert_int_equal(hl_arcos_frame(b, sizeof b, b, HL_ARCOS_PAYLOAD_MAX + 1, &n), HL_ERR_ARG);
}

static hl_status_t decode_bytes(const uint8_t *d, size_t n, hl_arcos_cmd_t *c)
{
    hl_arcos_packet_t pk = { .len = (uint8_t)n };
    memcpy(pk.data, d, n);
    return hl_arcos_decode_cmd(&pk, c);
}

static void test_command_decoder_validates(void **state)
{
    (void)state;
    hl_arcos_cmd_t c;
    const uint8_t bad_type[] = { 11, 0x3C, 1, 0 }, short_int[] = { 11, 0x3B, 1 };
    const uint8_t long_int[] = { 11, 0x3B, 1, 0, 0 }, short_str[] = { 3, 0x2B, 5, 1, 2 };
    const uint8_t padded[] = { 3, 0x2B, 2, 1, 2, 0 }, trailing[] = { 3, 0x2B, 2, 1, 2, 7 };
    const uint8_t unknown[] = { 99 }, enable5[] = { 4, 0x3B, 5, 0 }, bare_vel[] = { 11 };
    const uint8_t open1[] = { 1, 0x3B, 1, 0 }, vel_neg[] = { 11, 0x1B, 0x2C, 0x01 };
    const uint8_t neg_zero[] = { 11, 0x1B, 0, 0 }, move_big[] = { 8, 0x1B, 0xFF, 0xFF };
    assert_int_equal(decode_bytes(bad_type, 0, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(bad_type, 4, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(short_int, 3, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(long_int, 5, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(short_str, 5, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(trailing, 6, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(padded, 6, &c), HL_OK);
    assert_int_equal(c.arg_kind, HL_ARCOS_ARG_STR);
    assert_int_equal(c.str_len, 2);
    assert_int_equal(c.str[1], 2);
    uint8_t huge[HL_ARCOS_PAYLOAD_MAX] = { 3, 0x2B, 0 };
    assert_int_equal(decode_bytes(huge, HL_ARCOS_CMD_COUNT_MAX - 1, &c), HL_ERR_PARSE);
    assert_int_equal(decode_bytes(huge, HL_ARCOS_CMD_COUNT_MAX - 2, &c), HL_OK);
    /* Well formed but outside the subset: RANGE, with the command still filled in. */
    assert_int_equal(decode_bytes(unknown, 1, &c), HL_ERR_RANGE);
    assert_int_equal(c.number, 99);
    assert_int_equal(decode_bytes(enable5, 4, &c), HL_ERR_RANGE);
    assert_int_equal(c.arg, 5);
    assert_int_equal(decode_bytes(bare_vel, 1, &c), HL_ERR_RANGE);
    assert_int_equal(decode_bytes(move_big, 4, &c), HL_ERR_RANGE);
    assert_int_equal(c.arg, -65535);
    /* ARIA's OPEN 1 is accepted; a negative magnitude and a negative zero decode. */
    assert_int_equal(decode_bytes(open1, 4, &c), HL_OK);
    assert_int_equal(c.number, HL_ARCOS_OPEN);
    assert_int_equal(decode_bytes(vel_neg, 4, &c), HL_OK);
    assert_int_equal(c.arg, -300);
    assert_int_equal(decode_bytes(neg_zero, 4, &c), HL_OK);
    assert_int_equal(c.arg, 0);
    assert_int_equal(hl_arcos_decode_cmd(NULL, &c), HL_ERR_ARG);
}


static void assert_sip_equal(const hl_arcos_sip_t *a, const hl_arcos_sip_t *b)
{
    assert_int_equal(a->type, b->type);
    assert_int_equal(a->x, b->x);
    assert_int_equal(a->y, b->y);
    assert_int_equal(a->th, b->th);
    assert_int_equal(a->vel_left, b->vel_left);
    assert_int_equal(a->vel_right, b->vel_right);
    assert_int_equal(a->battery, b->battery);
    assert_int_equal(a->stall_bumpers, b->stall_bumpers);
    assert_int_equal(a->control, b->control);
    assert_int_equal(a->flags, b->flags);
    assert_int_equal(a->compass, b->compass);
    assert_int_equal(a->sonar_count, b->sonar_count);
    for (uint8_t i = 0; i < a->sonar_count; i++) {
        assert_int_equal(a->sonar[i].transducer, b->sonar[i].transducer);
        assert_int_equal(a->sonar[i].range, b->sonar[i].range);
    }
    assert_int_equal(a->extra_len, b->extra_len);
}

/* A SIP written byte by byte from the manuals' table, independent of the encoder. */
static void test_sip_layout(void **state)
{
    (void)state;
    const uint8_t d[] = {
        0x33, 0x34, 0x12, 0xFF, 0x7F, 0xFF, 0xFF, 0x2C, 0x01, 0xD4, 0xFE, 121,
        0x01, 0x03, 0x00, 0x04, 0x23, 0x00, 45, 2, 3, 0xE8, 0x03, 15, 0x88, 0x13,
        0, 1, 0x80, 0, 0,   /* gripper, analog port, analog, digital in, digital out */
    };
    hl_arcos_packet_t pk = { .len = sizeof d };
    hl_arcos_sip_t s;
    memcpy(pk.data, d, sizeof d);
    assert_true(hl_arcos_is_sip(&pk));
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_OK);
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_int_equal(s.x, 0x1234);
    assert_int_equal(s.y, 0x7FFF);
    assert_int_equal(s.th, -1);
    assert_int_equal(s.vel_left, 300);
    assert_int_equal(s.vel_right, -300);
    assert_int_equal(s.battery, 121);
    assert_true(s.stall_bumpers & HL_ARCOS_STALL_LEFT);
    assert_true(s.stall_bumpers & HL_ARCOS_STALL_RIGHT);
    assert_int_equal(HL_ARCOS_BUMPERS_1(s.stall_bumpers), 0);
    assert_int_equal(HL_ARCOS_BUMPERS_2(s.stall_bumpers), 1);
    assert_int_equal(s.control, 1024);
    assert_true(s.flags & HL_ARCOS_FLAG_MOTORS);
    assert_int_equal(s.flags & HL_ARCOS_FLAG_SONAR, 2);
    assert_true(s.flags & HL_ARCOS_FLAG_STOP);
    assert_int_equal(s.compass, 45);
    assert_int_equal(s.sonar_count, 2);
    assert_int_equal(s.sonar[0].transducer, 3);
    assert_int_equal(s.sonar[0].range, 1000);
    assert_int_equal(s.sonar[1].transducer, 15);
    assert_int_equal(s.sonar[1].range, 5000);
    assert_int_equal(s.extra_len, 5);
    /* The encoder writes the same bytes (the trailer as zeros). */
    uint8_t b[HL_ARCOS_PACKET_MAX], want[HL_ARCOS_PACKET_MAX];
    size_t n = 0, wn = 0;
    pk.data[27] = pk.data[28] = 0;
    assert_int_equal(hl_arcos_frame(want, sizeof want, pk.data, pk.len, &wn), HL_OK);
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_OK);
    assert_bytes(b, n, want, wn);
}

static void test_sip_round_trips(void **state)
{
    (void)state;
    hl_rng_t r;
    hl_rng_seed(&r, 7);
    for (int rep = 0; rep < 20; rep++) {
        for (uint8_t count = 0; count <= HL_ARCOS_SONAR_MAX; count++) {
            hl_arcos_sip_t s, back;
            hl_arcos_packet_t pk;
            hl_arcos_parser_t p;
            uint8_t b[HL_ARCOS_PACKET_MAX];
            size_t n = 0, used = 0;
            random_sip(&r, &s, count);
            assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_OK);
            assert_int_equal(n, 25u + 3u * count + s.extra_len);
            hl_arcos_parser_init(&p);
            assert_int_equal(hl_arcos_parse(&p, b, n, &used, &pk), HL_OK);
            assert_int_equal(hl_arcos_decode_sip(&pk, &back), HL_OK);
            assert_sip_equal(&s, &back);
            assert_int_equal(hl_arcos_encode_sip(b, n - 1, &s, &n), HL_ERR_CAPACITY);
        }
    }
}

static void test_sip_rejects(void **state)
{
    (void)state;
    hl_arcos_packet_t pk = { .len = HL_ARCOS_SIP_FIXED + 3 * 33 };
    hl_arcos_sip_t s;
    uint8_t b[HL_ARCOS_PACKET_MAX];
    size_t n = 0;
    memset(pk.data, 0, sizeof pk.data);
    pk.data[0] = HL_ARCOS_SIP_STOPPED;
    pk.data[19] = 33;   /* 33 readings, and the bytes for them */
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_ERR_PARSE);
    pk.data[19] = 32;
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_OK);
    assert_int_equal(s.extra_len, 3);
    pk.data[HL_ARCOS_SIP_FIXED + 3 * 31] = 32;   /* transducer 32 */
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_ERR_PARSE);
    pk.data[HL_ARCOS_SIP_FIXED + 3 * 31] = 31;
    pk.len = HL_ARCOS_SIP_FIXED + 3 * 32 - 1;    /* one byte short of its readings */
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_ERR_PARSE);
    pk.data[19] = 0;
    pk.len = HL_ARCOS_SIP_FIXED - 1;
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_ERR_PARSE);
    pk.len = HL_ARCOS_SIP_FIXED;
    pk.data[0] = 0x31;
    assert_false(hl_arcos_is_sip(&pk));
    assert_int_equal(hl_arcos_decode_sip(&pk, &s), HL_ERR_PARSE);
    assert_int_equal(hl_arcos_decode_sip(NULL, &s), HL_ERR_ARG);
    hl_rng_t r;
    hl_rng_seed(&r, 3);
    random_sip(&r, &s, 32);
    s.extra_len = HL_ARCOS_PAYLOAD_MAX - HL_ARCOS_SIP_FIXED - 3 * 32;
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_OK);
    assert_int_equal(n, HL_ARCOS_PACKET_MAX);
    s.extra_len++;
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_ERR_ARG);
    s.extra_len = 0;
    s.sonar[5].transducer = 32;
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_ERR_ARG);
    s.sonar[5].transducer = 0;
    s.sonar_count = 33;
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_ERR_ARG);
    s.sonar_count = 0;
    s.type = 0x34;
    assert_int_equal(hl_arcos_encode_sip(b, sizeof b, &s, &n), HL_ERR_ARG);
}

static void test_sync_handshake(void **state)
{
    (void)state;
    hl_arcos_robot_id_t id = { "bonnie", "Pioneer", "p3dx" }, back;
    uint8_t b[HL_ARCOS_PACKET_MAX];
    size_t n = 0, used = 0;
    hl_arcos_parser_t p;
    hl_arcos_packet_t pk;
    assert_int_equal(hl_arcos_encode_sync2(b, sizeof b, &id, &n), HL_OK);
    assert_int_equal(n, 5u + 1 + 7 + 8 + 5);
    hl_arcos_parser_init(&p);
    assert_int_equal(hl_arcos_parse(&p, b, n, &used, &pk), HL_OK);
    assert_false(hl_arcos_is_sync_echo(&pk, HL_ARCOS_SYNC2));
    assert_int_equal(hl_arcos_decode_sync2(&pk, &back), HL_OK);
    assert_string_equal(back.name, "bonnie");
    assert_string_equal(back.cls, "Pioneer");
    assert_string_equal(back.subclass, "p3dx");
    pk.data[pk.len - 1] = 'x';   /* the subclass loses its NUL */
    assert_int_equal(hl_arcos_decode_sync2(&pk, &back), HL_ERR_PARSE);
    assert_string_equal(back.name, "");
    pk.data[pk.len - 1] = 0;
    pk.data[2] = 0x07;           /* not printable */
    assert_int_equal(hl_arcos_decode_sync2(&pk, &back), HL_ERR_PARSE);
    memset(pk.data + 1, 'a', 100);   /* a name longer than 63 bytes */
    pk.data[101] = pk.data[102] = pk.data[103] = 0;
    pk.len = 104;
    assert_int_equal(hl_arcos_decode_sync2(&pk, &back), HL_ERR_PARSE);
    pk.data[64] = 0;             /* 63 bytes: the longest that fits */
    assert_int_equal(hl_arcos_decode_sync2(&pk, &back), HL_OK);
    assert_int_equal(strlen(back.name), 63);
    id.cls[0] = '\t';
    assert_int_equal(hl_arcos_encode_sync2(b, sizeof b, &id, &n), HL_ERR_ARG);
    memset(id.cls, 'c', sizeof id.cls);   /* unterminated */
    assert_int_equal(hl_arcos_encode_sync2(b, sizeof b, &id, &n), HL_ERR_ARG);
    /* The SYNC0/1/2 echoes are the commands' own bytes. */
    for (uint8_t k = 0; k < 3; k++) {
        assert_int_equal(hl_arcos_encode_none(b, sizeof b, k, &n), HL_OK);
        assert_int_equal(hl_arcos_parse(&p, b, n, &used, &pk), HL_OK);
        assert_true(hl_arcos_is_sync_echo(&pk, k));
        assert_false(hl_arcos_is_sync_echo(&pk, (uint8_t)((k + 1) % 3)));
    }
}

/* A stream of @p k packets of assorted kinds and sizes (1 and 247 payload bytes among
 * them); returns its length and their offsets in @p at. */
static void test_odometry_unwraps(void **state)
{
    (void)state;
    hl_arcos_odom_t o;
    hl_arcos_sip_t s = { .type = HL_ARCOS_SIP_STOPPED };
    hl_arcos_odom_init(&o, 4096);
    s.x = 0x8000 | 0x7FF0;   /* bit 15 is not position */
    s.y = 5;
    s.th = 4090;
    assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_OK);
    assert_int_equal(o.x, 0x7FF0);
    assert_int_equal(o.y, 5);
    assert_int_equal(o.th, 4090);
    s.x = 0x0010;            /* forward through the 15-bit wrap: +32 */
    s.y = 0x7FFB;            /* backward through 0: -10 */
    s.th = 6;                /* ccw through a turn: +12 */
    assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_OK);
    assert_int_equal(o.x, 0x7FF0 + 32);
    assert_int_equal(o.y, -5);
    assert_int_equal(o.th, 4102);
    for (int i = 0; i < 100; i++) {   /* 100 steps of 400 units: 40000 > 2^15 */
        s.x = (uint16_t)((s.x + 400) & 0x7FFF);
        s.th = (int16_t)((s.th + 4096 - 100) % 4096);
        assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_OK);
    }
    assert_int_equal(o.x, 0x7FF0 + 32 + 40000);
    assert_int_equal(o.th, 4102 - 10000);
    /* A heading that wraps at 2^16 (units_per_turn 0). */
    hl_arcos_odom_init(&o, 0);
    s.th = 32000;
    assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_OK);
    s.th = -32000;
    assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_OK);
    assert_int_equal(o.th, 33536);
    hl_arcos_odom_init(&o, 70000);
    assert_int_equal(hl_arcos_odom_unwrap(&o, &s), HL_ERR_ARG);
    assert_int_equal(hl_arcos_odom_unwrap(NULL, &s), HL_ERR_ARG);
    /* Angle units to binary angles: 4096 per turn is 16 BAM per unit. */
    const hl_arcos_conv_t pioneer = HL_ARCOS_CONV_PIONEER, none = { 0, 0, 0, 0 };
    assert_int_equal(hl_arcos_angle_to_bam(&pioneer, 1024), 16384);
    assert_int_equal(hl_arcos_angle_to_bam(&pioneer, -1024), 49152);
    assert_int_equal(hl_arcos_angle_to_bam(&pioneer, 4096 * 1000 + 1), 16);
    assert_int_equal(hl_arcos_angle_to_bam(&none, 5), 0);
    const hl_arcos_conv_t degrees = { 1000, 1000, 1000, 360 };
    assert_int_equal(hl_arcos_angle_to_bam(&degrees, 90), 16384);
    assert_int_equal(hl_arcos_angle_to_bam(&degrees, 1), 182);   /* 182.04 */
}

static void test_parser_arguments(void **state)
{
    (void)state;
    hl_arcos_parser_t p;
    hl_arcos_packet_t pk;
    size_t used = 7;
    uint8_t b[4] = { 0xFA, 0xFB, 0x03, 0x00 };
    hl_arcos_parser_init(&p);
    assert_int_equal(hl_arcos_parse(NULL, b, 4, &used, &pk), HL_ERR_ARG);
    assert_int_equal(hl_arcos_parse(&p, NULL, 4, &used, &pk), HL_ERR_ARG);
    assert_int_equal(hl_arcos_parse(&p, b, 4, NULL, &pk), HL_ERR_ARG);
    assert_int_equal(hl_arcos_parse(&p, b, 4, &used, NULL), HL_ERR_ARG);
    assert_int_equal(hl_arcos_parse(&p, NULL, 0, &used, &pk), HL_ERR_EMPTY);
    assert_int_equal(used, 0);
    assert_int_equal(hl_arcos_parse(&p, b, 4, &used, &pk), HL_ERR_EMPTY);
    assert_int_equal(used, 4);
    assert_int_equal(p.fill, 4);
    hl_arcos_parser_discard(&p);    /* a reconnection: the partial SYNC0 is gone */
    assert_int_equal(p.fill, 0);
    assert_int_equal(p.garbage_bytes, 0);
    const uint8_t rest[] = { 0x00, 0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00 };
    assert_int_equal(hl_arcos_parse(&p, rest, sizeof rest, &used, &pk), HL_OK);
    assert_int_equal(used, sizeof rest);
    assert_true(hl_arcos_is_sync_echo(&pk, HL_ARCOS_SYNC0));
    assert_int_equal(p.garbage_bytes, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_checksum_manual_examples),
        cmocka_unit_test(test_every_command_round_trips),
        cmocka_unit_test(test_command_encoder_refuses),
        cmocka_unit_test(test_command_decoder_validates),
        cmocka_unit_test(test_sip_layout),
        cmocka_unit_test(test_sip_round_trips),
        cmocka_unit_test(test_sip_rejects),
        cmocka_unit_test(test_sync_handshake),
        cmocka_unit_test(test_odometry_unwraps),
        cmocka_unit_test(test_parser_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
