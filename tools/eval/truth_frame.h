/*
 * truth_frame.h - the simulator's GROUND_TRUTH moved into houghlocd's map frame, for the
 * tools that show or score the truth beside the estimate (hl-eval, houghloc-map,
 * houghloc-console).
 *
 * The simulator publishes the true pose in its world's frame; the daemon's estimate is
 * in the map frame, anchored at the daemon's start pose ([start], the origin unless
 * configured), which is where the robot stands when its odometry begins. The first true
 * pose of a run is that same standing robot, so every true pose T maps to
 *     start (+) (first^-1 (+) T)
 * (a rigid motion: distances along the true path are kept). Pure: no I/O.
 */
#ifndef HOUGHLOC_TOOLS_TRUTH_FRAME_H
#define HOUGHLOC_TOOLS_TRUTH_FRAME_H

#include <stdbool.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_TRUTH_FRAME_WHY_LEN 160

typedef struct hl_truth_frame {
    hl_pose_t start;        /* the daemon's start pose, map frame */
    hl_pose_t first;        /* the first true pose, world frame (once anchored) */
    bool anchored;
} hl_truth_frame_t;

/** A frame not yet anchored, for a daemon that starts at @p start (map frame). */
void hl_truth_frame_init(hl_truth_frame_t *f, hl_pose_t start);

/** Anchors @p f at @p first (the run's first true pose) unless it already is. */
void hl_truth_frame_anchor(hl_truth_frame_t *f, hl_pose_t first);

/**
 * @p truth (world frame) in the map frame; the first call anchors the frame at @p truth.
 * Positions are rounded once to the millimetre. @return false (and @p out untouched)
 * when the result lies beyond +-HL_COORD_MAX_MM.
 */
bool hl_truth_frame_map(hl_truth_frame_t *f, hl_pose_t truth, hl_pose_t *out);

/**
 * Parses "X,Y,DEG" (metres, metres, degrees; houghloc-sim's --start syntax) into
 * @p out. @return false after writing a one-line reason into @p why
 * (HL_TRUTH_FRAME_WHY_LEN bytes) naming the text.
 */
bool hl_truth_frame_parse_pose(const char *s, hl_pose_t *out, char *why);

#ifdef __cplusplus
}
#endif
#endif
