/*
 * valid_scan.h (private) - the core's stages for a scan already checked: each is its
 * public function (localize.h, refine.h, echo.h, normals.h, reloc.h) without the
 * hl_scan_check of its input, which the caller has made. The tracker checks a scan once,
 * in hl_slam_update, and runs every stage of its cycle through these; the global search
 * checks its scans once and localizes its hypotheses through hl_loc_run_valid. Every
 * other check (arguments, poses, capacities) stays.
 */
#ifndef HOUGHLOC_CORE_VALID_SCAN_H
#define HOUGHLOC_CORE_VALID_SCAN_H

#include "houghloc-internal/echo.h"
#include "houghloc-internal/localize.h"
#include "houghloc-internal/normals.h"
#include "houghloc-internal/refine.h"
#include "houghloc-internal/reloc.h"

hl_status_t hl_loc_run_valid(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                             const hl_scan_t *scan, const hl_loc_query_t *query,
                             hl_loc_result_t *result);

hl_status_t hl_refine_run_valid(hl_refiner_t *r, const hl_vector_t *map, uint32_t n,
                                const hl_scan_t *scan, hl_pose_t start, bool heading,
                                hl_pose_t *out);

hl_status_t hl_echo_correct_valid(const hl_echo_params_t *p, const hl_scan_t *in,
                                  hl_scan_t *out);

hl_status_t hl_normals_fit_valid(const hl_normals_params_t *p, const hl_scan_t *in,
                                 hl_scan_t *out);

hl_status_t hl_reloc_run_scans_valid(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                                     const hl_scan_t *const *scans, const hl_pose_t *odometry,
                                     uint32_t count, hl_reloc_result_t *result);

void hl_reloc_judge_poses_valid(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                                const hl_scan_t *scan, const hl_pose_t *poses, uint32_t count,
                                uint32_t *scores);

#endif
