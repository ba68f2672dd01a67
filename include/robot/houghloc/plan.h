/*
 * plan.h - a path planner on the robot's own map: the tangent vectors drawn into an
 * occupancy grid, inflated by the robot's radius, searched with A*, and the cell path
 * pulled into a few straight legs.
 *
 * The grid (hl_costmap_*, costmap.c) covers the bounding box of the map's wall segments,
 * the extra obstacles, the start and the goal, plus a margin of radius + clearance + one
 * cell. Cell (i, j) is centred at (x0 + i * cell_mm, y0 + j * cell_mm) and covers
 * +-cell_mm / 2 around it; the centres lie on multiples of cell_mm, so the cells of two
 * builds line up. Each cell holds one byte:
 *   0                      free, far from every obstacle cell;
 *   1..HL_PLAN_COST_MAX    the clearance band: a cost that falls linearly from
 *                          HL_PLAN_COST_MAX at radius_mm to 1 near radius + clearance;
 *   HL_PLAN_CELL_LETHAL    some point of the cell is within radius_mm of some point of an
 *                          obstacle cell (the body would touch it);
 *   HL_PLAN_CELL_FENCE     its centre is outside the allowed area (hl_planner_set_allowed)
 *                          or outside +-HL_COORD_MAX_MM; not inflated;
 *   HL_PLAN_CELL_OBSTACLE  a wall segment or an extra obstacle passes through it.
 * Unknown space is free: the map knows only surfaces it has heard.
 *
 * Sonar hears phantoms: an echo is placed on its beam's axis, but came from somewhere
 * across the lobe, and side lobes and multiple reflections answer too. So each wall cell
 * needs more evidence than against it: a cell is an obstacle when more wall segments pass
 * through it than beams crossed it on their way to a farther echo (each vector's beam runs
 * from where its sensor stood, range_mm along its normal, to CARVE_SHORT_MM before its
 * surface point). A surface heard from several places stays; an echo placed where other
 * beams went through is dropped. Vectors sensed farther than wall_range_mm carve but draw
 * no wall.
 *
 * The lethal test is between whole cells, so the promise is exact, not up to a cell: every
 * point of every leg of a path lies at least radius_mm from every wall segment and extra
 * obstacle, except inside the start's lethal region (below). The price: a doorway must be
 * one to two cells wider than 2 * radius_mm, as it falls on the grid (at the defaults,
 * 555 to 600 mm).
 *
 * Wall cells within radius_mm of the start are dropped before inflating: the robot stands
 * there, so they are echoes misplaced by localization error. The extra obstacles are kept
 * however near: each is a reading that has just stopped the robot, and a robot that
 * coasted up to it must back out round it, not through it. A start still inside
 * the lethal zone (a robot stopped next to a wall) plans out through its own lethal
 * region: the lethal and fence cells connected to the start cell whose centres lie within
 * radius_mm + cell_mm of the start, at a high cost per step, never through an obstacle.
 *
 * All arithmetic is integer and nothing but the inputs steers the search, so the same
 * inputs give the same path. Pure: no I/O, no global state, and nothing is allocated after
 * hl_planner_create (about 25 bytes per cell of max_cells: 25 MB at the default).
 */
#ifndef HOUGHLOC_PLAN_H
#define HOUGHLOC_PLAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/fixed.h"
#include "houghloc/map.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_plan_params {
    int32_t cell_mm;        /* grid cell, 20..500 (default 50) */
    int32_t radius_mm;      /* robot body radius: its centre never closer than this to an
                               obstacle cell (the lethal zone); 50..2000 (default 250) */
    int32_t clearance_mm;   /* beyond the radius, a cost that falls to 0 over this
                               distance, so that paths keep to the middle of passages;
                               0..3000 (default 300) */
    hl_bam_t half_beam;     /* a vector is drawn as a wall segment along its tangent
                               (perpendicular to its normal), half-length
                               range_mm * tan(half_beam), 0..45 degrees (default 7.5) ... */
    int32_t max_half_mm;    /* ... capped at this, 0..5000 (default 150) */
    int32_t wall_range_mm;  /* a vector sensed farther than this is drawn as no wall: a
                               sonar echo lies somewhere across its lobe, +-0.26 m at 2 m
                               for a 7.5-degree half-width, and the robot hears it again
                               nearer before it gets there; 100..32767 (default 2000) */
    int32_t max_cells;      /* grid capacity, allocated at create, 1024..(1 << 22)
                               (default 1 << 20: 51 x 51 m at 50 mm cells) */
} hl_plan_params_t;

/** Fills @p p with the defaults above. */
void hl_plan_params_default(hl_plan_params_t *p);
/** A one-line description of what is wrong with @p p (naming the field), or NULL. */
const char *hl_plan_params_error(const hl_plan_params_t *p);

/* ---- results ------------------------------------------------------------------------ */

#define HL_PLAN_MAX_POINTS 64
#define HL_PLAN_MAX_OBSTACLES 64

typedef struct hl_plan_path {
    uint32_t n;             /* points, the start first; 0 on failure, >= 2 on success */
    hl_mm_t x_mm[HL_PLAN_MAX_POINTS], y_mm[HL_PLAN_MAX_POINTS];
    int32_t length_mm;      /* along the points, rounded */
    bool cut;               /* the way needed more than HL_PLAN_MAX_POINTS points: these
                               are its first ones and the last is not the goal (the
                               robot replans at every leg anyway) */
} hl_plan_path_t;

typedef enum hl_plan_result {
    HL_PLAN_OK = 0,
    HL_PLAN_GOAL_BLOCKED,   /* the goal's cell is lethal, fenced or an obstacle, or the
                               goal is outside allowed. A lethal goal cell means the goal
                               is less than radius_mm + 1.42 cell_mm from an obstacle cell
                               (hl_planner_goal_clearance); always so below radius_mm */
    HL_PLAN_NO_PATH,        /* no way from start to goal */
    HL_PLAN_TOO_BIG,        /* the grid over map, start and goal would exceed max_cells */
    HL_PLAN_BAD_ARG,        /* NULL, or coordinates out of +-HL_COORD_MAX_MM, or a vector
                               out of range (hl_vector_in_range), or n too large */
} hl_plan_result_t;

/** A constant name, e.g. "goal blocked". */
const char *hl_plan_result_name(hl_plan_result_t r);

/* ---- the planner -------------------------------------------------------------------- */

typedef struct hl_planner hl_planner_t;

/** Allocates a planner (and its grid) for @p p. @return NULL on bad params
 *  (hl_plan_params_error) or out of memory. */
hl_planner_t *hl_planner_create(const hl_plan_params_t *p);
/** Frees the planner. Accepts NULL. */
void hl_planner_destroy(hl_planner_t *pl);

/**
 * Adds an extra obstacle point (a sonar reading that stopped the robot while driving),
 * map frame, mm. Kept until cleared and drawn into every build; at most
 * HL_PLAN_MAX_OBSTACLES (a new one then replaces the oldest).
 * @return HL_OK, HL_ERR_ARG on NULL, HL_ERR_RANGE outside +-HL_COORD_MAX_MM (not added).
 */
hl_status_t hl_planner_add_obstacle(hl_planner_t *pl, hl_mm_t x_mm, hl_mm_t y_mm);
/** Forgets every extra obstacle. */
void hl_planner_clear_obstacles(hl_planner_t *pl);
/** How many extra obstacles are kept, 0..HL_PLAN_MAX_OBSTACLES. */
uint32_t hl_planner_obstacle_count(const hl_planner_t *pl);

/**
 * Where the robot may go besides the walls (the geofence), asked at cell centres, map
 * frame, mm. Called during hl_planner_plan only, once per cell and once for the goal.
 */
typedef bool (*hl_plan_allowed_fn)(void *ctx, hl_mm_t x_mm, hl_mm_t y_mm);
/** Sets the geofence: cells whose centre fails @p fn are obstacles for the search but
 *  are not inflated. NULL @p fn for everywhere. @p ctx is the caller's, passed back. A
 *  leg joins allowed cell centres, so it stays inside a convex allowed area; at a
 *  concave corner it may cut up to half a cell across. */
void hl_planner_set_allowed(hl_planner_t *pl, hl_plan_allowed_fn fn, void *ctx);

/**
 * Builds the grid over @p v (n vectors, n <= HL_MAP_MAX_CAPACITY; v may be NULL when n
 * is 0), the extra obstacles, the start and the goal, then plans from start to goal (map
 * frame, mm, within +-HL_COORD_MAX_MM) with A* (8-connected, octile heuristic) and pulls
 * the cell path into straight legs: from each point, the farthest later point whose
 * segment crosses no lethal or fenced cell (the start's lethal region excepted) and no
 * cell costlier than HL_PLAN_SMOOTH_COST or than the A* path it replaces.
 * @param[out] out  the path (start and goal exact; the points between are cell centres);
 *                  n = 0 unless HL_PLAN_OK. Must not be NULL.
 * @return HL_PLAN_OK or the reason; the grid of this build can be read after any result
 *         but HL_PLAN_BAD_ARG and HL_PLAN_TOO_BIG (it is then empty).
 */
hl_plan_result_t hl_planner_plan(hl_planner_t *pl, const hl_vector_t *v, uint32_t n,
                                 hl_mm_t start_x, hl_mm_t start_y, hl_mm_t goal_x,
                                 hl_mm_t goal_y, hl_plan_path_t *out);

/** For GOAL_BLOCKED messages: the distance from the goal of the last build to the
 *  nearest obstacle cell (to its square), mm; -1 when there was none or no build. */
int32_t hl_planner_goal_clearance(const hl_planner_t *pl);

/** Bytes allocated by the planner and its grid (0 for NULL). */
size_t hl_planner_mem_bytes(const hl_planner_t *pl);

/* ---- the grid, for drawing and for checking a leg --------------------------------- */

#define HL_PLAN_COST_MAX 252
#define HL_PLAN_CELL_LETHAL 253
#define HL_PLAN_CELL_FENCE 254
#define HL_PLAN_CELL_OBSTACLE 255
/* A leg may cross cells up to this cost (the outer half of the clearance band) unless
 * the A* path it replaces went costlier. */
#define HL_PLAN_SMOOTH_COST (HL_PLAN_COST_MAX / 2)

/** A read-only view of the last build. Its arrays belong to the planner (or costmap) and
 *  are valid until the next build or destroy. */
typedef struct hl_plan_grid {
    int32_t cols, rows;             /* 0 when nothing is built */
    int32_t cell_mm;
    hl_mm_t x0_mm, y0_mm;           /* the centre of cell (0, 0) */
    const uint8_t *cells;           /* cols * rows, row-major: cells[j * cols + i] */
    const uint8_t *start_region;    /* same layout: 1 for the start's lethal region */
    int32_t start_col, start_row;   /* the cells holding start and goal */
    int32_t goal_col, goal_row;
    int32_t goal_clearance_mm;      /* as hl_planner_goal_clearance */
} hl_plan_grid_t;

/** The planner's last grid into @p out (cols = 0 when none, or when @p pl is NULL). */
void hl_planner_grid(const hl_planner_t *pl, hl_plan_grid_t *out);

/**
 * Whether a robot centre moving straight from (ax, ay) to (bx, by) stays on cells of
 * cost <= @p max_cost or of the start's lethal region (never touching an obstacle cell,
 * not even at a corner). false when either end is outside the grid. For example, whether
 * a leg planned earlier is still clear after new echoes (build a grid first).
 */
bool hl_plan_segment_clear(const hl_plan_grid_t *g, hl_mm_t ax, hl_mm_t ay, hl_mm_t bx,
                           hl_mm_t by, uint8_t max_cost);

/* The grid alone (what hl_planner_plan builds before it searches), for drawing a costmap
 * without planning. */
typedef struct hl_costmap hl_costmap_t;

/** What a grid is built from. The arrays are the caller's, read during the build only. */
typedef struct hl_costmap_input {
    const hl_vector_t *v;           /* n vectors; NULL when n is 0 */
    uint32_t n;                     /* 0..HL_MAP_MAX_CAPACITY */
    const hl_mm_t *obstacle_x;      /* n_obstacles extra obstacle points */
    const hl_mm_t *obstacle_y;
    uint32_t n_obstacles;
    hl_plan_allowed_fn allowed;     /* NULL for everywhere */
    void *allowed_ctx;
    hl_mm_t start_x, start_y, goal_x, goal_y;
} hl_costmap_input_t;

/** Allocates a grid of @p p->max_cells. @return NULL on bad params or out of memory. */
hl_costmap_t *hl_costmap_create(const hl_plan_params_t *p);
/** Frees the grid. Accepts NULL. */
void hl_costmap_destroy(hl_costmap_t *cm);
/** Builds the grid for @p in. @return HL_PLAN_OK, HL_PLAN_TOO_BIG or HL_PLAN_BAD_ARG
 *  (then the grid is empty); never GOAL_BLOCKED or NO_PATH. */
hl_plan_result_t hl_costmap_build(hl_costmap_t *cm, const hl_costmap_input_t *in);
/** The last build into @p out (cols = 0 when none, or when @p cm is NULL). */
void hl_costmap_grid(const hl_costmap_t *cm, hl_plan_grid_t *out);
/** Bytes allocated by the grid (0 for NULL). */
size_t hl_costmap_mem_bytes(const hl_costmap_t *cm);

#ifdef __cplusplus
}
#endif
#endif
