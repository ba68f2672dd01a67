/*
 * fixed.h - the fixed-point formats of houghloc, with their ranges and overflow bounds.
 *
 * Every number on the localization hot path is an integer in one of these formats.
 *
 *   length / coordinate   int32_t millimetres (hl_mm_t).
 *       World coordinates:  |x|, |y| <= HL_COORD_MAX_MM  (2^22 mm = 4194 m).
 *       Ranges:             0 <= r <= HL_RANGE_MAX_MM    (32767 mm, fits int16).
 *       A difference of two coordinates is < 2^23 in magnitude: no overflow.
 *
 *   angle                 uint16_t binary angle units, BAM (hl_bam_t): 65536 per turn,
 *       counter-clockwise, 0 = +x.  Wrap-around is free: uint16 arithmetic is modulo
 *       one turn.  A signed difference is (int16_t)(a - b), in [-32768, 32767].
 *       1 degree = 182.04 BAM; 1 BAM = 0.0055 degrees.
 *
 *   sine / cosine         a first-quadrant table of sin in Q30 (int32, 16385 entries,
 *       generated at build time; error <= 2^-31). The public hl_sin / hl_cos round it
 *       to int16_t Q14 (HL_TRIG_ONE = 16384 means 1.0), error <= 0.5 / 16384.
 *
 *   polar -> cartesian    hl_polar_to_xy (the core's, houghloc-internal/fixed.h):
 *       x = (r * cos_q14 + 2^13) >> 14, in mm.
 *       |r * cos| <= 32767 * 16384 < 2^29.  Error <= 0.5 mm + r * 0.5/16384 <= 1.5 mm.
 *       hl_polar_to_xy_q8 (the vote loop): x = (r * cos_q30 + 2^21) >> 22, in 1/256 mm.
 *       |r * cos_q30| <= 2^15 * 2^30 = 2^45, computed in int64; the result is below
 *       2^23 and its error below 1/256 mm, so a vote lands in the same cell as with
 *       exact trigonometry unless it is within 1/256 mm of a cell border.
 *
 *   vote cell             uint16_t vote count, saturating at 65535 (HL_VOTE_MAX).
 *
 *   blurred vote          uint32_t, votes x 256 (Q8).  The blur is separable with integer
 *       kernels whose taps sum to at most 256 per axis, and each pass after the first
 *       shifts right by 8 with rounding, so every intermediate stays below
 *       65535 * 256 * 256 < 2^32 and a final value below 65535 * 256 < 2^24.
 */
#ifndef HOUGHLOC_FIXED_H
#define HOUGHLOC_FIXED_H

#include <stdint.h>

#include "houghloc/export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t hl_mm_t;
typedef uint16_t hl_bam_t;

#define HL_COORD_MAX_MM (1 << 22)
#define HL_RANGE_MAX_MM 32767
#define HL_BAM_PER_TURN 65536
#define HL_BAM_HALF_TURN 32768u
#define HL_BAM_QUARTER_TURN 16384
#define HL_TRIG_SHIFT 14
#define HL_TRIG_ONE (1 << HL_TRIG_SHIFT)
#define HL_VOTE_MAX UINT16_MAX

/** Sine of a binary angle, Q14. */
HL_API int16_t hl_sin(hl_bam_t a);
/** Cosine of a binary angle, Q14. */
HL_API int16_t hl_cos(hl_bam_t a);

/** Signed shortest difference a - b, in BAM: [-32768, 32767]. */
static inline int32_t hl_bam_diff(hl_bam_t a, hl_bam_t b)
{
    return (int16_t)(uint16_t)(a - b);
}

/** Conversions for configuration and tools (not the hot path). Rounds to nearest. */
HL_API hl_bam_t hl_bam_from_deg(double deg);
HL_API hl_bam_t hl_bam_from_rad(double rad);
HL_API double hl_bam_to_deg(hl_bam_t a);   /* in [0, 360) */
HL_API double hl_bam_to_rad(hl_bam_t a);   /* in [0, 2 pi) */
/** Signed angle in degrees, [-180, 180). */
HL_API double hl_bam_to_sdeg(hl_bam_t a);

#ifdef __cplusplus
}
#endif
#endif
