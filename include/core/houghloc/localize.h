/*
 * localize.h - Hough-transform localization of one scan against a map of tangent
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
 */
#ifndef HOUGHLOC_LOCALIZE_H
#define HOUGHLOC_LOCALIZE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/export.h"
#include "houghloc/map.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

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
HL_API void hl_loc_params_default(hl_loc_params_t *p);
/** Raster cells a local search with half-width @p window_mm needs (for max_cells). */
HL_API uint32_t hl_loc_cells_for_window(const hl_loc_params_t *p, hl_mm_t window_mm,
                                        bool search_theta);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
HL_API const char *hl_loc_params_error(const hl_loc_params_t *p);

typedef struct hl_loc_query {
    hl_pose_t predicted;    /* the window centre, and the centre heading of the slice */
    hl_mm_t window_mm;      /* half-width of the local xy window; 0 = global search over
                               the bounding box of the map vectors */
    bool search_theta;      /* false: one slice at predicted.theta (heading known) */
    bool use_prior;         /* attenuate votes with distance from the prediction */
} hl_loc_query_t;

/*
 * Two measures of a peak. Before the prior: how well the scan matches the map at the
 * peak (peak) and at the best place at least peak_separation_mm away (second), in
 * blurred votes; the guard's peak-ratio test reads this (slam.h), so that a good match
 * is not taken for a bad one because the odometry drifted away from it. After the
 * prior: what the search maximised (score, second_score), which tells how distinct the
 * chosen pose is given the odometry; the confidence reads this. Without a prior the two
 * pairs are equal.
 */
typedef struct hl_loc_result {
    hl_pose_t pose;         /* interpolated peak */
    hl_pose_t cell_pose;    /* centre of the peak cell, no interpolation */
    int32_t ix, iy, it;     /* peak cell */
    uint32_t peak;          /* blurred votes x 256 in the peak cell, before the prior */
    uint32_t second;        /* the best cell >= peak_separation_mm from the peak cell in
                               x and y, same units, before the prior */
    uint32_t score;         /* the peak cell's score after the prior (the highest of the
                               raster), votes x 256; = peak without a prior */
    uint32_t second_score;  /* the best score >= peak_separation_mm from the peak cell,
                               after the prior; = second without a prior */
    uint32_t votes;         /* votes that landed in the raster */
    uint32_t pairs;         /* pairs that passed the normal gate */
} hl_loc_result_t;

/**
 * Confidence 0..1: 1 - second_score / score, how far the chosen pose stands out from the
 * best one at least peak_separation_mm away, after the prior when the query used one
 * (0 if there is no peak or @p r is NULL).
 */
HL_API double hl_loc_confidence(const hl_loc_result_t *r);

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
HL_API hl_localizer_t *hl_loc_create(const hl_loc_params_t *params);
/** Accepts NULL. */
HL_API void hl_loc_destroy(hl_localizer_t *loc);
HL_API const hl_loc_params_t *hl_loc_get_params(const hl_localizer_t *loc);
/** Bytes allocated by the localizer. */
HL_API size_t hl_loc_mem_bytes(const hl_localizer_t *loc);

/**
 * Localizes @p scan against @p n map vectors.
 * @return HL_OK; HL_ERR_EMPTY when the map or the scan's valid readings are empty or no
 *         vote landed (result->votes tells); HL_ERR_CAPACITY when the raster or the map
 *         exceeds what the localizer was created for; HL_ERR_RANGE for out-of-range
 *         input; HL_ERR_ARG for NULL.
 */
HL_API hl_status_t hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                              const hl_scan_t *scan, const hl_loc_query_t *query,
                              hl_loc_result_t *result);

/** The surface of the last successful hl_loc_run. */
HL_API void hl_loc_get_surface(const hl_localizer_t *loc, hl_loc_surface_t *out);

#ifdef __cplusplus
}
#endif
#endif
