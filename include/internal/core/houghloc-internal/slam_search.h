/*
 * slam_search.h - the tracker's searches, one at a time, without changing anything: the
 * local search of tracking, the global search of the recovery and its judge. The
 * tracker's recovery (src/core/slam_lost.c) is built on them; the laboratory's research
 * tools (make kidnap, the tour study) and the tests call them directly. Not API: a
 * program drives the tracker through hl_slam_update (houghloc/slam.h).
 */
#ifndef HOUGHLOC_INTERNAL_SLAM_SEARCH_H
#define HOUGHLOC_INTERNAL_SLAM_SEARCH_H

#include "houghloc/slam.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Localizes @p scan against the current map as tracking would, with @p predicted as the
 * prediction, and changes nothing: no map update, no state.
 * @param[out] loc   the Hough result;  @param[out] pose  the pose (refined if asked).
 * @return as hl_loc_run.
 */
hl_status_t hl_slam_localize(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t predicted,
                             hl_loc_result_t *loc, hl_pose_t *pose);

/**
 * Where is the robot, heading unknown (the kidnapped robot, reloc.h): the scan at its
 * echo bearings when the params ask, searched over the whole map, the answer refined
 * when the params ask. Changes nothing.
 * @return as hl_reloc_run.
 */
hl_status_t hl_slam_relocalize(hl_slam_t *s, const hl_scan_t *scan, hl_reloc_result_t *out);

/**
 * hl_slam_relocalize of @p scans[0] with the robot's other scans @p scans[1 .. count - 1]
 * taken at the odometry poses @p odometry[1 ..] (@p odometry[0] the first's):
 * hl_reloc_run_scans. count 1 is hl_slam_relocalize (@p odometry may then be NULL).
 */
hl_status_t hl_slam_relocalize_scans(hl_slam_t *s, const hl_scan_t *const *scans,
                                     const hl_pose_t *odometry, uint32_t count,
                                     hl_reloc_result_t *out);

/** hl_reloc_judge of @p scan (at its echo bearings when the params ask) at @p pose against
 *  the current map. */
uint32_t hl_slam_judge(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t pose);
/** hl_slam_judge at each of @p poses[0 .. count - 1] into @p scores, the scan prepared
 *  and the map hashed once (hl_reloc_judge_poses). */
void hl_slam_judge_poses(hl_slam_t *s, const hl_scan_t *scan, const hl_pose_t *poses,
                         uint32_t count, uint32_t *scores);

#ifdef __cplusplus
}
#endif
#endif
