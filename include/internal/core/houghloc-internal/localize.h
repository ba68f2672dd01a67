/*
 * localize.h (internal) - Hough-transform localization of one scan against a map of tangent
 * vectors (paper, sections 5 and 6).
 *
 * For every candidate heading h (one slice, or a slice of headings around a predicted
 * one) and every pair <test reading, map vector> whose surface normals agree within the
 * normal gate, the pair votes for the robot position that would make the reading hit
 * the map vector's surface:  position = map point - R(h) * reading.  Votes go into an
 * (x, y, theta) raster; the raster is blurred with a separable integer Gaussian; the
 * highest cell is the pose, refined by parabolic sub-cell interpolation on each axis.
 *
 * The xy raster covers either the map's bounding box (global search) or a square window
 * around a predicted position (local search). All memory is allocated by
 * hl_loc_create; hl_loc_run allocates nothing. Fixed-point formats: fixed.h.
 *
 * The stage the tracker (slam.c), the global search and the laboratory run; a program
 * localizes through the tracker (slam.h).
 */
#ifndef HOUGHLOC_INTERNAL_LOCALIZE_H
#define HOUGHLOC_INTERNAL_LOCALIZE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/map.h"
#include "houghloc/localize.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fixed (were settings): the heading raster (1.1-degree slices, 8 each side: +-8.8
 * degrees, the fewest whole slices that cover the +-8.4 asked for; 12 mended some
 * long-drive slips at 1.5 times the time, which slam.long_drive_mm does better), the
 * paper's 30-degree normal gate, the heading blur (wider looks precise only because the
 * window's edges pull the peak to its middle) and the second peak's distance (the wild
 * error's). */
#define HL_LOC_THETA_STEP_DEG 1.1
#define HL_LOC_THETA_HALF_STEPS 8
#define HL_LOC_NORMAL_GATE_DEG 30
#define HL_LOC_BLUR_SIGMA_THETA_DEG 0.75
#define HL_LOC_PEAK_SEPARATION_MM 500
/* The largest map a standalone localizer accepts by default (a tracker's is made for its
 * slam.map_capacity). */
#define HL_LOC_MAX_MAP_VECTORS 16384

/* The largest raster a localizer allocates for (max_cells): 2^26 cells, 640 MiB. */
#define HL_LOC_MAX_CELLS (1u << 26)

typedef struct hl_loc_params {
    hl_mm_t cell_mm;            /* xy raster cell, 1..1000; default 24 (paper: 47, 24) */
    hl_bam_t theta_step;        /* heading raster step; default 1.1 deg (200 BAM) */
    uint16_t theta_half_steps;  /* slices each side of the predicted heading when
                                   searching heading; default 8: +-8.8 deg, the fewest
                                   whole 1.1 deg steps that cover the +-8.4 deg asked
                                   for; max 256 */
    hl_bam_t normal_gate;       /* pairs vote only if normals agree within this;
                                   default 30 deg (paper) */
    hl_mm_t blur_sigma_mm;      /* xy Gaussian blur; default 60 (the spread of echo-placed
                                   readings: about 40 mm of range noise and a few degrees
                                   of bearing); 0 = no blur */
    hl_bam_t blur_sigma_theta;  /* heading blur; default 0.75 deg; 0 = no blur */
    hl_mm_t peak_separation_mm; /* the "second peak" is the best cell at least this far
                                   from the best one; default 500 (the wild-error radius) */
    hl_mm_t prior_sigma_mm;     /* odometry prior (paper, section 9): votes attenuated by
                                   a Gaussian of the distance from the prediction, when a
                                   query asks for it; default 300 */
    hl_bam_t prior_sigma_theta; /* default 15 deg */
    uint32_t max_cells;         /* raster cells (nx * ny * nt) to allocate for,
                                   1..HL_LOC_MAX_CELLS; default 2^20 (10 MiB). A global search over a 10 m x 10 m map at
                                   24 mm needs 174k per heading; a +-1 m window with 17
                                   headings, 120k. Each raster side must also stay below
                                   2^21 mm. */
    hl_mm_t group_mm;           /* map vectors in one square of this side vote together,
                                   from their centroid, with the weight of how many pass
                                   the normal gate (vgroup.h in src/core): a dense map
                                   costs writes per occupied square, not per vector;
                                   0 = every vector votes alone (the paper, and the
                                   default: a sparse map gains nothing); else 8..1000;
                                   48 (two cells, votes move < 34 mm, inside the blur)
                                   for a laser's dense map */
    bool vote_once;             /* each reading votes at most once into any cell, however
                                   many map vectors put it there: a cell's votes count the
                                   readings that meet a surface under its pose, not the
                                   pairs, so a cluttered, much-mapped or many-walled place
                                   does not outvote the right one (the global search's
                                   coarse stage, reloc.h); costs 2 bytes a cell; default
                                   false (the paper's pair votes) */
    uint16_t reading_stride;    /* only readings 0, k, 2k, ... of a scan vote (1 = all,
                                   the default; 1..64): a laser's hundreds of readings
                                   pin the peak with a fraction of them, and the
                                   refinement (refine.h) still uses every one */
    uint32_t max_map_vectors;   /* largest map to accept; default 16384. hl_slam sets it
                                   to its map_capacity (slam.h) */
} hl_loc_params_t;

/** Fills @p p with the defaults above. */
void hl_loc_params_default(hl_loc_params_t *p);
/** Raster cells a local search with half-width @p window_mm needs (for max_cells). */
uint32_t hl_loc_cells_for_window(const hl_loc_params_t *p, hl_mm_t window_mm,
                                 bool search_theta);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_loc_params_error(const hl_loc_params_t *p);

typedef struct hl_loc_query {
    hl_pose_t predicted;    /* the window centre, and the centre heading of the slice */
    hl_mm_t window_mm;      /* half-width of the local xy window; 0 = global search over
                               the bounding box of the map vectors */
    bool search_theta;      /* false: one slice at predicted.theta (heading known) */
    bool use_prior;         /* attenuate votes with distance from the prediction */
} hl_loc_query_t;

/** The blurred vote surface of the last run, for figures and tests. */
typedef struct hl_loc_surface {
    const uint32_t *cells;  /* [it][iy][ix], blurred votes x 256 */
    const uint16_t *votes;  /* [it][iy][ix], raw votes */
    int32_t nx, ny, nt;
    hl_mm_t x0_mm, y0_mm;   /* corner of cell (0, 0) */
    hl_mm_t cell_mm;
    hl_bam_t theta0;        /* heading of slice 0 */
    hl_bam_t theta_step;
} hl_loc_surface_t;

typedef struct hl_localizer hl_localizer_t;

/** @return NULL if the parameters are invalid or memory is short. */
hl_localizer_t *hl_loc_create(const hl_loc_params_t *params);
/** Accepts NULL. */
void hl_loc_destroy(hl_localizer_t *loc);
const hl_loc_params_t *hl_loc_get_params(const hl_localizer_t *loc);
/** Bytes allocated by the localizer. */
size_t hl_loc_mem_bytes(const hl_localizer_t *loc);

/**
 * Localizes @p scan against @p n map vectors.
 * @return HL_OK; HL_ERR_EMPTY when the map or the scan's valid readings are empty or no
 *         vote landed (result->votes tells); HL_ERR_CAPACITY when the raster or the map
 *         exceeds what the localizer was created for; HL_ERR_RANGE for out-of-range
 *         input; HL_ERR_ARG for NULL.
 */
hl_status_t hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, const hl_loc_query_t *query,
                       hl_loc_result_t *result);

/** The surface of the last successful hl_loc_run. After a search the localizer ran on
 *  the tiles near its votes alone (a large raster without a prior, localize.c), the first
 *  call lays the blurred raster out, a pass over its cells. */
void hl_loc_get_surface(hl_localizer_t *loc, hl_loc_surface_t *out);

#ifdef __cplusplus
}
#endif
#endif
