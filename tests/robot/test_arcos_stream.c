/* Tests for src/robot/arcos.c's streaming parser: streams cut at every offset and fed byte
 * by byte, resynchronization, and 2 x 10,000 randomly corrupted streams (counters checked
 * where the corruption fixes them). */
#include "arcos_testkit.h"

static got_t g_got;
static uint8_t g_stream[STREAM_MAX];

static size_t mixed_stream(uint8_t *s, size_t k, size_t *at)
{
    hl_rng_t r;
    hl_rng_seed(&r, 11);
    size_t n = 0, len = 0;
    for (size_t i = 0; i < k; i++) {
        uint8_t payload[HL_ARCOS_PAYLOAD_MAX];
        hl_arcos_sip_t sip;
        at[i] = n;
        switch (i % 4) {
        case 0:
            random_sip(&r, &sip, (uint8_t)(i % 33));
            assert_int_equal(hl_arcos_encode_sip(s + n, STREAM_MAX - n, &sip, &len), HL_OK);
            break;
        case 1:
            assert_int_equal(hl_arcos_encode_int(s + n, STREAM_MAX - n, HL_ARCOS_RVEL, -45, &len),
                             HL_OK);
            break;
        default:
            for (size_t j = 0; j < HL_ARCOS_PAYLOAD_MAX; j++)
                payload[j] = (uint8_t)hl_rng_next(&r);
            assert_int_equal(hl_arcos_frame(s + n, STREAM_MAX - n, payload,
                                            i % 4 == 2 ? 1 : HL_ARCOS_PAYLOAD_MAX, &len),
                             HL_OK);
        }
        n += len;
    }
    return n;
}

static void assert_stream_packets(const got_t *g, const uint8_t *s, const size_t *at, size_t k)
{
    assert_int_equal(g->n, k);
    for (size_t i = 0; i < k; i++)
        assert_true(same_packet(&g->pk[i], s + at[i]));
}

static void test_byte_by_byte(void **state)
{
    (void)state;
    size_t at[24];
    size_t n = mixed_stream(g_stream, 24, at);
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    memset(&g_got, 0, sizeof g_got);
    for (size_t i = 0; i < n; i++)
        feed(&p, g_stream + i, 1, &g_got);
    assert_stream_packets(&g_got, g_stream, at, 24);
    assert_int_equal(p.packets, 24);
    assert_int_equal(p.garbage_bytes + p.bad_checksums + p.bad_lengths + p.fill, 0);
}

static void test_split_at_every_offset(void **state)
{
    (void)state;
    size_t at[6];
    size_t n = mixed_stream(g_stream, 6, at);
    for (size_t cut = 1; cut < n; cut++) {
        hl_arcos_parser_t p;
        hl_arcos_parser_init(&p);
        memset(&g_got, 0, sizeof g_got);
        feed(&p, g_stream, cut, &g_got);
        feed(&p, g_stream + cut, n - cut, &g_got);
        assert_stream_packets(&g_got, g_stream, at, 6);
        assert_int_equal(p.garbage_bytes + p.bad_checksums + p.bad_lengths + p.fill, 0);
    }
}

/* Feeds @p pre, then a STOP packet, then @p post; checks the STOP (and only it) came out
 * with the given counters. */
static void check_resync(const uint8_t *pre, size_t npre, const uint8_t *post, size_t npost,
                         uint64_t garbage, uint64_t bad_ck, uint64_t bad_len)
{
    uint8_t s[2 * HL_ARCOS_PACKET_MAX], stop[8];
    size_t n = 0, len = 0;
    hl_arcos_parser_t p;
    assert_int_equal(hl_arcos_encode_none(stop, sizeof stop, HL_ARCOS_STOP, &len), HL_OK);
    memcpy(s, pre, npre);
    memcpy(s + npre, stop, len);
    if (npost > 0)
        memcpy(s + npre + len, post, npost);
    n = npre + len + npost;
    for (size_t chunk = 1; chunk <= n; chunk = chunk * 3 + 1) {
        hl_arcos_parser_init(&p);
        memset(&g_got, 0, sizeof g_got);
        for (size_t off = 0; off < n; off += chunk)
            feed(&p, s + off, off + chunk <= n ? chunk : n - off, &g_got);
        assert_int_equal(g_got.n, 1);
        assert_true(same_packet(&g_got.pk[0], stop));
        assert_int_equal(p.garbage_bytes, garbage);
        assert_int_equal(p.bad_checksums, bad_ck);
        assert_int_equal(p.bad_lengths, bad_len);
        assert_int_equal(p.fill, 0);
    }
}

static void test_resynchronizes(void **state)
{
    (void)state;
    const uint8_t noise[] = { 0x00, 0x11, 0xFA, 0x22, 0xFB };
    const uint8_t fafa[] = { 0xFA };
    const uint8_t short_count[] = { 0xFA, 0xFB, 0x02 };
    /* A count of 250 that is the next packet's 0xFA: rejected, and the search restarts at
     * the byte after the bad header, which begins the real packet. */
    const uint8_t count_fa[] = { 0xFA, 0xFB };
    /* A header announcing 32 bytes with only 4 of them: the STOP hides inside its span
     * and is found once the span is complete and fails its checksum. */
    const uint8_t cut[] = { 0xFA, 0xFB, 32, 1, 2, 3, 4 };
    uint8_t filler[40];
    memset(filler, 0x55, sizeof filler);
    check_resync(noise, sizeof noise, NULL, 0, 5, 0, 0);
    check_resync(fafa, sizeof fafa, NULL, 0, 1, 0, 0);
    check_resync(short_count, sizeof short_count, NULL, 0, 3, 0, 1);
    check_resync(count_fa, sizeof count_fa, NULL, 0, 2, 0, 1);
    check_resync(cut, sizeof cut, filler, sizeof filler, 7 + 40, 1, 0);
    /* A STOP with its last checksum byte wrong: all 6 bytes are garbage. */
    const uint8_t bad_sum[] = { 0xFA, 0xFB, 0x03, 0x1D, 0x00, 0x1E };
    check_resync(bad_sum, sizeof bad_sum, NULL, 0, 6, 1, 0);
}

/*
 * Randomized corruption. Each iteration builds 1..6 packets, each intact, with one bit
 * flipped or truncated, some followed by 1..8 random bytes, then a clean tail of at
 * least HL_ARCOS_PACKET_MAX bytes so that every candidate is decided; the stream is fed
 * in random chunks. Every intact packet must come out, in order, and nothing else.
 *
 * In "tame" streams no payload, checksum or inserted byte is 0xFA or 0xFB, so the only
 * candidates are the packets' own headers and the counters follow from the corruption:
 * a flip in the header makes the whole packet garbage; in the count, a bad length if
 * the new count is outside 3..249, else a bad checksum; anywhere else a bad checksum. A
 * truncation to 1 byte is garbage; to 2 bytes (0xFA 0xFB), the next byte is the count;
 * to more, the span runs into what follows and fails its checksum. "Wild" streams use
 * any bytes and flip up to three bits; there only the packets are checked.
 *
 * The protocol cannot tell every corruption from a packet: a span that runs past a real
 * end passes the 16-bit checksum by chance (2^-16), and stacked cut headers can form a
 * valid frame outright (0xFA 0xFB 4, 0xFA 0xFB, 0xFA 0xFB: a 2-byte payload is its own
 * checksum). Such a phantom must be a valid frame present verbatim in the stream; the
 * test checks that, counts those iterations instead of failing on them, and bounds them.
 */
typedef struct expect {
    size_t at[64], n;          /* offsets of the intact packets in g_stream */
    uint64_t garbage, bad_ck, bad_len;
} expect_t;

static uint8_t random_byte(hl_rng_t *r, bool tame)
{
    for (;;) {
        uint8_t b = (uint8_t)hl_rng_next(r);
        if (!tame || (b != 0xFA && b != 0xFB))
            return b;
    }
}

static bool is_header_byte(uint8_t b)
{
    return b == 0xFA || b == 0xFB;
}

static size_t random_packet(hl_rng_t *r, uint8_t *out, bool tame)
{
    for (;;) {
        uint8_t payload[HL_ARCOS_PAYLOAD_MAX];
        size_t n = 1 + hl_rng_below(r, hl_rng_below(r, 4) ? 40 : HL_ARCOS_PAYLOAD_MAX), len = 0;
        for (size_t i = 0; i < n; i++)
            payload[i] = random_byte(r, tame);
        assert_int_equal(hl_arcos_frame(out, HL_ARCOS_PACKET_MAX, payload, n, &len), HL_OK);
        if (!tame || (!is_header_byte(out[len - 2]) && !is_header_byte(out[len - 1])))
            return len;
    }
}

/* Builds one corrupted stream in g_stream; returns its length. */
static size_t corrupted_stream(hl_rng_t *r, bool tame, expect_t *e)
{
    size_t n = 0, cut2[8], ncut2 = 0;
    uint32_t k = 1 + hl_rng_below(r, 6);
    memset(e, 0, sizeof *e);
    for (uint32_t i = 0; i < k; i++) {
        uint8_t *pk = g_stream + n;
        size_t len = random_packet(r, pk, tame);
        uint32_t op = hl_rng_below(r, 4);
        if (op < 2) {
            e->at[e->n++] = n;
        } else if (op == 2) {
            /* One bit (tame) or a random non-empty set of bits of one byte (wild). */
            size_t q = hl_rng_below(r, (uint32_t)len);
            pk[q] ^= (uint8_t)(tame ? 1u << hl_rng_below(r, 8) : 1 + hl_rng_below(r, 255));
            if (q == 2 && (pk[2] < HL_ARCOS_COUNT_MIN || pk[2] > HL_ARCOS_COUNT_MAX))
                e->bad_len++;
            else if (q >= 2)
                e->bad_ck++;
            e->garbage += len;
        } else {
            len = 1 + hl_rng_below(r, (uint32_t)len - 1);
            if (len == 2)
                cut2[ncut2++] = n + 2;
            else if (len >= 3)
                e->bad_ck++;
            e->garbage += len;
        }
        n += len;
        if (hl_rng_below(r, 10) < 3) {
            uint32_t extra = 1 + hl_rng_below(r, 8);
            for (uint32_t j = 0; j < extra; j++)
                g_stream[n++] = random_byte(r, tame);
            e->garbage += extra;
        }
    }
    for (size_t tail = 0; tail < HL_ARCOS_PACKET_MAX;) {
        size_t len = random_packet(r, g_stream + n, tame);
        e->at[e->n++] = n;
        n += len;
        tail += len;
    }
    /* A packet cut to 0xFA 0xFB takes whatever follows for its count. */
    for (size_t c = 0; c < ncut2; c++) {
        uint8_t count = g_stream[cut2[c]];
        if (count < HL_ARCOS_COUNT_MIN || count > HL_ARCOS_COUNT_MAX)
            e->bad_len++;
        else
            e->bad_ck++;
    }
    return n;
}

/* True if @p pk is framed, checksum and all, somewhere in g_stream[0, n). */
static bool framed_in_stream(const hl_arcos_packet_t *pk, size_t n)
{
    for (size_t q = 0; q + pk->len + 5u <= n; q++) {
        const uint8_t *f = g_stream + q;
        if (f[0] == 0xFA && f[1] == 0xFB && same_packet(pk, f) &&
            hl_arcos_checksum(f + 3, pk->len) == (uint16_t)(f[3 + pk->len] << 8 | f[4 + pk->len]))
            return true;
    }
    return false;
}

/* Feeds g_stream in random chunks; returns true if the output is exactly the intact
 * packets (and then checks the counters when @p tame), false if a phantom came out. */
static bool run_corrupted(hl_rng_t *r, bool tame)
{
    expect_t e;
    size_t n = corrupted_stream(r, tame, &e);
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    memset(&g_got, 0, sizeof g_got);
    size_t max_chunk = hl_rng_below(r, 10) == 0 ? n : 1 + hl_rng_below(r, 64);
    for (size_t off = 0; off < n;) {
        size_t chunk = 1 + hl_rng_below(r, (uint32_t)max_chunk);
        chunk = chunk < n - off ? chunk : n - off;
        feed(&p, g_stream + off, chunk, &g_got);
        off += chunk;
    }
    /* Every byte fed is in a packet, in garbage, or pending. */
    uint64_t in_packets = 0;
    for (size_t i = 0; i < g_got.n; i++)
        in_packets += g_got.pk[i].len + 5u;
    assert_int_equal(in_packets + p.garbage_bytes + p.fill, n);
    assert_int_equal(p.packets, g_got.n);
    bool exact = g_got.n == e.n;
    for (size_t i = 0; exact && i < e.n; i++)
        exact = same_packet(&g_got.pk[i], g_stream + e.at[i]);
    if (!exact) {
        /* Only a phantom may explain it: a packet that was not sent intact. */
        bool phantom = false;
        for (size_t i = 0; i < g_got.n && !phantom; i++) {
            bool sent = false;
            for (size_t j = 0; j < e.n && !sent; j++)
                sent = same_packet(&g_got.pk[i], g_stream + e.at[j]);
            phantom = !sent;
            if (phantom)
                assert_true(framed_in_stream(&g_got.pk[i], n));
        }
        assert_true(phantom);
        return false;
    }
    assert_int_equal(p.fill, 0);
    if (tame) {
        assert_int_equal(p.garbage_bytes, e.garbage);
        assert_int_equal(p.bad_checksums, e.bad_ck);
        assert_int_equal(p.bad_lengths, e.bad_len);
    }
    return true;
}

static void test_random_corruption(void **state)
{
    (void)state;
    hl_rng_t r;
    hl_rng_seed(&r, 20240611);
    int phantoms = 0;
    for (int it = 0; it < 10000; it++) {
        phantoms += !run_corrupted(&r, true);
        phantoms += !run_corrupted(&r, false);
    }
    /* Some 3 x 10^4 candidates are rejected in all; 2 phantoms with this seed. */
    print_message("  random corruption: %d phantom packet(s) in 20000 streams\n", phantoms);
    assert_true(phantoms <= 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_byte_by_byte),
        cmocka_unit_test(test_split_at_every_offset),
        cmocka_unit_test(test_resynchronizes),
        cmocka_unit_test(test_random_corruption),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
