/*
 * corrmatch.h (private) - a correlative scan matcher for loop closure: every pose within
 * a window searched, exhaustively and fast, by branch and bound over a resolution pyramid
 * (Olson, "Real-time correlative scan matching", ICRA 2009; the fast correlative matcher
 * of Hess et al., "Real-time loop closure in 2D LIDAR SLAM", ICRA 2016).
 *
 * The map's points are drawn into a likelihood field (each cell the nearness of its
 * nearest point, a Gaussian of HL_CORR_SIGMA_MM), and each level h of the pyramid holds
 * the largest value over a square of 2^h cells, so that a square of candidate positions
 * scored on level h bounds every position within it from above. A pose's score is the
 * mean field value under the query's points: 1 where every point lies on a map point.
 *
 * Unlike the tracker's Hough vote (localize.h), whose window is the odometry's and whose
 * peak may be the nearest of two alike places, this answers with the best pose in the
 * whole window and the best pose distinctly elsewhere in it (the runner-up): a match is
 * taken only when the two differ clearly, which is what tells a corridor's length or a
 * row of alike doors from one place.
 *
 * Memory: the field and its pyramid grow to the largest search asked (at most
 * HL_CORR_MAX_CELLS cells a level), then are reused.
 */
#ifndef HOUGHLOC_CORE_CORRMATCH_H
#define HOUGHLOC_CORE_CORRMATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/posegraph.h"
#include "houghloc/scan.h"

#define HL_CORR_CELL_MM 50.0        /* the field's cell */
#define HL_CORR_SIGMA_MM 50.0       /* a point's spread in the field */
#define HL_CORR_RANGE_MM 12000.0    /* readings farther are left out (a long return's
                                       place errs most with the heading, and the field
                                       would grow with its square) */
#define HL_CORR_MAX_CELLS (1u << 21)  /* a level's cells at most (a 72 x 72 m field) */
#define HL_CORR_MAX_POINTS 4096     /* map or query points a search at most */
#define HL_CORR_MAX_WINDOW_MM 10000.0 /* a region's half-width at most */
#define HL_CORR_MIN_STEP_RAD 0.002  /* the finest turn searched (0.11 degrees) */

typedef struct hl_corr_point {
    float x, y;             /* mm */
} hl_corr_point_t;

/* What a search covers and what it answers. */
typedef struct hl_corr_params {
    double window_mm;       /* +- in x and y about the centre, 0..HL_CORR_MAX_WINDOW_MM */
    double window_rad;      /* +- in heading, >= 0 */
    double min_score;       /* a best pose scoring less is no answer (0..1): the search
                               prunes every square that cannot reach it */
    double runner_share;    /* ... nor one that a pose distinct from it scores this share
                               of (0..1; 1: no runner-up sought) */
    double distinct_mm;     /* distinct: farther than this from it ... */
    double distinct_rad;    /* ... or turned more than this */
} hl_corr_params_t;

typedef struct hl_corr_result {
    bool matched;           /* the best pose reaches min_score and has no runner-up */
    hl_pg_pose_t pose;      /* the best pose, polished below the cell when matched */
    double score;           /* its mean field value, 0..1 (0: none reached min_score) */
    double runner_up;       /* the score of a distinct pose at least runner_share of it,
                               if one was found (the first found, not the best); else 0 */
} hl_corr_result_t;

typedef struct hl_corr hl_corr_t;

hl_corr_t *hl_corr_create(void);
void hl_corr_destroy(hl_corr_t *c);     /* accepts NULL */
size_t hl_corr_mem_bytes(const hl_corr_t *c);

/** Appends @p scan's valid readings within HL_CORR_RANGE_MM, taken at @p at, as points of
 *  @p at's frame's parent (the map's, for a map; pass the origin for the robot's own
 *  frame) to @p out, which holds @p n of @p max. @return the new count. */
uint32_t hl_corr_points(const hl_scan_t *scan, hl_pg_pose_t at, hl_corr_point_t *out,
                        uint32_t n, uint32_t max);

/**
 * Where the @p n_query points of @p query (the robot's frame) best fit the @p n_map
 * points of @p map, among the poses of @p p's region about @p center.
 * @return false when there is nothing to match (no points, a region out of range, a
 * field too large, no memory); true with @p out filled otherwise.
 */
bool hl_corr_search(hl_corr_t *c, const hl_corr_point_t *map, uint32_t n_map,
                    const hl_corr_point_t *query, uint32_t n_query, hl_pg_pose_t center,
                    const hl_corr_params_t *p, hl_corr_result_t *out);

#endif
