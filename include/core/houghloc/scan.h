/*
 * scan.h - one sonar sounding in the robot frame, and poses.
 *
 * A scan is a fixed-size value (no allocation): up to HL_SCAN_MAX_READINGS readings,
 * each a bearing in the robot frame and a calibrated range. Invalid readings (cable
 * echoes, the no-echo sentinel) stay in the scan, flagged, so that a scan keeps the
 * shape of the transducer ring.
 */
#ifndef HOUGHLOC_SCAN_H
#define HOUGHLOC_SCAN_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/export.h"
#include "houghloc/fixed.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_SCAN_MAX_READINGS 1024

typedef struct hl_pose {
    hl_mm_t x_mm;       /* |x| <= HL_COORD_MAX_MM */
    hl_mm_t y_mm;
    hl_bam_t theta;     /* heading */
} hl_pose_t;

typedef struct hl_reading {
    int32_t range_mm;   /* 0..HL_RANGE_MAX_MM when valid */
    hl_bam_t bearing;   /* robot frame */
    int8_t transducer;  /* 0..127, -1 when not from a ring transducer */
    bool valid;
    int16_t tilt;       /* the surface normal's turn from the beam's reverse, in BAM,
                           within +-a quarter turn: 0 (a surface square to the beam, as
                           a sonar hears it) unless hl_normals_fit estimated it */
} hl_reading_t;

typedef struct hl_scan {
    uint32_t count;     /* 0..HL_SCAN_MAX_READINGS */
    hl_reading_t readings[HL_SCAN_MAX_READINGS];
} hl_scan_t;

/** Empties @p scan. */
HL_API void hl_scan_clear(hl_scan_t *scan);

/**
 * Appends one reading. A range outside 0..HL_RANGE_MAX_MM cannot be held: the reading
 * is still appended (so that the scan keeps the ring's shape), as an invalid one with
 * range 0, and the call says so. A caller counts and reports these: a laser return
 * beyond 32.767 m is lost this way.
 * @return HL_OK; HL_ERR_RANGE when @p valid was asked for a range outside
 *         0..HL_RANGE_MAX_MM (appended as invalid); HL_ERR_CAPACITY when the scan is
 *         full (nothing appended); HL_ERR_ARG on NULL.
 */
HL_API hl_status_t hl_scan_add(hl_scan_t *scan, hl_bam_t bearing, int32_t range_mm,
                               int8_t transducer, bool valid);

/** The world direction of @p r's surface normal (towards the sensor) seen from a robot
 *  heading @p heading: the beam's reverse turned by the reading's tilt. */
static inline hl_bam_t hl_reading_normal(const hl_reading_t *r, hl_bam_t heading)
{
    return (hl_bam_t)(heading + r->bearing + (int32_t)HL_BAM_HALF_TURN + r->tilt);
}

/** Number of valid readings. */
HL_API uint32_t hl_scan_valid_count(const hl_scan_t *scan);

/** Checks count and every valid reading's range and tilt. @return HL_OK or HL_ERR_RANGE. */
HL_API hl_status_t hl_scan_check(const hl_scan_t *scan);

/** Composes poses: the pose @p rel, given in the frame of @p base, in the world frame. */
HL_API hl_pose_t hl_pose_compose(hl_pose_t base, hl_pose_t rel);
/** The pose of @p to in the frame of @p from (inverse of hl_pose_compose). */
HL_API hl_pose_t hl_pose_between(hl_pose_t from, hl_pose_t to);
/** Checks |x|, |y| <= HL_COORD_MAX_MM. */
HL_API bool hl_pose_in_range(hl_pose_t p);
/**
 * The prediction (dead reckoning): @p pose, where the odometry read @p odom_then, moved
 * by the odometry's motion since, to @p odom_now. Every prediction of the tracker and the
 * daemon is this one function.
 * @return true with the moved pose in @p out; false, with @p pose in @p out, when the
 *         moved pose is out of range.
 */
HL_API bool hl_pose_predict(hl_pose_t pose, hl_pose_t odom_then, hl_pose_t odom_now,
                            hl_pose_t *out);

#ifdef __cplusplus
}
#endif
#endif
