/*
 * localize.h - what a Hough localization of one scan found (paper, sections 5 and 6):
 * the peak of the vote raster, and how distinct it is. A tracker's step carries one
 * (hl_slam_step_t.loc, slam.h).
 *
 * For every candidate heading and every pair <test reading, map vector> whose surface
 * normals agree within the normal gate, the pair votes for the robot position that would
 * make the reading hit the map vector's surface. Votes go into an (x, y, theta) raster,
 * blurred with a separable integer Gaussian; the highest cell is the pose, refined by
 * parabolic sub-cell interpolation. Fixed-point formats: fixed.h.
 */
#ifndef HOUGHLOC_LOCALIZE_H
#define HOUGHLOC_LOCALIZE_H

#include <stdint.h>

#include "houghloc/export.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Two measures of a peak. Before the prior: how well the scan matches the map at the
 * peak (peak) and at the best place at least peak_separation_mm away (second), in
 * blurred votes; the guard's peak-ratio test reads this (slam.h), so that a good match
 * is not taken for a bad one because the odometry drifted away from it. After the
 * prior: what the search maximised (score, second_score), which tells how distinct the
 * chosen pose is given the odometry; the confidence reads this. Without a prior the two
 * pairs are equal.
 */
typedef struct hl_loc_result {
    hl_pose_t pose;         /* interpolated peak */
    hl_pose_t cell_pose;    /* centre of the peak cell, no interpolation */
    int32_t ix, iy, it;     /* peak cell */
    uint32_t peak;          /* blurred votes x 256 in the peak cell, before the prior */
    uint32_t second;        /* the best cell >= peak_separation_mm from the peak cell in
                               x and y, same units, before the prior */
    uint32_t score;         /* the peak cell's score after the prior (the highest of the
                               raster), votes x 256; = peak without a prior */
    uint32_t second_score;  /* the best score >= peak_separation_mm from the peak cell,
                               after the prior; = second without a prior */
    uint32_t votes;         /* votes that landed in the raster */
    uint32_t pairs;         /* pairs that passed the normal gate */
} hl_loc_result_t;

/**
 * Confidence 0..1: 1 - second_score / score, how far the chosen pose stands out from the
 * best one at least peak_separation_mm away, after the prior when the query used one
 * (0 if there is no peak or @p r is NULL).
 */
HL_API double hl_loc_confidence(const hl_loc_result_t *r);

#ifdef __cplusplus
}
#endif
#endif
