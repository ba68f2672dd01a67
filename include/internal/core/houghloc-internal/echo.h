/*
 * echo.h (internal) - where in the beam each sonar echo came from (an improvement on the paper).
 *
 * A sonar reading is the first echo from anywhere in a cone of about 22 degrees, but the
 * paper places it on the beam axis. For most readings that is wrong by up to half the
 * cone: a wall seen off its normal echoes from the cone's edge nearest the normal, and
 * a wall seen near its normal echoes from its foot, wherever the axis points. Placed on
 * the axis, both bend walls into arcs and bias every vote.
 *
 * The sounding itself says where the echo can be. If reading i's echo came from bearing
 * psi at range r_i, then every other reading of the same sounding whose cone contains
 * psi would have heard that surface too, so its range cannot be much longer than r_i.
 * For each candidate psi in reading i's cone this module scores how much the readings
 * covering psi contradict it (the sum over them of ((r_k - r_i) / sigma_k)^2 / 2 where
 * r_k > r_i, each term capped so one bounced reading cannot veto a bearing) and moves the
 * reading to the middle of the least contradicted bearings. A wall's plateau collapses
 * towards its foot, its steep flanks move to their cone edges (to within half a ring
 * step), and a reading with no contradiction anywhere stays on its axis. An isolated
 * spike, longer than both its ring neighbours by more than three sigma, is taken for a
 * bounced echo and contradicts nothing: the neighbours' cones overlap most of its own,
 * so a real surface that far would have shown in them too.
 *
 * Within the range noise a wall's flank near its foot looks flat, so readings there move
 * only part of the way (the bearing errors before and after: docs/design/localizer.md).
 *
 * Integer arithmetic only; no allocation; O(n * k * s) for n readings, k neighbours
 * within a cone width and s candidate bearings (128 x 16 x 45 for the paper's ring).
 */
#ifndef HOUGHLOC_INTERNAL_ECHO_H
#define HOUGHLOC_INTERNAL_ECHO_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fixed (were settings; the lab's studies found nothing better, docs/design/expert-keys.md):
 * the candidate bearings' spacing, the range noise (10 mm + 1 %, the ring's), and the
 * contradiction's cap and tie (3-16 and 0.25-1 were within noise of these). */
#define HL_ECHO_STEP_DEG 0.5
#define HL_ECHO_NOISE_MM 10
#define HL_ECHO_NOISE_PERMILLE 10
#define HL_ECHO_CAP 8           /* x 256 in cap_q8 */
#define HL_ECHO_TIE 0.5         /* x 256 in tie_q8 */

/* At most this many candidate bearings per reading (half_beam * 2 / step + 1). */
#define HL_ECHO_MAX_CANDIDATES 257

typedef struct hl_echo_params {
    hl_bam_t half_beam;         /* half the width within which an echo can come from;
                                   default 7 deg, where a Polaroid-type transducer's
                                   two-way response is 12 dB down (1..45 deg); 11 for a
                                   hard 22-degree cone */
    hl_bam_t step;              /* spacing of candidate bearings; default 0.5 deg */
    uint16_t noise_mm;          /* range noise sigma = noise_mm + range * noise_permille
                                   / 1000; defaults 10 mm and 10 (1 %) */
    uint16_t noise_permille;
    uint16_t cap_q8;            /* cap of one reading's contradiction, (z^2 / 2) x 256;
                                   default 8 x 256 */
    uint16_t tie_q8;            /* bearings scoring within this of the best count as best;
                                   default 0.5 x 256 */
    bool flank_normals;         /* a reading on a wall's flank: its echo at the cone's
                                   edge and its normal the wall's (flank.h); default off */
} hl_echo_params_t;

/** Fills @p p with the defaults above. */
void hl_echo_params_default(hl_echo_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_echo_params_error(const hl_echo_params_t *p);

/**
 * Copies @p in to @p out with every valid reading's bearing moved to its estimated echo
 * bearing (robot frame), and with flank_normals its flank readings' normals (flank.h).
 * Ranges, validity and order are unchanged. @p in and @p out may
 * not overlap.
 * @return HL_OK; HL_ERR_ARG for NULL, overlap or invalid parameters; HL_ERR_RANGE when
 *         @p in fails hl_scan_check.
 */
hl_status_t hl_echo_correct(const hl_echo_params_t *p, const hl_scan_t *in, hl_scan_t *out);

#ifdef __cplusplus
}
#endif
#endif
