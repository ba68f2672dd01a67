/* corridor.h - the benchmarks' synthetic loop-closure graph (hl-bench-posegraph,
 * hl-bench-solve): N stops back and forth along a 28 m corridor, 0.6 m apart and weaving
 * 1 m either side of its middle; a step between consecutive stops and, for each stop, a
 * match with up to HL_CLOSURE_MAX_TAKEN of the stops at least HL_CLOSURE_GAP before it
 * within HL_CLOSURE_RADIUS_MM (closure.h's rules at their most), every one measured with
 * 30 mm and 1.1 degrees of noise, a share of the matches 2 m and 29 degrees wrong. A
 * function of N and that share alone (a fixed seed). */
#ifndef HOUGHLOC_BENCH_CORRIDOR_H
#define HOUGHLOC_BENCH_CORRIDOR_H

#include <stdint.h>

#include "houghloc-internal/posegraph.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The most edges a graph of @p n stops can have: the size of sr_corridor's @p edges. */
uint32_t sr_corridor_max_edges(uint32_t n);

/** Fills @p truth and @p chained (n poses each: the true stops, and the stops chained by
 *  their measured steps, as a tour's drift leaves them) and @p edges
 *  (sr_corridor_max_edges(n)), @p wrong_pct per cent of the matches wrong (0..100).
 *  @return the number of edges. */
uint32_t sr_corridor(uint32_t n, double wrong_pct, hl_pg_pose_t *truth, hl_pg_pose_t *chained,
                     hl_pg_edge_t *edges);

#ifdef __cplusplus
}
#endif

#endif
