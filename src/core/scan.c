/* scan.c - scans and pose algebra. */
#include "houghloc/scan.h"

#include <stddef.h>

void hl_scan_clear(hl_scan_t *scan)
{
    scan->count = 0;
}

hl_status_t hl_scan_add(hl_scan_t *scan, hl_bam_t bearing, int32_t range_mm,
                        int8_t transducer, bool valid)
{
    if (!scan)
        return HL_ERR_ARG;
    if (scan->count >= HL_SCAN_MAX_READINGS)
        return HL_ERR_CAPACITY;
    bool in_range = range_mm >= 0 && range_mm <= HL_RANGE_MAX_MM;
    hl_reading_t *r = &scan->readings[scan->count++];
    r->bearing = bearing;
    r->range_mm = in_range ? range_mm : 0;
    r->transducer = transducer;
    r->valid = valid && in_range;
    r->tilt = 0;
    return valid && !in_range ? HL_ERR_RANGE : HL_OK;
}

uint32_t hl_scan_valid_count(const hl_scan_t *scan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < scan->count && i < HL_SCAN_MAX_READINGS; i++)
        n += scan->readings[i].valid;
    return n;
}

hl_status_t hl_scan_check(const hl_scan_t *scan)
{
    if (!scan)
        return HL_ERR_ARG;
    if (scan->count > HL_SCAN_MAX_READINGS)
        return HL_ERR_RANGE;
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *r = &scan->readings[i];
        if (r->valid && (r->range_mm < 0 || r->range_mm > HL_RANGE_MAX_MM ||
                         r->tilt <= -HL_BAM_QUARTER_TURN || r->tilt >= HL_BAM_QUARTER_TURN))
            return HL_ERR_RANGE;
    }
    return HL_OK;
}

/* Rotates (x, y) by angle a; int64 because world coordinates reach 2^22 mm and the
 * Q14 product would overflow int32 beyond the 32 m range of hl_polar_to_xy. */
static void rotate(int32_t x, int32_t y, hl_bam_t a, int32_t *ox, int32_t *oy)
{
    int64_t c = hl_cos(a), s = hl_sin(a);
    int64_t rx = (int64_t)x * c - (int64_t)y * s;
    int64_t ry = (int64_t)x * s + (int64_t)y * c;
    int64_t half = 1 << (HL_TRIG_SHIFT - 1);
    *ox = (int32_t)(rx >= 0 ? (rx + half) >> HL_TRIG_SHIFT : -((-rx + half) >> HL_TRIG_SHIFT));
    *oy = (int32_t)(ry >= 0 ? (ry + half) >> HL_TRIG_SHIFT : -((-ry + half) >> HL_TRIG_SHIFT));
}

hl_pose_t hl_pose_compose(hl_pose_t base, hl_pose_t rel)
{
    int32_t dx, dy;
    rotate(rel.x_mm, rel.y_mm, base.theta, &dx, &dy);
    hl_pose_t out = { base.x_mm + dx, base.y_mm + dy, (hl_bam_t)(base.theta + rel.theta) };
    return out;
}

hl_pose_t hl_pose_between(hl_pose_t from, hl_pose_t to)
{
    int32_t dx, dy;
    rotate(to.x_mm - from.x_mm, to.y_mm - from.y_mm, (hl_bam_t)(0u - from.theta), &dx, &dy);
    hl_pose_t out = { dx, dy, (hl_bam_t)(to.theta - from.theta) };
    return out;
}

bool hl_pose_in_range(hl_pose_t p)
{
    return p.x_mm >= -HL_COORD_MAX_MM && p.x_mm <= HL_COORD_MAX_MM &&
           p.y_mm >= -HL_COORD_MAX_MM && p.y_mm <= HL_COORD_MAX_MM;
}

bool hl_pose_predict(hl_pose_t pose, hl_pose_t odom_then, hl_pose_t odom_now, hl_pose_t *out)
{
    hl_pose_t moved = hl_pose_compose(pose, hl_pose_between(odom_then, odom_now));
    bool in_range = hl_pose_in_range(moved);
    *out = in_range ? moved : pose;
    return in_range;
}
