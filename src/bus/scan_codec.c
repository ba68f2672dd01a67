/* scan_codec.c - SONAR and pose messages <-> core structs (see houghloc/bus.h). */
#include "houghloc/bus.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "houghloc_pose_t.h"
#include "houghloc_scan_t.h"

/*
 * Byte layout of an encoded houghloc_scan_t (lcmtypes/houghloc_scan_t.lcm), big-endian:
 *   8 hash | 8 utime | 4 seq | odometry: 8 utime 4 x 4 y 2 heading 2 velocity 1 stopped
 *   | 2 nreadings | n transducer | 2n bearing | 4n range | n valid
 * The generated decoder allocates the arrays as it goes and leaks them when a later
 * field is truncated, and it allocates whatever a negative count asks for. So the count
 * and the total length are checked here, from the bytes, before it runs; a test checks
 * this layout against the generated _encoded_size so a change to the .lcm is caught.
 */
#define SCAN_COUNT_OFFSET (8 + 8 + 4 + (8 + 4 + 4 + 2 + 2 + 1))
#define SCAN_FIXED_BYTES (SCAN_COUNT_OFFSET + 2)
#define SCAN_BYTES_PER_READING (1 + 2 + 4 + 1)

static hl_status_t reject(char *why, hl_status_t st, const char *what)
{
    if (why)
        snprintf(why, HL_BUS_WHY_LEN, "%s", what);
    return st;
}

static bool coord_ok(int32_t v)
{
    return v >= -HL_COORD_MAX_MM && v <= HL_COORD_MAX_MM;
}

hl_status_t hl_bus_decode_scan(const void *data, size_t len, hl_bus_scan_t *out, char *why)
{
    if (!data || !out)
        return reject(why, HL_ERR_ARG, "no message");
    if (len < SCAN_FIXED_BYTES || len > (size_t)INT32_MAX)
        return reject(why, HL_ERR_PARSE, "scan message truncated");
    const uint8_t *b = data;
    int16_t n = (int16_t)(uint16_t)((b[SCAN_COUNT_OFFSET] << 8) | b[SCAN_COUNT_OFFSET + 1]);
    if (n < 0 || n > HL_SCAN_MAX_READINGS)
        return reject(why, HL_ERR_RANGE, "scan nreadings outside 0..1024");
    if (len != SCAN_FIXED_BYTES + (size_t)n * SCAN_BYTES_PER_READING)
        return reject(why, HL_ERR_PARSE, "scan message length does not match nreadings");

    houghloc_scan_t m;
    if (houghloc_scan_t_decode(data, 0, (int)len, &m) < 0)
        return reject(why, HL_ERR_PARSE, "scan message does not decode (wrong type hash?)");
    hl_status_t st = HL_OK;
    const char *what = NULL;
    if (!coord_ok(m.odometry.x_mm) || !coord_ok(m.odometry.y_mm)) {
        st = HL_ERR_RANGE;
        what = "scan odometry position outside +-4194304 mm";
    }
    hl_scan_clear(&out->scan);
    for (int i = 0; st == HL_OK && i < m.nreadings; i++) {
        bool valid = m.valid[i] != 0;
        if (valid && (m.range_mm[i] < 0 || m.range_mm[i] > HL_RANGE_MAX_MM)) {
            st = HL_ERR_RANGE;
            what = "scan reading marked valid with range outside 0..32767 mm";
        } else if (m.transducer[i] < -1) {
            st = HL_ERR_RANGE;
            what = "scan transducer number below -1";
        } else {
            hl_scan_add(&out->scan, (hl_bam_t)m.bearing_bam[i], valid ? m.range_mm[i] : 0,
                        m.transducer[i], valid);
        }
    }
    if (st == HL_OK) {
        out->utime = m.utime;
        out->seq = m.seq;
        out->odometry = (hl_pose_t){ m.odometry.x_mm, m.odometry.y_mm,
                                     (hl_bam_t)m.odometry.heading_bam };
    }
    houghloc_scan_t_decode_cleanup(&m);
    return st == HL_OK ? HL_OK : reject(why, st, what);
}

hl_status_t hl_bus_decode_pose(const void *data, size_t len, hl_bus_pose_t *out, char *why)
{
    if (!data || !out)
        return reject(why, HL_ERR_ARG, "no message");
    houghloc_pose_t m;
    if (len > (size_t)INT32_MAX || houghloc_pose_t_decode(data, 0, (int)len, &m) < 0)
        return reject(why, HL_ERR_PARSE, "pose message does not decode (truncated or wrong type)");
    if ((size_t)houghloc_pose_t_encoded_size(&m) != len)
        return reject(why, HL_ERR_PARSE, "pose message has trailing bytes");
    if (!coord_ok(m.x_mm) || !coord_ok(m.y_mm))
        return reject(why, HL_ERR_RANGE, "pose position outside +-4194304 mm");
    if (m.status < HOUGHLOC_POSE_T_ACCEPTED || m.status > HOUGHLOC_POSE_T_ODOMETRY_ONLY)
        return reject(why, HL_ERR_RANGE, "pose status is not one of the defined constants");
    out->utime = m.utime;
    out->scan_seq = m.scan_seq;
    out->pose = (hl_pose_t){ m.x_mm, m.y_mm, (hl_bam_t)m.heading_bam };
    out->status = m.status;
    return HL_OK;
}

int hl_bus_encode_scan(const hl_bus_scan_t *in, void *buf, size_t cap)
{
    if (!in || !buf || hl_scan_check(&in->scan) != HL_OK || cap > (size_t)INT32_MAX)
        return -1;
    int8_t transducer[HL_SCAN_MAX_READINGS], valid[HL_SCAN_MAX_READINGS];
    int16_t bearing[HL_SCAN_MAX_READINGS];
    int32_t range[HL_SCAN_MAX_READINGS];
    for (uint32_t i = 0; i < in->scan.count; i++) {
        const hl_reading_t *r = &in->scan.readings[i];
        transducer[i] = r->transducer;
        bearing[i] = (int16_t)r->bearing;
        range[i] = r->range_mm;
        valid[i] = r->valid;
    }
    houghloc_scan_t m = {
        .utime = in->utime, .seq = in->seq,
        .odometry = { .utime = in->utime, .x_mm = in->odometry.x_mm,
                      .y_mm = in->odometry.y_mm, .heading_bam = (int16_t)in->odometry.theta,
                      .stopped = 1 },
        .nreadings = (int16_t)in->scan.count,
        .transducer = transducer, .bearing_bam = bearing, .range_mm = range, .valid = valid,
    };
    if ((size_t)houghloc_scan_t_encoded_size(&m) > cap)
        return -1;
    return houghloc_scan_t_encode(buf, 0, (int)cap, &m);
}
