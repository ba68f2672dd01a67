/* arcos.c - ARCOS framing: the checksum, framing a payload, and the streaming parser
 * (see arcos.h; commands and SIPs are in arcos_msg.c). */
#include "houghloc/arcos.h"

#include <string.h>

uint16_t hl_arcos_checksum(const uint8_t *payload, size_t n)
{
    /* Sum of big-endian byte pairs, modulo 2^16; an odd last byte is XORed into the low
     * byte (Pioneer manuals, "Packet Checksum"; ARIA's ArRobotPacket::calcCheckSum). */
    uint16_t sum = 0;
    size_t i = 0;
    if (!payload)
        return 0;
    for (; i + 1 < n; i += 2)
        sum = (uint16_t)(sum + (uint16_t)(payload[i] << 8 | payload[i + 1]));
    if (i < n)
        sum ^= payload[i];
    return sum;
}

hl_status_t hl_arcos_frame(uint8_t *buf, size_t cap, const uint8_t *payload, size_t n,
                           size_t *len)
{
    if (!buf || !payload || !len || n < 1 || n > HL_ARCOS_PAYLOAD_MAX)
        return HL_ERR_ARG;
    if (cap < n + 5)
        return HL_ERR_CAPACITY;
    uint16_t sum = hl_arcos_checksum(payload, n);
    buf[0] = HL_ARCOS_HDR0;
    buf[1] = HL_ARCOS_HDR1;
    buf[2] = (uint8_t)(n + 2);
    memmove(buf + 3, payload, n);   /* the payload may already sit at buf + 3 */
    buf[3 + n] = (uint8_t)(sum >> 8);
    buf[4 + n] = (uint8_t)sum;
    *len = n + 5;
    return HL_OK;
}

void hl_arcos_parser_init(hl_arcos_parser_t *p)
{
    if (p)
        memset(p, 0, sizeof *p);
}

void hl_arcos_parser_discard(hl_arcos_parser_t *p)
{
    if (p)
        p->fill = 0;
}

/* Removes the first @p k pending bytes. */
static void drop(hl_arcos_parser_t *p, size_t k)
{
    memmove(p->buf, p->buf + k, p->fill - k);
    p->fill = (uint16_t)(p->fill - k);
}

/* Rejects the candidate at buf[0]: its 0xFA is garbage, and the search goes on from the
 * byte after it, so a packet that started inside the rejected span is not lost. */
static void reject(hl_arcos_parser_t *p)
{
    p->garbage_bytes++;
    drop(p, 1);
}

/*
 * Works through the pending bytes. Returns true with a packet in *out, or false when the
 * pending bytes are a proper prefix of a packet that may still complete: nothing, 0xFA,
 * 0xFA 0xFB, or a header with a valid count and fewer than count bytes after it.
 */
static bool scan(hl_arcos_parser_t *p, hl_arcos_packet_t *out)
{
    for (;;) {
        if (p->fill == 0)
            return false;
        if (p->buf[0] != HL_ARCOS_HDR0) {
            const uint8_t *fa = memchr(p->buf, HL_ARCOS_HDR0, p->fill);
            size_t skip = fa ? (size_t)(fa - p->buf) : p->fill;
            p->garbage_bytes += skip;
            drop(p, skip);
            continue;
        }
        if (p->fill < 2)
            return false;
        if (p->buf[1] != HL_ARCOS_HDR1) {
            reject(p);
            continue;
        }
        if (p->fill < 3)
            return false;
        uint8_t count = p->buf[2];
        if (count < HL_ARCOS_COUNT_MIN || count > HL_ARCOS_COUNT_MAX) {
            p->bad_lengths++;
            reject(p);
            continue;
        }
        size_t total = 3u + count;
        if (p->fill < total)
            return false;
        size_t n = count - 2u;
        uint16_t sent = (uint16_t)(p->buf[total - 2] << 8 | p->buf[total - 1]);
        if (hl_arcos_checksum(p->buf + 3, n) != sent) {
            p->bad_checksums++;
            reject(p);
            continue;
        }
        out->len = (uint8_t)n;
        memcpy(out->data, p->buf + 3, n);
        p->packets++;
        drop(p, total);
        return true;
    }
}

hl_status_t hl_arcos_parse(hl_arcos_parser_t *p, const uint8_t *in, size_t n,
                           size_t *consumed, hl_arcos_packet_t *out)
{
    if (!p || !consumed || !out || (!in && n > 0))
        return HL_ERR_ARG;
    *consumed = 0;
    /* Bytes kept after a rejected candidate come before any new input. */
    if (scan(p, out))
        return HL_OK;
    size_t i = 0;
    while (i < n) {
        if (p->fill == 0) {
            /* Between packets: skip to the next 0xFA without buffering. */
            const uint8_t *fa = memchr(in + i, HL_ARCOS_HDR0, n - i);
            size_t skip = fa ? (size_t)(fa - (in + i)) : n - i;
            p->garbage_bytes += skip;
            i += skip;
            if (i == n)
                break;
        }
        /* Inside a header, one byte at a time (each may end the candidate); once the
         * count is known and valid, the rest of the candidate at once. */
        size_t take = 1;
        if (p->fill >= 3) {
            take = 3u + p->buf[2] - p->fill;
            if (take > n - i)
                take = n - i;
        }
        memcpy(p->buf + p->fill, in + i, take);
        p->fill = (uint16_t)(p->fill + take);
        i += take;
        if (scan(p, out)) {
            *consumed = i;
            return HL_OK;
        }
    }
    *consumed = n;
    return HL_ERR_EMPTY;
}
