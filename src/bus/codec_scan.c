/*
 * codec_scan.c - SONAR (houghloc.scan_t) and ODOMETRY (houghloc.odometry_t).
 *
 * scan_t on the wire (lcmtypes/houghloc_scan_t.lcm), after the 8-byte hash:
 *   8 utime | 4 seq | odometry_t without a hash: 8 utime 4 x 4 y 2 heading 2 velocity
 *   1 stopped | 2 nreadings | n transducer | 2n bearing | 4n range | n valid
 *
 * hl_bus_scan_t carries only the embedded odometry's pose: the encoder writes the scan's
 * utime, velocity 0 and stopped true around it (the base stands still while it sounds),
 * and the decoder checks those three fields (utime >= 0, stopped 0 or 1) but drops them.
 *
 * The fingerprints come from lcm-gen's own __houghloc_X_t_get_hash(): it is computed on
 * the first call from a list on the stack (no allocation) and cached in a static, so a
 * change to a .lcm file changes what these codecs expect with no edit here (a changed
 * layout shows in the tests, which compare bytes with the generated code). The cache is
 * a plain static: a threaded program makes one codec call before it starts threads
 * (houghlocd is single-threaded). The codecs never call the generated _decode, which
 * mallocs its arrays.
 */
#include "wire.h"

#include "houghloc_odometry_t.h"
#include "houghloc_scan_t.h"

#define SCAN_FIXED_BYTES (8 + 8 + 4 + 21 + 2)
#define SCAN_BYTES_PER_READING (1 + 2 + 4 + 1)

_Static_assert(HL_BUS_SCAN_MAX_BYTES ==
                   SCAN_FIXED_BYTES + HL_SCAN_MAX_READINGS * SCAN_BYTES_PER_READING,
               "bus.h's HL_BUS_SCAN_MAX_BYTES disagrees with the layout");
_Static_assert(HL_BUS_ODOMETRY_BYTES == 8 + 21, "bus.h's HL_BUS_ODOMETRY_BYTES");

static hl_status_t check_pose_xy(hl_pose_t p, const char *msg, const char *field, char *why)
{
    if (!hl_wire_coord_ok(p.x_mm) || !hl_wire_coord_ok(p.y_mm))
        return hl_wire_fail(why, HL_ERR_RANGE, msg, "%s (%ld, %ld) mm outside +-%d mm", field,
                            (long)p.x_mm, (long)p.y_mm, HL_COORD_MAX_MM);
    return HL_OK;
}

/* Every check a scan passes, on the way out and on the way in. */
static hl_status_t check_scan(const hl_bus_scan_t *m, char *why)
{
    if (m->utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "scan", "utime %lld is negative",
                            (long long)m->utime);
    if (m->seq < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "scan", "seq %ld is negative", (long)m->seq);
    hl_status_t st = check_pose_xy(m->odometry, "scan", "odometry position", why);
    if (st != HL_OK)
        return st;
    if (m->scan.count > HL_SCAN_MAX_READINGS)
        return hl_wire_fail(why, HL_ERR_RANGE, "scan", "nreadings %lu outside 0..%d",
                            (unsigned long)m->scan.count, HL_SCAN_MAX_READINGS);
    for (uint32_t i = 0; i < m->scan.count; i++) {
        const hl_reading_t *r = &m->scan.readings[i];
        if (r->range_mm < 0 || r->range_mm > HL_RANGE_MAX_MM)
            return hl_wire_fail(why, HL_ERR_RANGE, "scan", "range_mm[%lu] %ld outside 0..%d",
                                (unsigned long)i, (long)r->range_mm, HL_RANGE_MAX_MM);
        if (r->transducer < -1)
            return hl_wire_fail(why, HL_ERR_RANGE, "scan", "transducer[%lu] %d below -1",
                                (unsigned long)i, r->transducer);
    }
    return HL_OK;
}

int hl_bus_encode_scan(const hl_bus_scan_t *in, void *buf, size_t cap)
{
    if (!in || check_scan(in, NULL) != HL_OK)
        return -1;
    uint32_t n = in->scan.count;
    if (cap < SCAN_FIXED_BYTES + (size_t)n * SCAN_BYTES_PER_READING)
        return -1;      /* before writing: the cursor would catch it, but only at the end */
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_scan_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i32(&w, in->seq);
    hl_wire_put_i64(&w, in->utime);                     /* odometry.utime */
    hl_wire_put_i32(&w, in->odometry.x_mm);
    hl_wire_put_i32(&w, in->odometry.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->odometry.theta);
    hl_wire_put_i16(&w, 0);                             /* odometry.velocity_mm_s */
    hl_wire_put_bool(&w, true);                         /* odometry.stopped */
    hl_wire_put_i16(&w, (int16_t)n);
    const hl_reading_t *r = in->scan.readings;
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i8(&w, r[i].transducer);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i16(&w, (int16_t)r[i].bearing);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_i32(&w, r[i].range_mm);
    for (uint32_t i = 0; i < n; i++)
        hl_wire_put_bool(&w, r[i].valid);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_scan(const void *data, size_t len, hl_bus_scan_t *out, char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out, (uint64_t)__houghloc_scan_t_get_hash(),
                                   SCAN_FIXED_BYTES, false, "scan", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->seq = hl_wire_get_i32(&r);
    int64_t odo_utime = hl_wire_get_i64(&r);
    out->odometry.x_mm = hl_wire_get_i32(&r);
    out->odometry.y_mm = hl_wire_get_i32(&r);
    out->odometry.theta = (hl_bam_t)hl_wire_get_i16(&r);
    (void)hl_wire_get_i16(&r);                          /* velocity: not kept */
    bool stopped;
    if ((st = hl_wire_get_bool(&r, &stopped, "scan", "odometry.stopped", why)) != HL_OK)
        return st;
    if (odo_utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "scan", "odometry.utime %lld is negative",
                            (long long)odo_utime);
    int16_t n = hl_wire_get_i16(&r);
    if (n < 0 || n > HL_SCAN_MAX_READINGS)
        return hl_wire_fail(why, HL_ERR_RANGE, "scan", "nreadings %d outside 0..%d", n,
                            HL_SCAN_MAX_READINGS);
    size_t want = SCAN_FIXED_BYTES + (size_t)n * SCAN_BYTES_PER_READING;
    if (len != want)
        return hl_wire_fail(why, HL_ERR_PARSE, "scan", "%zu bytes, but nreadings %d needs %zu",
                            len, n, want);
    out->scan.count = (uint32_t)n;
    hl_reading_t *rd = out->scan.readings;
    for (int i = 0; i < n; i++) {
        rd[i].transducer = hl_wire_get_i8(&r);
        rd[i].tilt = 0;     /* not on the wire: the core estimates it (normals.h) */
    }
    for (int i = 0; i < n; i++)
        rd[i].bearing = (hl_bam_t)hl_wire_get_i16(&r);
    for (int i = 0; i < n; i++)
        rd[i].range_mm = hl_wire_get_i32(&r);
    for (int i = 0; i < n; i++) {
        uint8_t b = hl_wire_get_u8(&r);
        if (b > 1)
            return hl_wire_fail(why, HL_ERR_RANGE, "scan", "valid[%d] byte %u is not 0 or 1",
                                i, b);
        rd[i].valid = b == 1;
    }
    if ((st = hl_wire_end(&r, "scan", why)) != HL_OK)
        return st;
    return check_scan(out, why);
}

/* ---- ODOMETRY ---------------------------------------------------------------------- */

static hl_status_t check_odometry(const hl_bus_odometry_t *m, char *why)
{
    if (m->utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "odometry", "utime %lld is negative",
                            (long long)m->utime);
    return check_pose_xy(m->pose, "odometry", "position", why);
}

int hl_bus_encode_odometry(const hl_bus_odometry_t *in, void *buf, size_t cap)
{
    if (!in || check_odometry(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_odometry_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i32(&w, in->pose.x_mm);
    hl_wire_put_i32(&w, in->pose.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->pose.theta);
    hl_wire_put_i16(&w, in->velocity_mm_s);
    hl_wire_put_bool(&w, in->stopped);
    return hl_wire_out_len(&w);
}

hl_status_t hl_bus_decode_odometry(const void *data, size_t len, hl_bus_odometry_t *out,
                                   char *why)
{
    hl_wire_in_t r;
    hl_status_t st = hl_wire_begin(&r, data, len, out,
                                   (uint64_t)__houghloc_odometry_t_get_hash(),
                                   HL_BUS_ODOMETRY_BYTES, true, "odometry", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->pose.x_mm = hl_wire_get_i32(&r);
    out->pose.y_mm = hl_wire_get_i32(&r);
    out->pose.theta = (hl_bam_t)hl_wire_get_i16(&r);
    out->velocity_mm_s = hl_wire_get_i16(&r);
    if ((st = hl_wire_get_bool(&r, &out->stopped, "odometry", "stopped", why)) != HL_OK)
        return st;
    if ((st = hl_wire_end(&r, "odometry", why)) != HL_OK)
        return st;
    return check_odometry(out, why);
}
