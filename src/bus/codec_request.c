/*
 * codec_request.c - DESTINATION, COMMAND (operator requests) and REPLY.
 *
 * On the wire, after the 8-byte hash:
 *   destination_t  8 utime | 8 seq | 4 x | 4 y | 1 has_heading | 2 heading | 32 mac
 *   command_t      8 utime | 8 seq | 1 kind | 4 x | 4 y | 2 heading | 32 mac
 *   reply_t        8 utime | 8 seq | 1 result | message as an LCM string | 32 mac
 * The fingerprints come from the generated __houghloc_X_t_get_hash (see codec_scan.c).
 * The MAC bytes are carried, not checked: that is auth.h's job.
 */
#include "wire.h"

#include "houghloc_command_t.h"
#include "houghloc_destination_t.h"
#include "houghloc_reply_t.h"

#define REPLY_FIXED_BYTES (8 + 8 + 8 + 1)

_Static_assert(HOUGHLOC_COMMAND_T_SET_POSE == HL_BUS_COMMAND_SET_POSE &&
               HOUGHLOC_COMMAND_T_SAVE == HL_BUS_COMMAND_SAVE &&
               HOUGHLOC_COMMAND_T_RELOCALIZE == HL_BUS_COMMAND_RELOCALIZE &&
               HOUGHLOC_COMMAND_T_STOP == HL_BUS_COMMAND_STOP,
               "bus.h's HL_BUS_COMMAND_* disagree with lcmtypes/houghloc_command_t.lcm");

_Static_assert(HL_BUS_REPLY_MAX_BYTES ==
                   REPLY_FIXED_BYTES + 4 + HL_BUS_TEXT_MAX + HL_BUS_MAC_BYTES,
               "bus.h's HL_BUS_REPLY_MAX_BYTES disagrees with the layout");

static hl_status_t check_request(const char *msg, int64_t utime, int64_t seq, int32_t x,
                                 int32_t y, char *why)
{
    if (utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "utime %lld is negative", (long long)utime);
    if (seq < 1)
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "seq %lld is not positive", (long long)seq);
    if (!hl_wire_coord_ok(x) || !hl_wire_coord_ok(y))
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "position (%ld, %ld) mm outside +-%d mm",
                            (long)x, (long)y, HL_COORD_MAX_MM);
    return HL_OK;
}

/* ---- DESTINATION ------------------------------------------------------------------- */

int hl_bus_encode_destination(const hl_bus_destination_t *in, void *buf, size_t cap)
{
    if (!in ||
        check_request("destination", in->utime, in->seq, in->x_mm, in->y_mm, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_destination_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i64(&w, in->seq);
    hl_wire_put_i32(&w, in->x_mm);
    hl_wire_put_i32(&w, in->y_mm);
    hl_wire_put_bool(&w, in->has_heading);
    hl_wire_put_i16(&w, (int16_t)in->heading);
    hl_wire_put_bytes(&w, in->mac, HL_BUS_MAC_BYTES);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_destination(const void *data, size_t len,
                                      hl_bus_destination_t *out, char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out,
                                   (uint64_t)__houghloc_destination_t_get_hash(),
                                   HL_BUS_DESTINATION_BYTES, true, "destination", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->seq = hl_wire_get_i64(&r);
    out->x_mm = hl_wire_get_i32(&r);
    out->y_mm = hl_wire_get_i32(&r);
    st = hl_wire_get_bool(&r, &out->has_heading, "destination", "has_heading", why);
    if (st != HL_OK)
        return st;
    out->heading = (hl_bam_t)hl_wire_get_i16(&r);
    hl_wire_get_bytes(&r, out->mac, HL_BUS_MAC_BYTES);
    if ((st = hl_wire_end(&r, "destination", why)) != HL_OK)
        return st;
    return check_request("destination", out->utime, out->seq, out->x_mm, out->y_mm, why);
}

/* ---- COMMAND ----------------------------------------------------------------------- */

static hl_status_t check_command(const hl_bus_command_t *m, char *why)
{
    if (m->kind < HOUGHLOC_COMMAND_T_SET_POSE || m->kind > HOUGHLOC_COMMAND_T_STOP)
        return hl_wire_fail(why, HL_ERR_RANGE, "command", "kind %d outside %d..%d", m->kind,
                            HOUGHLOC_COMMAND_T_SET_POSE, HOUGHLOC_COMMAND_T_STOP);
    return check_request("command", m->utime, m->seq, m->pose.x_mm, m->pose.y_mm, why);
}

int hl_bus_encode_command(const hl_bus_command_t *in, void *buf, size_t cap)
{
    if (!in || check_command(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_command_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i64(&w, in->seq);
    hl_wire_put_i8(&w, in->kind);
    hl_wire_put_i32(&w, in->pose.x_mm);
    hl_wire_put_i32(&w, in->pose.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->pose.theta);
    hl_wire_put_bytes(&w, in->mac, HL_BUS_MAC_BYTES);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_command(const void *data, size_t len, hl_bus_command_t *out,
                                  char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out,
                                   (uint64_t)__houghloc_command_t_get_hash(),
                                   HL_BUS_COMMAND_BYTES, true, "command", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->seq = hl_wire_get_i64(&r);
    out->kind = hl_wire_get_i8(&r);
    out->pose.x_mm = hl_wire_get_i32(&r);
    out->pose.y_mm = hl_wire_get_i32(&r);
    out->pose.theta = (hl_bam_t)hl_wire_get_i16(&r);
    hl_wire_get_bytes(&r, out->mac, HL_BUS_MAC_BYTES);
    if ((st = hl_wire_end(&r, "command", why)) != HL_OK)
        return st;
    return check_command(out, why);
}

/* ---- REPLY ------------------------------------------------------------------------- */

static const char *const reply_names[] = {
    [HL_BUS_REPLY_ACCEPTED] = "ACCEPTED",
    [HL_BUS_REPLY_ARRIVED] = "ARRIVED",
    [HL_BUS_REPLY_REJECTED_FENCE] = "REJECTED_FENCE",
    [HL_BUS_REPLY_REJECTED_AUTH] = "REJECTED_AUTH",
    [HL_BUS_REPLY_REJECTED_REPLAY] = "REJECTED_REPLAY",
    [HL_BUS_REPLY_NO_ROBOT] = "NO_ROBOT",
    [HL_BUS_REPLY_FAILED] = "FAILED",
    [HL_BUS_REPLY_REJECTED_INVALID] = "REJECTED_INVALID",
};
#define REPLY_COUNT ((int)(sizeof reply_names / sizeof reply_names[0]))

_Static_assert(HOUGHLOC_REPLY_T_REJECTED_INVALID == HL_BUS_REPLY_REJECTED_INVALID &&
               HOUGHLOC_REPLY_T_ACCEPTED == HL_BUS_REPLY_ACCEPTED &&
               HOUGHLOC_REPLY_T_FAILED == HL_BUS_REPLY_FAILED,
               "bus.h's HL_BUS_REPLY_* disagree with lcmtypes/houghloc_reply_t.lcm");

const char *hl_bus_reply_name(int8_t result)
{
    return result >= 0 && result < REPLY_COUNT ? reply_names[result] : "?";
}

/* The request's seq is echoed as it came, so any value passes. */
static hl_status_t check_reply(const hl_bus_reply_t *m, char *why)
{
    if (m->utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "reply", "utime %lld is negative",
                            (long long)m->utime);
    if (m->result < 0 || m->result >= REPLY_COUNT)
        return hl_wire_fail(why, HL_ERR_RANGE, "reply", "result %d outside 0..%d", m->result,
                            REPLY_COUNT - 1);
    size_t bad;
    if (!hl_wire_text_ok(m->message, &bad))
        return hl_wire_fail(why, HL_ERR_RANGE, "reply", "message: bad byte %zu", bad);
    return HL_OK;
}

int hl_bus_encode_reply(const hl_bus_reply_t *in, void *buf, size_t cap)
{
    if (!in || check_reply(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_reply_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i64(&w, in->seq);
    hl_wire_put_i8(&w, in->result);
    hl_wire_put_text(&w, in->message);
    hl_wire_put_bytes(&w, in->mac, HL_BUS_MAC_BYTES);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_reply(const void *data, size_t len, hl_bus_reply_t *out, char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out, (uint64_t)__houghloc_reply_t_get_hash(),
                                   REPLY_FIXED_BYTES + 4 + 1 + HL_BUS_MAC_BYTES, false,
                                   "reply", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->seq = hl_wire_get_i64(&r);
    out->result = hl_wire_get_i8(&r);
    if ((st = hl_wire_get_text(&r, out->message, "reply", "message", why)) != HL_OK)
        return st;
    hl_wire_get_bytes(&r, out->mac, HL_BUS_MAC_BYTES);
    if ((st = hl_wire_end(&r, "reply", why)) != HL_OK)
        return st;
    return check_reply(out, why);
}
