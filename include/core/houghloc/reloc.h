/*
 * reloc.h - what a global relocalization found: where the robot is in a known map, with
 * no idea of its position or heading, from its scans (the kidnapped robot; not in the
 * paper). A tracker's step carries one when it searched (hl_slam_step_t.search, slam.h).
 *
 * Each candidate pose is judged by what it explains: the valid readings that, placed at
 * it, land near a map vector facing the same way (a reading counts once). The answer is
 * the pose that explains most; the runner-up the best other one that is distinct (far
 * enough away in position or heading). The answer is "found" when it explains enough of
 * the readings and clearly more than the runner-up; otherwise "ambiguous" (a symmetric
 * corridor, a scan that sees too little). Design: docs/design/relocalization.md.
 */
#ifndef HOUGHLOC_RELOC_H
#define HOUGHLOC_RELOC_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/export.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_reloc_result {
    bool found;                 /* an answer distinct enough from the runner-up */
    hl_pose_t pose;             /* the best fine pose (also when ambiguous) */
    uint32_t score;             /* readings it explains (within verify_mm) */
    uint32_t readings;          /* the scan's valid readings (of all the scans) */
    double explained_pct;       /* score as a share of them */
    bool have_runner_up;
    hl_pose_t runner_up;        /* the best distinct other pose */
    uint32_t runner_up_score;   /* readings it explains; 0 if none */
    uint32_t edge;              /* readings that favour the answer over the runner-up: +1
                                   for each explained at the answer and not at the
                                   runner-up or contradicting the runner-up and not the
                                   answer, +2 for both; = score with no runner-up */
    uint32_t runner_edge;       /* ... the runner-up over the answer */
    uint16_t headings_tried;    /* stage 1 candidates searched */
    uint16_t hypotheses_tried;  /* stage 3 searches run */
    uint16_t scans;             /* scans searched together */
} hl_reloc_result_t;

/** 1 - runner_up_score / score (0..1; 1 with no runner-up, 0 with no answer). */
HL_API double hl_reloc_confidence(const hl_reloc_result_t *r);

#ifdef __cplusplus
}
#endif
#endif
