/*
 * posegraph.h (private) - the least-squares fit of 2-D poses to relative measurements
 * between them (a pose graph): what loop closure (closure.h) asks of the stops when a
 * new match says where one stop lies from another.
 *
 * Gauss-Newton; each step's normal equations, 3 x 3 blocks (each pose's own and each
 * edge's between its two poses), are solved by the solve layer's sparse Cholesky
 * factorization (houghloc-internal/solve.h: Eigen's SimplicialLDLT behind a C interface),
 * whose ordering serves while the pattern holds; or, while the poses have moved little
 * since the last factorization (a fit's last steps, the next fit after a stop added),
 * by conjugate gradients preconditioned by that factorization, kept from fit to fit. Every edge weighs the same (one localization's error, sigma_mm
 * and sigma_rad), but that a loop edge may be weighed down by a Cauchy kernel (iteratively
 * reweighted: each Gauss-Newton step weighs it by 1 / (1 + e / kernel^2), e its squared
 * error in standard deviations at the poses the step starts from). A pose may also carry
 * a heading of its own (hl_pg_heading_t), weighed by its own sigma alone, never under the
 * kernel: the walls' headings (closure.h) are many and each weak, and under the kernel a
 * stretch of stops turned as a whole could not be turned back. Pose 0 is held where it
 * is. Memory: the workspace from create; the factorization's own from Eigen, in the
 * calls (docs/results/pose-graph-solver.md). Design and figures:
 * docs/design/loop-closure.md.
 */
#ifndef HOUGHLOC_CORE_POSEGRAPH_H
#define HOUGHLOC_CORE_POSEGRAPH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/scan.h"

typedef struct hl_pg_pose {
    double x, y, theta;     /* mm, mm, radians */
} hl_pg_pose_t;

typedef struct hl_pg_edge {
    uint32_t from, to;      /* pose indices */
    hl_pg_pose_t rel;       /* pose `to` in the frame of pose `from`, as measured */
    bool loop;              /* a match (may be dropped as an outlier), not a step */
} hl_pg_edge_t;

/* A heading measured against the world rather than another pose (a building's walls seen
 * square to its axes, closure.h): pose `pose` should have heading `theta`. */
typedef struct hl_pg_heading {
    uint32_t pose;
    double theta;           /* radians */
    double sigma_rad;       /* its standard deviation, > 0 */
} hl_pg_heading_t;

typedef struct hl_posegraph hl_posegraph_t;

/** A workspace for up to @p max_poses poses and @p max_edges edges; NULL on no memory. */
hl_posegraph_t *hl_posegraph_create(uint32_t max_poses, uint32_t max_edges);
void hl_posegraph_destroy(hl_posegraph_t *g);     /* accepts NULL */
size_t hl_posegraph_mem_bytes(uint32_t max_poses, uint32_t max_edges);

/* A fixed-point pose as a graph's, and back (rounded, positions clamped to the
 * coordinate range). */
hl_pg_pose_t hl_pg_from_pose(hl_pose_t p);
hl_pose_t hl_pg_to_pose(hl_pg_pose_t p);

/* Pose @p b in the frame of @p a, and its inverse. */
hl_pg_pose_t hl_pg_between(hl_pg_pose_t a, hl_pg_pose_t b);
hl_pg_pose_t hl_pg_compose(hl_pg_pose_t a, hl_pg_pose_t rel);

/** The poses were renumbered since the last fit: pose i is now pose i - @p k (the first
 *  @p k forgotten, as a record of stops forgets its oldest), so that the factorization
 *  kept from that fit still preconditions the next (hl_posegraph_fit). */
void hl_posegraph_shift(hl_posegraph_t *g, uint32_t k);

/* What the fits so far did (for benchmarks and tests): Gauss-Newton steps, the
 * analyses and factorizations of their normal equations, and the steps solved instead by
 * conjugate gradients on the last factorization (with their iterations, and the tries
 * that did not converge and were factored after all). */
typedef struct hl_pg_work {
    uint64_t steps, analyses, factorizations;
    uint64_t pcg_solves, pcg_iterations, pcg_failures;
} hl_pg_work_t;

hl_pg_work_t hl_posegraph_work(const hl_posegraph_t *g);

/** A loop edge (a match) counts @p weight (0 < weight <= 1) of a step in the fits from
 *  now on, after its kernel (which, with the outlier gate, still reads its error in the
 *  steps' sigmas): for matches less sure than the steps, as a continuous sensor's
 *  keyframes are joined by many scans' tracking. 1 from create. @return false on a
 *  weight out of range (nothing changed). */
bool hl_posegraph_weigh_matches(hl_posegraph_t *g, double weight);

/**
 * Moves @p poses[1 .. n - 1] to the least-squares fit of @p edges and of the @p n_headings
 * @p headings (pose 0 held: a heading of its own is ignored; a heading naming no pose,
 * not a number or with no positive finite sigma refuses the call), each loop edge under
 * a Cauchy kernel of @p kernel standard deviations (0: none). Then the loop
 * edges more than @p gate standard deviations off the fit (rms over their three terms)
 * are dropped from @p edges (*n_edges shrinks, the order kept), worst first, and the rest
 * fitted again, until none is that far off or 8 are dropped: under a kernel all such
 * edges at once, then a few steps from the fit before; without, one at a time, each time
 * a whole fit. Each fit's Gauss-Newton steps end when no pose moves more than 1/500 of
 * @p sigma_mm and @p sigma_rad (both positive, else the call is refused).
 * n <= max_poses, *n_edges <= max_edges; edges must name poses below n. A
 * pose that no chain of edges ties to pose 0 makes the system singular: the solver
 * refuses it and the poses stay as they are.
 * @return the number of loop edges dropped.
 */
uint32_t hl_posegraph_fit(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n,
                          hl_pg_edge_t *edges, uint32_t *n_edges,
                          const hl_pg_heading_t *headings, uint32_t n_headings,
                          double sigma_mm, double sigma_rad, double kernel, double gate);

#endif
