/*
 * codec_status.c - STATUS (houghloc.status_t).
 *
 * On the wire, after the 8-byte hash: 8 utime | 1 state | 8 destination_seq | 8 x 9
 * counters (scans .. rejected_requests) | 4 map_vectors | 8 map_version | 8 saves |
 * 4 x | 4 y | 2 heading | 4 compute_median_us |
 * 4 compute_p99_us | 4 compute_samples | last_error as an LCM string. The fingerprint
 * comes from the generated __houghloc_status_t_get_hash (see codec_scan.c).
 */
#include "wire.h"

#include "houghloc_status_t.h"

#define STATUS_NCOUNTERS 11   /* the 64-bit counters, in wire order (STATUS_COUNTERS) */
#define STATUS_FIXED_BYTES (8 + 8 + 1 + 8 + 8 * STATUS_NCOUNTERS + 4 + 4 + 4 + 2 + 4 * 3)
#define STATUS_MIN_BYTES (STATUS_FIXED_BYTES + 4 + 1)

_Static_assert(HL_BUS_STATUS_MAX_BYTES == STATUS_FIXED_BYTES + 4 + HL_BUS_TEXT_MAX,
               "bus.h's HL_BUS_STATUS_MAX_BYTES disagrees with the layout");
_Static_assert(HOUGHLOC_STATUS_T_STARTING == HL_BUS_STATE_STARTING &&
               HOUGHLOC_STATUS_T_SOUNDING == HL_BUS_STATE_SOUNDING &&
               HOUGHLOC_STATUS_T_LOCALIZING == HL_BUS_STATE_LOCALIZING &&
               HOUGHLOC_STATUS_T_MOVING == HL_BUS_STATE_MOVING &&
               HOUGHLOC_STATUS_T_IDLE == HL_BUS_STATE_IDLE &&
               HOUGHLOC_STATUS_T_FAULT == HL_BUS_STATE_FAULT &&
               HOUGHLOC_STATUS_T_STOPPING == HL_BUS_STATE_STOPPING &&
               HOUGHLOC_STATUS_T_LOST == HL_BUS_STATE_LOST,
               "bus.h's HL_BUS_STATE_* disagree with lcmtypes/houghloc_status_t.lcm");

/* The counters in wire order, with their names for the reason text. map_vectors, a
 * size of 32 bits, sits on the wire between rejected_requests and map_version
 * (STATUS_SIZE_AT: the counters before it). */
#define STATUS_COUNTERS(m)                                                                 \
    { &(m)->scans, &(m)->accepted, &(m)->rejected_wild, &(m)->odometry_only,               \
      &(m)->relocalized, &(m)->lost, &(m)->bad_packets, &(m)->bad_messages,                \
      &(m)->rejected_requests, &(m)->map_version, &(m)->saves }
#define STATUS_SIZE_AT 9
static const char *const counter_names[STATUS_NCOUNTERS] = {
    "scans", "accepted", "rejected_wild", "odometry_only", "relocalized", "lost",
    "bad_packets", "bad_messages", "rejected_requests", "map_version", "saves",
};

static hl_status_t check_status(const hl_bus_status_t *m, char *why)
{
    if (m->utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "status", "utime %lld is negative",
                            (long long)m->utime);
    if (m->state < HOUGHLOC_STATUS_T_STARTING || m->state > HOUGHLOC_STATUS_T_LOST)
        return hl_wire_fail(why, HL_ERR_RANGE, "status", "state %d outside %d..%d", m->state,
                            HOUGHLOC_STATUS_T_STARTING, HOUGHLOC_STATUS_T_LOST);
    if (m->destination_seq != -1 && m->destination_seq < 1)
        return hl_wire_fail(why, HL_ERR_RANGE, "status",
                            "destination_seq %lld is neither -1 nor positive",
                            (long long)m->destination_seq);
    const int64_t *counters[STATUS_NCOUNTERS] = STATUS_COUNTERS(m);
    for (int i = 0; i < STATUS_NCOUNTERS; i++)
        if (*counters[i] < 0)
            return hl_wire_fail(why, HL_ERR_RANGE, "status", "%s %lld is negative",
                                counter_names[i], (long long)*counters[i]);
    if (m->map_vectors < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "status", "map_vectors %ld is negative",
                            (long)m->map_vectors);
    if (m->map_vectors > (int32_t)HL_MAP_MAX_CAPACITY)
        return hl_wire_fail(why, HL_ERR_RANGE, "status", "map_vectors %ld above %lu",
                            (long)m->map_vectors, (unsigned long)HL_MAP_MAX_CAPACITY);
    if (!hl_wire_coord_ok(m->pose.x_mm) || !hl_wire_coord_ok(m->pose.y_mm))
        return hl_wire_fail(why, HL_ERR_RANGE, "status",
                            "position (%ld, %ld) mm outside +-%d mm", (long)m->pose.x_mm,
                            (long)m->pose.y_mm, HL_COORD_MAX_MM);
    if (m->compute_median_us < 0 || m->compute_p99_us < 0 || m->compute_samples < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "status",
                            "negative compute time (median %ld, p99 %ld, samples %ld)",
                            (long)m->compute_median_us, (long)m->compute_p99_us,
                            (long)m->compute_samples);
    size_t bad;
    if (!hl_wire_text_ok(m->last_error, &bad))
        return hl_wire_fail(why, HL_ERR_RANGE, "status", "last_error: bad byte %zu", bad);
    return HL_OK;
}

int hl_bus_encode_status(const hl_bus_status_t *in, void *buf, size_t cap)
{
    if (!in || check_status(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_status_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i8(&w, in->state);
    hl_wire_put_i64(&w, in->destination_seq);
    const int64_t *counters[STATUS_NCOUNTERS] = STATUS_COUNTERS(in);
    for (int i = 0; i < STATUS_NCOUNTERS; i++) {
        if (i == STATUS_SIZE_AT)
            hl_wire_put_i32(&w, in->map_vectors);
        hl_wire_put_i64(&w, *counters[i]);
    }
    hl_wire_put_i32(&w, in->pose.x_mm);
    hl_wire_put_i32(&w, in->pose.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->pose.theta);
    hl_wire_put_i32(&w, in->compute_median_us);
    hl_wire_put_i32(&w, in->compute_p99_us);
    hl_wire_put_i32(&w, in->compute_samples);
    hl_wire_put_text(&w, in->last_error);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_status(const void *data, size_t len, hl_bus_status_t *out,
                                 char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out,
                                   (uint64_t)__houghloc_status_t_get_hash(),
                                   STATUS_MIN_BYTES, false, "status", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->state = hl_wire_get_i8(&r);
    out->destination_seq = hl_wire_get_i64(&r);
    int64_t *counters[STATUS_NCOUNTERS] = STATUS_COUNTERS(out);
    for (int i = 0; i < STATUS_NCOUNTERS; i++) {
        if (i == STATUS_SIZE_AT)
            out->map_vectors = hl_wire_get_i32(&r);
        *counters[i] = hl_wire_get_i64(&r);
    }
    out->pose.x_mm = hl_wire_get_i32(&r);
    out->pose.y_mm = hl_wire_get_i32(&r);
    out->pose.theta = (hl_bam_t)hl_wire_get_i16(&r);
    out->compute_median_us = hl_wire_get_i32(&r);
    out->compute_p99_us = hl_wire_get_i32(&r);
    out->compute_samples = hl_wire_get_i32(&r);
    if ((st = hl_wire_get_text(&r, out->last_error, "status", "last_error", why)) != HL_OK)
        return st;
    if ((st = hl_wire_end(&r, "status", why)) != HL_OK)
        return st;
    return check_status(out, why);
}
