/* arcos_msg.c - ARCOS payloads: client commands, the standard SIP, the SYNC2 reply, and
 * odometry unwrapping (see arcos.h; framing and the parser are in arcos.c). */
#include "houghloc/arcos.h"

#include <string.h>

/* ---- client commands ---------------------------------------------------------------- */

/* The supported subset (docs/manual/arcos.md). A constant table, not state. Integer limits are
 * what the manuals and ARIA give for each command; +-32767 where a command takes any
 * signed 16-bit value. POLLING's string length counts sonar numbers: up to 16 for each of
 * four arrays; an empty string disables the sonar, as SONAR 0 does. */
static const hl_arcos_cmd_spec_t SPECS[] = {
    { HL_ARCOS_PULSE, HL_ARCOS_ARG_NONE, 0, 0, "SYNC0/PULSE" },
    { HL_ARCOS_OPEN, HL_ARCOS_ARG_NONE, 0, 0, "SYNC1/OPEN" },
    { HL_ARCOS_CLOSE, HL_ARCOS_ARG_NONE, 0, 0, "SYNC2/CLOSE" },
    { HL_ARCOS_POLLING, HL_ARCOS_ARG_STR, 0, 64, "POLLING" },
    { HL_ARCOS_ENABLE, HL_ARCOS_ARG_INT, 0, 1, "ENABLE" },
    { HL_ARCOS_SETA, HL_ARCOS_ARG_INT, -32767, 32767, "SETA" },
    { HL_ARCOS_SETV, HL_ARCOS_ARG_INT, 0, 32767, "SETV" },
    { HL_ARCOS_SETO, HL_ARCOS_ARG_NONE, 0, 0, "SETO" },
    { HL_ARCOS_MOVE, HL_ARCOS_ARG_INT, -32767, 32767, "MOVE" },
    { HL_ARCOS_SETRV, HL_ARCOS_ARG_INT, 0, 32767, "SETRV" },
    { HL_ARCOS_VEL, HL_ARCOS_ARG_INT, -32767, 32767, "VEL" },
    { HL_ARCOS_HEAD, HL_ARCOS_ARG_INT, -32767, 32767, "HEAD" },
    { HL_ARCOS_DHEAD, HL_ARCOS_ARG_INT, -32767, 32767, "DHEAD" },
    { HL_ARCOS_RVEL, HL_ARCOS_ARG_INT, -32767, 32767, "RVEL" },
    { HL_ARCOS_SETRA, HL_ARCOS_ARG_INT, -32767, 32767, "SETRA" },
    { HL_ARCOS_SONAR, HL_ARCOS_ARG_INT, 0, 9, "SONAR" },
    { HL_ARCOS_STOP, HL_ARCOS_ARG_NONE, 0, 0, "STOP" },
    { HL_ARCOS_SONARCYCLE, HL_ARCOS_ARG_INT, 2, 120, "SONARCYCLE" },
    { HL_ARCOS_STEP, HL_ARCOS_ARG_NONE, 0, 0, "STEP" },
};

const hl_arcos_cmd_spec_t *hl_arcos_spec_of(uint8_t number)
{
    for (size_t i = 0; i < sizeof SPECS / sizeof SPECS[0]; i++)
        if (SPECS[i].number == number)
            return &SPECS[i];
    return NULL;
}

/* Whether @p c is in the supported subset. @p lenient accepts an integer argument on a
 * command that takes none, as ARCOS does (ARIA sends OPEN and CLOSE with 1). */
static bool supported(const hl_arcos_cmd_t *c, bool lenient)
{
    const hl_arcos_cmd_spec_t *s = hl_arcos_spec_of(c->number);
    if (!s)
        return false;
    if (c->arg_kind != s->arg_kind)
        return lenient && s->arg_kind == HL_ARCOS_ARG_NONE && c->arg_kind == HL_ARCOS_ARG_INT &&
               c->arg >= -HL_ARCOS_INT_MAX && c->arg <= HL_ARCOS_INT_MAX;
    if (s->arg_kind == HL_ARCOS_ARG_INT)
        return c->arg >= s->min && c->arg <= s->max;
    if (s->arg_kind == HL_ARCOS_ARG_STR) {
        if (c->str_len < s->min || c->str_len > s->max)
            return false;
        /* POLLING names transducers 1..32 (the SIP numbers them 0..31). */
        for (size_t i = 0; i < c->str_len; i++)
            if (c->str[i] < 1 || c->str[i] > 32)
                return false;
    }
    return true;
}

hl_status_t hl_arcos_encode_cmd(uint8_t *buf, size_t cap, const hl_arcos_cmd_t *cmd,
                                size_t *len)
{
    if (!buf || !cmd || !len || !supported(cmd, false))
        return HL_ERR_ARG;
    uint8_t payload[HL_ARCOS_CMD_COUNT_MAX - 2];
    size_t n = 0;
    payload[n++] = cmd->number;
    if (cmd->arg_kind == HL_ARCOS_ARG_INT) {
        uint32_t mag = (uint32_t)(cmd->arg < 0 ? -cmd->arg : cmd->arg);
        payload[n++] = cmd->arg < 0 ? HL_ARCOS_ARGTYPE_NEG : HL_ARCOS_ARGTYPE_POS;
        payload[n++] = (uint8_t)mag;
        payload[n++] = (uint8_t)(mag >> 8);
    } else if (cmd->arg_kind == HL_ARCOS_ARG_STR) {
        payload[n++] = HL_ARCOS_ARGTYPE_STR;
        payload[n++] = cmd->str_len;
        memcpy(payload + n, cmd->str, cmd->str_len);
        n += cmd->str_len;
    }
    return hl_arcos_frame(buf, cap, payload, n, len);
}

hl_status_t hl_arcos_encode_none(uint8_t *buf, size_t cap, uint8_t number, size_t *len)
{
    hl_arcos_cmd_t c = { .number = number, .arg_kind = HL_ARCOS_ARG_NONE };
    return hl_arcos_encode_cmd(buf, cap, &c, len);
}

hl_status_t hl_arcos_encode_int(uint8_t *buf, size_t cap, uint8_t number, int32_t arg,
                                size_t *len)
{
    hl_arcos_cmd_t c = { .number = number, .arg_kind = HL_ARCOS_ARG_INT, .arg = arg };
    return hl_arcos_encode_cmd(buf, cap, &c, len);
}

hl_status_t hl_arcos_encode_str(uint8_t *buf, size_t cap, uint8_t number, const uint8_t *s,
                                size_t n, size_t *len)
{
    if ((!s && n > 0) || n > HL_ARCOS_STR_MAX)
        return HL_ERR_ARG;
    hl_arcos_cmd_t c = { .number = number, .arg_kind = HL_ARCOS_ARG_STR, .str_len = (uint8_t)n };
    if (n > 0)
        memcpy(c.str, s, n);
    return hl_arcos_encode_cmd(buf, cap, &c, len);
}

hl_status_t hl_arcos_decode_cmd(const hl_arcos_packet_t *pkt, hl_arcos_cmd_t *cmd)
{
    if (!pkt || !cmd)
        return HL_ERR_ARG;
    memset(cmd, 0, sizeof *cmd);
    const uint8_t *d = pkt->data;
    size_t n = pkt->len;
    if (n < 1 || n > HL_ARCOS_CMD_COUNT_MAX - 2)
        return HL_ERR_PARSE;
    cmd->number = d[0];
    if (n > 1) {
        switch (d[1]) {
        case HL_ARCOS_ARGTYPE_POS:
        case HL_ARCOS_ARGTYPE_NEG: {
            if (n != 4)
                return HL_ERR_PARSE;
            int32_t mag = d[2] | d[3] << 8;
            cmd->arg_kind = HL_ARCOS_ARG_INT;
            cmd->arg = d[1] == HL_ARCOS_ARGTYPE_NEG ? -mag : mag;
            break;
        }
        case HL_ARCOS_ARGTYPE_STR: {
            if (n < 3 || 3u + d[2] > n)
                return HL_ERR_PARSE;
            /* Only NUL padding may follow the counted bytes. */
            for (size_t i = 3u + d[2]; i < n; i++)
                if (d[i] != 0)
                    return HL_ERR_PARSE;
            cmd->arg_kind = HL_ARCOS_ARG_STR;
            cmd->str_len = d[2];
            memcpy(cmd->str, d + 3, d[2]);
            break;
        }
        default:
            return HL_ERR_PARSE;
        }
    }
    return supported(cmd, true) ? HL_OK : HL_ERR_RANGE;
}

/* ---- server information packets ----------------------------------------------------- */

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

bool hl_arcos_is_sip(const hl_arcos_packet_t *pkt)
{
    return pkt && pkt->len >= 1 &&
           (pkt->data[0] == HL_ARCOS_SIP_STOPPED || pkt->data[0] == HL_ARCOS_SIP_MOVING);
}

hl_status_t hl_arcos_decode_sip(const hl_arcos_packet_t *pkt, hl_arcos_sip_t *sip)
{
    if (!pkt || !sip)
        return HL_ERR_ARG;
    memset(sip, 0, sizeof *sip);
    const uint8_t *d = pkt->data;
    size_t n = pkt->len;
    if (!hl_arcos_is_sip(pkt) || n < HL_ARCOS_SIP_FIXED || n > HL_ARCOS_PAYLOAD_MAX)
        return HL_ERR_PARSE;
    uint8_t count = d[19];
    if (count > HL_ARCOS_SONAR_MAX || n < HL_ARCOS_SIP_FIXED + 3u * count)
        return HL_ERR_PARSE;
    sip->type = d[0];
    sip->x = get16(d + 1);
    sip->y = get16(d + 3);
    sip->th = (int16_t)get16(d + 5);
    sip->vel_left = (int16_t)get16(d + 7);
    sip->vel_right = (int16_t)get16(d + 9);
    sip->battery = d[11];
    sip->stall_bumpers = get16(d + 12);
    sip->control = (int16_t)get16(d + 14);
    sip->flags = get16(d + 16);
    sip->compass = d[18];
    for (size_t i = 0; i < count; i++) {
        const uint8_t *r = d + HL_ARCOS_SIP_FIXED + 3 * i;
        if (r[0] >= HL_ARCOS_SONAR_MAX)
            return HL_ERR_PARSE;
        sip->sonar[i].transducer = r[0];
        sip->sonar[i].range = get16(r + 1);
    }
    sip->sonar_count = count;
    sip->extra_len = (uint8_t)(n - HL_ARCOS_SIP_FIXED - 3u * count);
    return HL_OK;
}

hl_status_t hl_arcos_encode_sip(uint8_t *buf, size_t cap, const hl_arcos_sip_t *sip,
                                size_t *len)
{
    if (!buf || !sip || !len)
        return HL_ERR_ARG;
    if ((sip->type != HL_ARCOS_SIP_STOPPED && sip->type != HL_ARCOS_SIP_MOVING) ||
        sip->sonar_count > HL_ARCOS_SONAR_MAX)
        return HL_ERR_ARG;
    size_t n = HL_ARCOS_SIP_FIXED + 3u * sip->sonar_count + sip->extra_len;
    if (n > HL_ARCOS_PAYLOAD_MAX)
        return HL_ERR_ARG;
    uint8_t d[HL_ARCOS_PAYLOAD_MAX];
    d[0] = sip->type;
    put16(d + 1, sip->x);
    put16(d + 3, sip->y);
    put16(d + 5, (uint16_t)sip->th);
    put16(d + 7, (uint16_t)sip->vel_left);
    put16(d + 9, (uint16_t)sip->vel_right);
    d[11] = sip->battery;
    put16(d + 12, sip->stall_bumpers);
    put16(d + 14, (uint16_t)sip->control);
    put16(d + 16, sip->flags);
    d[18] = sip->compass;
    d[19] = sip->sonar_count;
    for (size_t i = 0; i < sip->sonar_count; i++) {
        uint8_t *r = d + HL_ARCOS_SIP_FIXED + 3 * i;
        if (sip->sonar[i].transducer >= HL_ARCOS_SONAR_MAX)
            return HL_ERR_ARG;
        r[0] = sip->sonar[i].transducer;
        put16(r + 1, sip->sonar[i].range);
    }
    memset(d + n - sip->extra_len, 0, sip->extra_len);
    return hl_arcos_frame(buf, cap, d, n, len);
}

/* ---- the SYNC handshake ------------------------------------------------------------- */

bool hl_arcos_is_sync_echo(const hl_arcos_packet_t *pkt, uint8_t sync)
{
    return pkt && sync <= HL_ARCOS_SYNC2 && pkt->len == 1 && pkt->data[0] == sync;
}

/* Length of the printable ASCII string @p s of at most @p max bytes before its NUL, or
 * -1 if it has a byte outside 0x20..0x7E or no NUL within @p max + 1 bytes. */
static long printable_len(const uint8_t *s, size_t avail, size_t max)
{
    for (size_t i = 0; i < avail && i <= max; i++) {
        if (s[i] == 0)
            return (long)i;
        if (s[i] < 0x20 || s[i] > 0x7E)
            return -1;
    }
    return -1;
}

hl_status_t hl_arcos_decode_sync2(const hl_arcos_packet_t *pkt, hl_arcos_robot_id_t *id)
{
    if (!pkt || !id)
        return HL_ERR_ARG;
    memset(id, 0, sizeof *id);
    if (pkt->len < 1 || pkt->data[0] != HL_ARCOS_SYNC2)
        return HL_ERR_PARSE;
    char *fields[3] = { id->name, id->cls, id->subclass };
    size_t pos = 1;
    for (size_t f = 0; f < 3; f++) {
        long k = printable_len(pkt->data + pos, pkt->len - pos, HL_ARCOS_ID_MAX - 1);
        if (k < 0) {
            memset(id, 0, sizeof *id);
            return HL_ERR_PARSE;
        }
        memcpy(fields[f], pkt->data + pos, (size_t)k);
        pos += (size_t)k + 1;
    }
    return HL_OK;
}

hl_status_t hl_arcos_encode_sync2(uint8_t *buf, size_t cap, const hl_arcos_robot_id_t *id,
                                  size_t *len)
{
    if (!buf || !id || !len)
        return HL_ERR_ARG;
    const char *fields[3] = { id->name, id->cls, id->subclass };
    uint8_t d[1 + 3 * HL_ARCOS_ID_MAX];
    size_t n = 0;
    d[n++] = HL_ARCOS_SYNC2;
    for (size_t f = 0; f < 3; f++) {
        long k = printable_len((const uint8_t *)fields[f], HL_ARCOS_ID_MAX, HL_ARCOS_ID_MAX - 1);
        if (k < 0)
            return HL_ERR_ARG;
        memcpy(d + n, fields[f], (size_t)k + 1);
        n += (size_t)k + 1;
    }
    return hl_arcos_frame(buf, cap, d, n, len);
}

/* ---- units and odometry ------------------------------------------------------------- */

hl_bam_t hl_arcos_angle_to_bam(const hl_arcos_conv_t *conv, int64_t units)
{
    if (!conv || conv->angle_units_per_turn == 0)
        return 0;
    int64_t turn = conv->angle_units_per_turn;
    int64_t r = units % turn;   /* reduce first: no overflow below */
    if (r < 0)
        r += turn;
    return (hl_bam_t)((r * HL_BAM_PER_TURN + turn / 2) / turn);
}

void hl_arcos_odom_init(hl_arcos_odom_t *o, uint32_t angle_units_per_turn)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->angle_units_per_turn = angle_units_per_turn;
}

/* @p d taken modulo @p period into [-period / 2, period - period / 2). */
static int32_t wrap_step(int32_t d, int32_t period)
{
    d %= period;
    if (d >= period - period / 2)
        d -= period;
    else if (d < -(period / 2))
        d += period;
    return d;
}

hl_status_t hl_arcos_odom_unwrap(hl_arcos_odom_t *o, const hl_arcos_sip_t *sip)
{
    if (!o || !sip || o->angle_units_per_turn > 65536)
        return HL_ERR_ARG;
    /* Bit 15 is not part of the position: older firmware sends 15-bit values (ARIA masks
     * them with 0x7FFF). */
    uint16_t x = sip->x & 0x7FFF, y = sip->y & 0x7FFF;
    int32_t turn = o->angle_units_per_turn ? (int32_t)o->angle_units_per_turn : 65536;
    if (!o->started) {
        o->x = x;
        o->y = y;
        o->th = sip->th;
        o->started = true;
    } else {
        o->x += wrap_step((int32_t)x - o->last_x, 0x8000);
        o->y += wrap_step((int32_t)y - o->last_y, 0x8000);
        o->th += wrap_step((int32_t)sip->th - o->last_th, turn);
    }
    o->last_x = x;
    o->last_y = y;
    o->last_th = sip->th;
    return HL_OK;
}
