/*
 * votesum.h (private) - the vote rasters of several scans of one robot added in the frame
 * of the first (the global search from several scans, reloc.h).
 *
 * Scan k was taken at the pose `offset` in the first scan's frame (the odometry between
 * them). A robot at P in the first scan's frame was at P + R(P.theta) offset.xy, heading
 * P.theta + offset.theta, at scan k: so scan k's raster searched with its headings turned
 * by offset.theta lines up slice by slice with the first's, each slice moved by its own
 * whole number of cells. Adding them, a pose collects the votes of every scan that agrees
 * with it, and a place that explains one scan by chance rarely explains the others.
 */
#ifndef HOUGHLOC_CORE_VOTESUM_H
#define HOUGHLOC_CORE_VOTESUM_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc-internal/localize.h"

typedef struct hl_votesum {
    uint32_t *cells;        /* [it][iy][ix], the sum; capacity max_cells */
    uint32_t max_cells;
    hl_loc_surface_t geom;  /* the sum's geometry (cells points at `cells`) */
    bool started;
} hl_votesum_t;

/**
 * Starts an empty sum over @p s's grid in the first scan's frame: @p s is scan k's raster
 * at @p offset; its headings turned back by offset.theta, and its corner placed at
 * @p corner (the first scan's raster: the map's box for a whole-map search, the window
 * around the hypothesis for a local one). @return false when @p s has more cells than
 * the sum holds.
 */
bool hl_votesum_start(hl_votesum_t *v, const hl_loc_surface_t *s, hl_pose_t offset,
                      hl_mm_t corner_x, hl_mm_t corner_y);

/** Adds scan k's blurred raster @p s, taken at @p offset, each slice moved into the
 *  sum's frame (cells falling outside it are dropped). */
void hl_votesum_add(hl_votesum_t *v, const hl_loc_surface_t *s, hl_pose_t offset);

#endif
