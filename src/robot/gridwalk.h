/*
 * gridwalk.h - the cells a segment crosses on the planner's grid (private to src/robot):
 * drawing walls and beams into the costmap (costmap.c) and testing a straight leg
 * (hl_plan_segment_clear) walk the same cells.
 *
 * Coordinates are millimetres; inside the grid they become half millimetres from its
 * corner (X = 2 (x - x0) + cell_mm), so that an odd cell's borders are whole numbers too.
 */
#ifndef HOUGHLOC_ROBOT_GRIDWALK_H
#define HOUGHLOC_ROBOT_GRIDWALK_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/plan.h"

/* Every cell a segment touches, in order (Amanatides and Woo's traversal in integers).
 * Where the segment passes exactly through a cell corner it steps diagonally: the corner
 * belongs to both cells it joins, and corner.side_* name the two it only touches. */
typedef struct walk {
    int32_t col, row, end_col, end_row, step_col, step_row;
    int64_t next_c, next_r;     /* crossing times of the next column / row border, in
                                   units of 1 / (|dX| |dY|); INT64_MAX: never */
    int64_t inc_c, inc_r;
    int32_t left;               /* steps still allowed (a guard; exact arithmetic ends
                                   on the end cell) */
    bool corner;                /* the last step went through a corner */
} walk_t;

/** Starts at the cell of (ax, ay), bound for the cell of (bx, by). */
void hl_walk_init(walk_t *w, const hl_plan_grid_t *g, int64_t ax, int64_t ay, int64_t bx,
                  int64_t by);
/** Moves to the next cell; false when the end cell was reached. */
bool hl_walk_next(walk_t *w);
/** Whether (col, row) is a cell of @p g. */
bool hl_walk_in_grid(const hl_plan_grid_t *g, int32_t col, int32_t row);
/** Floor division (rounds towards minus infinity), @p b > 0. */
int64_t hl_walk_floor_div(int64_t a, int64_t b);

#endif
