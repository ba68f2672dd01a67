/*
 * codec_pose.c - POSE and GROUND_TRUTH (houghloc.pose_t).
 *
 * On the wire, after the 8-byte hash: 8 utime | 4 scan_seq | 4 x | 4 y | 2 heading |
 * 1 status | 4 confidence (IEEE float) | 4 peak | 4 second_peak | 4 votes |
 * 4 search_score | 4 runner-up x | 4 y | 2 heading | 4 runner_up_score.
 * The fingerprint comes from the generated __houghloc_pose_t_get_hash (see
 * codec_scan.c for why that is allocation-free).
 *
 * Logs made before the global search's fields were added (POSE and GROUND_TRUTH of
 * houghloc 0.x, the sample logs of logs/, earlier imports) carry the older layout, which
 * ends at votes, under its own fingerprint: it still decodes, with the search's fields
 * zero. The encoder writes the current layout only.
 */
#include "wire.h"

#include <math.h>

#include "houghloc/slam.h"
#include "houghloc_pose_t.h"

_Static_assert(HOUGHLOC_POSE_T_ACCEPTED == HL_BUS_POSE_ACCEPTED &&
               HOUGHLOC_POSE_T_REJECTED_WILD == HL_BUS_POSE_REJECTED_WILD &&
               HOUGHLOC_POSE_T_ODOMETRY_ONLY == HL_BUS_POSE_ODOMETRY_ONLY &&
               HOUGHLOC_POSE_T_RELOCALIZED == HL_BUS_POSE_RELOCALIZED &&
               HOUGHLOC_POSE_T_LOST == HL_BUS_POSE_LOST,
               "bus.h's HL_BUS_POSE_* disagree with lcmtypes/houghloc_pose_t.lcm");

int8_t hl_bus_pose_status(hl_slam_status_t status)
{
    switch (status) {
    case HL_SLAM_ACCEPTED: return HL_BUS_POSE_ACCEPTED;
    case HL_SLAM_REJECTED_WILD: return HL_BUS_POSE_REJECTED_WILD;
    case HL_SLAM_ODOMETRY_ONLY: return HL_BUS_POSE_ODOMETRY_ONLY;
    case HL_SLAM_RELOCALIZED: return HL_BUS_POSE_RELOCALIZED;
    case HL_SLAM_LOST: return HL_BUS_POSE_LOST;
    }
    return HL_BUS_POSE_LOST;    /* not a status: the pose is not to be trusted */
}

static hl_status_t check_pose(const hl_bus_pose_t *m, char *why)
{
    if (m->utime < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "pose", "utime %lld is negative",
                            (long long)m->utime);
    if (m->scan_seq < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "pose", "scan_seq %ld is negative",
                            (long)m->scan_seq);
    if (!hl_wire_coord_ok(m->pose.x_mm) || !hl_wire_coord_ok(m->pose.y_mm))
        return hl_wire_fail(why, HL_ERR_RANGE, "pose", "position (%ld, %ld) mm outside +-%d mm",
                            (long)m->pose.x_mm, (long)m->pose.y_mm, HL_COORD_MAX_MM);
    if (m->status < HOUGHLOC_POSE_T_ACCEPTED || m->status > HOUGHLOC_POSE_T_LOST)
        return hl_wire_fail(why, HL_ERR_RANGE, "pose", "status %d outside %d..%d", m->status,
                            HOUGHLOC_POSE_T_ACCEPTED, HOUGHLOC_POSE_T_LOST);
    if (!hl_wire_coord_ok(m->runner_up.x_mm) || !hl_wire_coord_ok(m->runner_up.y_mm))
        return hl_wire_fail(why, HL_ERR_RANGE, "pose",
                            "runner-up position (%ld, %ld) mm outside +-%d mm",
                            (long)m->runner_up.x_mm, (long)m->runner_up.y_mm, HL_COORD_MAX_MM);
    /* The negated tests also catch NaN. */
    const float shares[3] = { m->confidence, m->search_score, m->runner_up_score };
    static const char *const names[3] = { "confidence", "search_score", "runner_up_score" };
    for (int i = 0; i < 3; i++)
        if (!(shares[i] >= 0.0f && shares[i] <= 1.0f))
            return hl_wire_fail(why, HL_ERR_RANGE, "pose", "%s %g outside 0..1", names[i],
                                (double)shares[i]);
    if (m->peak < 0 || m->second_peak < 0 || m->votes < 0)
        return hl_wire_fail(why, HL_ERR_RANGE, "pose",
                            "negative %s (peak %ld, second_peak %ld, votes %ld)",
                            m->peak < 0 ? "peak" : m->second_peak < 0 ? "second_peak" : "votes",
                            (long)m->peak, (long)m->second_peak, (long)m->votes);
    return HL_OK;
}

int hl_bus_encode_pose(const hl_bus_pose_t *in, void *buf, size_t cap)
{
    if (!in || check_pose(in, NULL) != HL_OK)
        return -1;
    hl_wire_out_t w = hl_wire_out(buf, cap);
    hl_wire_put_i64(&w, __houghloc_pose_t_get_hash());
    hl_wire_put_i64(&w, in->utime);
    hl_wire_put_i32(&w, in->scan_seq);
    hl_wire_put_i32(&w, in->pose.x_mm);
    hl_wire_put_i32(&w, in->pose.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->pose.theta);
    hl_wire_put_i8(&w, in->status);
    hl_wire_put_f32(&w, in->confidence);
    hl_wire_put_i32(&w, in->peak);
    hl_wire_put_i32(&w, in->second_peak);
    hl_wire_put_i32(&w, in->votes);
    hl_wire_put_f32(&w, in->search_score);
    hl_wire_put_i32(&w, in->runner_up.x_mm);
    hl_wire_put_i32(&w, in->runner_up.y_mm);
    hl_wire_put_i16(&w, (int16_t)in->runner_up.theta);
    hl_wire_put_f32(&w, in->runner_up_score);
    return hl_wire_out_len(&w);
}

/* pose_t before search_score .. runner_up_score: its fingerprint and size */
#define POSE_V1_HASH 0xd976510111d909d3ull
#define POSE_V1_BYTES (HL_BUS_POSE_BYTES - 4 - 4 - 4 - 2 - 4)

static bool is_v1(const void *data, size_t len)
{
    const uint8_t *b = data;
    uint64_t hash = 0;
    for (int i = 0; data && len == POSE_V1_BYTES && i < 8; i++)
        hash = hash << 8 | b[i];
    return data && len == POSE_V1_BYTES && hash == POSE_V1_HASH;
}

hl_status_t hl_bus_decode_pose(const void *data, size_t len, hl_bus_pose_t *out, char *why)
{
    hl_wire_in_t r;
    bool v1 = is_v1(data, len);
    hl_status_t st = hl_wire_begin(&r, data, len, out,
                                   v1 ? POSE_V1_HASH : (uint64_t)__houghloc_pose_t_get_hash(),
                                   v1 ? POSE_V1_BYTES : HL_BUS_POSE_BYTES, true, "pose", why);
    if (st != HL_OK)
        return st;
    out->utime = hl_wire_get_i64(&r);
    out->scan_seq = hl_wire_get_i32(&r);
    out->pose.x_mm = hl_wire_get_i32(&r);
    out->pose.y_mm = hl_wire_get_i32(&r);
    out->pose.theta = (hl_bam_t)hl_wire_get_i16(&r);
    out->status = hl_wire_get_i8(&r);
    out->confidence = hl_wire_get_f32(&r);
    out->peak = hl_wire_get_i32(&r);
    out->second_peak = hl_wire_get_i32(&r);
    out->votes = hl_wire_get_i32(&r);
    out->search_score = v1 ? 0.0f : hl_wire_get_f32(&r);
    out->runner_up.x_mm = v1 ? 0 : hl_wire_get_i32(&r);
    out->runner_up.y_mm = v1 ? 0 : hl_wire_get_i32(&r);
    out->runner_up.theta = v1 ? 0 : (hl_bam_t)hl_wire_get_i16(&r);
    out->runner_up_score = v1 ? 0.0f : hl_wire_get_f32(&r);
    if ((st = hl_wire_end(&r, "pose", why)) != HL_OK)
        return st;
    return check_pose(out, why);
}
