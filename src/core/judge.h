/*
 * judge.h (private) - how well a scan placed at a pose agrees with the map: the global
 * search's judge (reloc.c; docs/design/relocalization.md).
 *
 * Votes are a poor score across a whole map: a place crowded with map vectors (a
 * cluttered corner) collects many for any heading, since a reading votes once per
 * vector it pairs with. The judge counts each reading once: explained when it lands
 * within tol_mm across and verify_along_mm along a map vector facing its way within
 * judge_gate; contradicting when its beam passes through a mapped surface facing the
 * sensor (it would have echoed there), or, with short_mm, stops short of one.
 *
 * Memory comes from hl_judge_init only.
 */
#ifndef HOUGHLOC_CORE_JUDGE_H
#define HOUGHLOC_CORE_JUDGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cellhash.h"
#include "houghloc-internal/reloc.h"

typedef struct hl_judge {
    hl_reloc_params_t p;    /* verify_mm, verify_along_mm, judge_gate, short_mm */
    hl_cellhash_t near;     /* the map by cells of the larger tolerance */
    int8_t verdict_a[HL_SCAN_MAX_READINGS], verdict_b[HL_SCAN_MAX_READINGS];
} hl_judge_t;

/** Allocates for maps of up to @p capacity vectors. @return false when memory is short
 *  (hl_judge_free releases what was allocated either way). */
bool hl_judge_init(hl_judge_t *j, const hl_reloc_params_t *p, uint32_t capacity);
void hl_judge_free(hl_judge_t *j);
size_t hl_judge_mem_bytes(const hl_judge_t *j);

/** Hashes @p map[0 .. n - 1] (n <= capacity) for the calls below. */
void hl_judge_build(hl_judge_t *j, const hl_vector_t *map, uint32_t n);

/**
 * The valid readings of @p scan at @p pose explained within @p tol_mm across; with
 * @p contradicted, also counts there the unexplained ones that contradict the map. With
 * @p verdict (one per reading of the scan), each reading's +1 explained, -1
 * contradicting (counted only with @p contradicted), 0 neither.
 */
uint32_t hl_judge_explained(const hl_judge_t *j, const hl_scan_t *scan, hl_pose_t pose,
                            int32_t tol_mm, uint32_t *contradicted, int8_t *verdict);

/** Explained within verify_mm less contradicting, at least 0: a pose's score. */
uint32_t hl_judge_score(const hl_judge_t *j, const hl_scan_t *scan, hl_pose_t pose);

/**
 * How poses @p a and @p b differ reading by reading: each reading's verdict at one less
 * at the other, summed where @p a is better (@p edge) and where @p b is (@p b_edge). The
 * readings both explain, a long wall's, say nothing of which is right.
 */
void hl_judge_edges(hl_judge_t *j, const hl_scan_t *scan, hl_pose_t a, hl_pose_t b,
                    uint32_t *edge, uint32_t *b_edge);

#endif
