/*
 * normals.h (internal) - each laser reading's surface normal, from its neighbours (an improvement
 * on the paper for dense scanners).
 *
 * The paper's tangent vector is a sonar's: a sonar only hears a surface near square to
 * its beam, so the surface's normal is the beam's reverse. A laser hears a wall at any
 * angle; placed square to the beam, a wall seen obliquely gets the beam's direction as its
 * normal, which changes from scan to scan as the robot moves. The normal gate then pairs
 * readings with map vectors by where they were seen from rather than by which way the
 * surface faces, and the global search's heading histogram (reloc.h) ranks headings at
 * random (docs/design/relocalization.md).
 *
 * A laser's neighbouring readings lie on the same surface: a line fitted through a reading
 * and its neighbours within reach gives the surface's direction, and the reading's normal
 * is the line's normal facing the sensor. The result is kept as the reading's tilt (scan.h,
 * the normal's turn from the beam's reverse), so the rest of the pipeline is unchanged.
 * Readings that do not lie on a line (corners, clutter, a lone return) or whose surface is
 * seen at grazing incidence are marked invalid: they have no tangent to offer. Tracking
 * wants them kept, square to their beams (keep_unfitted: the global search is better
 * without them, tracking worse).
 *
 * Readings are taken to be in bearing order, as a scanner gives them. No allocation;
 * O(n * w) for n readings and a window of w.
 */
#ifndef HOUGHLOC_INTERNAL_NORMALS_H
#define HOUGHLOC_INTERNAL_NORMALS_H

#include <stdint.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_NORMALS_MAX_HALF_WINDOW 32

/* Fixed (were settings): at 1 degree between beams, 4 neighbours each side span 0.6 m of
 * a wall 4 m away; 250 mm of reach keeps the line on one surface near the robot and lets
 * a far wall's sparser points still make one from their nearest neighbours. */
#define HL_NORMALS_HALF_WINDOW 4
#define HL_NORMALS_REACH_MM 250

typedef struct hl_normals_params {
    uint16_t half_window;       /* neighbours looked at on each side, in scan order;
                                   default 4 (1..32) */
    int32_t reach_mm;           /* a neighbour farther than this from the reading is on
                                   another surface; default 250 */
    uint16_t min_points;        /* a line needs this many points, the reading included;
                                   default 4 (3..65) */
    int32_t max_residual_mm;    /* RMS distance of the points from their line above which
                                   the reading has no surface (a corner); default 20 */
    hl_bam_t max_tilt;          /* a surface turned farther than this from square to the
                                   beam is seen too obliquely to trust; default 75 deg */
    bool keep_unfitted;         /* a reading with no line stays, square to its beam (tilt
                                   0, the paper's tangent), instead of being dropped;
                                   default false */
} hl_normals_params_t;

/** Fills @p p with the defaults above. */
void hl_normals_params_default(hl_normals_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_normals_params_error(const hl_normals_params_t *p);

/**
 * Copies @p in to @p out with every valid reading's tilt set from the line through it and
 * its neighbours; a reading with no such line becomes invalid (or keeps tilt 0 with
 * keep_unfitted). Bearings, ranges and order are unchanged. @p in and @p out may not
 * overlap.
 * @return HL_OK; HL_ERR_ARG for NULL, overlap or invalid parameters; HL_ERR_RANGE when
 *         @p in fails hl_scan_check.
 */
hl_status_t hl_normals_fit(const hl_normals_params_t *p, const hl_scan_t *in, hl_scan_t *out);

#ifdef __cplusplus
}
#endif
#endif
