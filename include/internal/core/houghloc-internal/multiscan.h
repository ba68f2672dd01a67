/*
 * multiscan.h (internal) - a sounding assembled by motion: the readings of the last
 * stretch of travel, each placed in the newest scan's robot frame by the odometry between
 * them, so that one localization sees what several views of the same walls saw (as the
 * paper's robot turned in place eight times to make one sounding of 128 readings).
 *
 * The window holds scans that are not yet in the map: a scan leaves it, to be drawn into
 * the map, once the robot has driven span_mm (or turned span_turn) past it. Matching the
 * window against a map that does not hold it keeps each view's evidence its own: were the
 * recent scans already drawn, they would vote for the odometry's prediction from where
 * they were taken, not for where the walls are.
 */
#ifndef HOUGHLOC_INTERNAL_MULTISCAN_H
#define HOUGHLOC_INTERNAL_MULTISCAN_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_MULTISCAN_MAX_SCANS 32   /* scans a window holds at most */

typedef struct hl_multiscan hl_multiscan_t;

/** A window of at most @p max_scans scans (1..HL_MULTISCAN_MAX_SCANS), spanning
 *  @p span_mm of travel or @p span_turn of turning. NULL on bad arguments or no memory. */
hl_multiscan_t *hl_multiscan_create(uint32_t max_scans, hl_mm_t span_mm, hl_bam_t span_turn);
void hl_multiscan_destroy(hl_multiscan_t *m);       /* accepts NULL */
void hl_multiscan_clear(hl_multiscan_t *m);
uint32_t hl_multiscan_count(const hl_multiscan_t *m);

/**
 * @p newest (a prepared scan whose odometry read @p odometry) and then the window's scans,
 * newest first, each reading moved into @p newest's robot frame by the odometry between
 * them, into @p out, up to HL_SCAN_MAX_READINGS readings. A moved reading keeps its
 * surface's normal (its tilt is recomputed against its new bearing) and is left out when
 * that surface faces away from the newest pose. @return the window's scans taken.
 */
uint32_t hl_multiscan_assemble(const hl_multiscan_t *m, const hl_scan_t *newest,
                               hl_pose_t odometry, hl_scan_t *out);

/**
 * The oldest scan that the drive to @p odometry has taken out of the window, if any: its
 * scan, the odometry it went with, its pose as estimated then, and whether it is to be
 * drawn; it is dropped from the window. Call until it returns false, then push.
 */
bool hl_multiscan_pop_due(hl_multiscan_t *m, hl_pose_t odometry, const hl_scan_t **scan,
                          hl_pose_t *scan_odometry, hl_pose_t *pose, bool *draw);

/** Adds @p scan (copied) with its odometry and estimated pose; @p draw: whether it goes
 *  into the map when it leaves. When the window is full the oldest is dropped first
 *  (pop_due gives it back before: call it). */
void hl_multiscan_push(hl_multiscan_t *m, const hl_scan_t *scan, hl_pose_t odometry,
                       hl_pose_t pose, bool draw);

#ifdef __cplusplus
}
#endif

#endif
