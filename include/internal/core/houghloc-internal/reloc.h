/*
 * reloc.h (internal) - global relocalization: where is the robot in a known map, with no idea of
 * its position or heading, from one scan (the kidnapped robot; not in the paper, which
 * searched a thin slice of headings around odometry).
 *
 * A full Hough search over every heading would cost hundreds of slices over the whole
 * map. Three stages keep it to a few dozen:
 *  1. headings: the normal gate makes heading partly separable. The circle is tiled with
 *     windows as wide as one coarse search; each is worth the highest value inside it of
 *     the circular correlation of two 256-bin histograms, the sensed normals (bearing +
 *     180 deg, robot frame) and the map's normals, smoothed: the headings that turn the
 *     scan's walls onto the map's. The best `headings` windows are searched (all of them,
 *     18 at the defaults, search every heading: a laser's normals are its beams'
 *     directions and tell little; a sonar's are its walls' normals and tell a lot);
 *  2. coarse positions: for each window, a Hough vote over the whole map's bounding box
 *     with coarse cells (coarse_cell_mm) and the window's headings (+-coarse_half_steps x
 *     coarse_theta_step); the best `peaks_per_heading` separate peaks of each become
 *     hypotheses, ranked by what they explain (below) within a coarse cell;
 *  3. fine poses: the best `hypotheses` of them are searched again with the tracking
 *     localizer's parameters in a small window (fine_window_mm, its heading slice).
 * Votes are a poor score across a whole map: a place crowded with map vectors collects
 * many for any heading. So each pose is judged by what it explains: the valid readings
 * that, placed at it, land within verify_mm of a map vector whose normal agrees within
 * the normal gate (a reading counts once, however many vectors crowd there).
 * The answer is the fine pose that explains most; the runner-up the best other one that
 * is distinct (at least distinct_mm away in position, or distinct_theta in heading). The
 * answer is "found" when it explains at least min_explained_pct of the readings and the
 * runner-up at most max_ratio of what it does; otherwise "ambiguous" (a symmetric
 * corridor, a scan that sees too little): say so rather than guess.
 *
 * Several scans (hl_reloc_run_scans): one robot's scans with the odometry between them,
 * searched together for the pose of the first. Stages 1 and 2 add up what the scans say
 * at one pose of the first: their normal histograms turned by the odometry's headings,
 * their coarse vote rasters moved by its translations (each scan voting with its own
 * headings turned by the odometry). Stage 3 searches each scan finely around where a
 * hypothesis puts it, alone (odometry errs by a few degrees over a turn), and the judge
 * adds up the readings explained at each scan's own pose. A place that explains one scan
 * by chance rarely explains the robot's next ones from half a metre away; the true place
 * explains them all.
 *
 * All memory is allocated by hl_reloc_create; hl_reloc_run allocates nothing. The
 * result depends only on the inputs (no randomness, no clock).
 */
#ifndef HOUGHLOC_INTERNAL_RELOC_H
#define HOUGHLOC_INTERNAL_RELOC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/localize.h"
#include "houghloc-internal/map.h"
#include "houghloc/reloc.h"
#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fixed (were settings; kept through every study of docs/results/relocalization.md):
 * the heading correlation's smoothing (a sonar normal is good to a few degrees), the
 * coarse slices (+-10 degrees in 2-degree steps: 18 windows tile the circle) and blur
 * (one coarse cell), the coarse peaks kept a window (fewer miss a place whose coarse peak
 * is lower than a crowded corner's), the fine window, what makes a runner-up distinct,
 * and the short-reading rule off (it helped one building and hurt two). */
#define HL_RELOC_HEADING_SMOOTH_DEG 4
#define HL_RELOC_COARSE_THETA_STEP_DEG 2
#define HL_RELOC_COARSE_HALF_STEPS 5
#define HL_RELOC_COARSE_BLUR_MM 100
#define HL_RELOC_PEAKS_PER_HEADING 8
#define HL_RELOC_FINE_WINDOW_MM 300
#define HL_RELOC_DISTINCT_MM 1000
#define HL_RELOC_DISTINCT_DEG 20
#define HL_RELOC_SHORT_MM 0

#define HL_RELOC_MAX_HEADINGS 64
#define HL_RELOC_MAX_PEAKS 32
#define HL_RELOC_MAX_HYPOTHESES 64
#define HL_RELOC_MAX_SCANS 4

typedef struct hl_reloc_params {
    uint16_t headings;          /* heading windows searched (stage 1), 1..64; default 12
                                   of the 18 (2 x 5 x 2 deg each) */
    hl_bam_t heading_smooth;    /* half-width of the correlation's triangular smoothing;
                                   default 4 deg (a sonar normal is good to a few
                                   degrees) */
    hl_mm_t coarse_cell_mm;     /* stage 2's cell, 10..1000; default 100 */
    hl_bam_t coarse_theta_step; /* default 2 deg */
    uint16_t coarse_half_steps; /* slices each side of a window's centre, 1..32; default
                                   5: +-10 deg */
    hl_mm_t coarse_blur_mm;     /* default 100 */
    hl_mm_t coarse_group_mm;    /* 0, or 8..1000: stage 2 votes with the map merged into
                                   squares this wide (localize.h, group_mm); default 0 */
    uint16_t coarse_stride;     /* stage 2 votes with readings 0, k, 2k, ... only (a laser's
                                   hundreds pin a coarse peak with a fraction; stage 3 and
                                   the judge use them all); 0 or 1 (the default): all */
    bool coarse_vote_once;      /* stage 2 counts readings, not pairs (localize.h,
                                   vote_once); default false */
    uint16_t peaks_per_heading; /* 1..32; default 8 (fewer miss a place whose coarse
                                   peak is lower than a crowded corner's) */
    uint32_t coarse_max_cells;  /* stage 2's raster budget (cells of one candidate's
                                   search, 10 bytes each); default 2^18 (2.6 MB). A
                                   map's bounding box of x * y metres needs
                                   x * y * 100 * 11 at the defaults: the lab (12 x 9 m)
                                   119k; a 50 x 50 m building wants coarse_cell_mm 200
                                   and 690k */
    uint16_t hypotheses;        /* refined in stage 3, 1..64; default 8 */
    hl_mm_t fine_window_mm;     /* half-width of stage 3's window; default 300; its
                                   raster (hl_loc_cells_for_window with the fine
                                   parameters, every heading) must fit HL_LOC_MAX_CELLS */
    hl_mm_t distinct_mm;        /* a runner-up is this far from the answer...; default
                                   1000 */
    hl_bam_t distinct_theta;    /* ... or this far in heading; default 20 deg */
    hl_mm_t verify_mm;          /* a reading is explained by a map vector this close
                                   whose normal agrees within the normal gate; default
                                   60 (the tracking blur); 1..1000 */
    hl_mm_t verify_along_mm;    /* ... measured across the vector's surface: the reading
                                   may lie up to this far along it (a tangent vector
                                   stands for a stretch of surface); default 60 */
    hl_bam_t judge_gate;        /* ... and whose normal agrees within this; default 90 deg
                                   (seen from the same side) */
    hl_mm_t short_mm;           /* a reading not explained whose beam stopped short of a
                                   mapped surface facing it, 300 mm to this far beyond its
                                   echo, counts against like one whose beam passed through
                                   a surface: something unmapped stood in front of a wall
                                   the map holds, which at a wrong pose is the rule and at
                                   the right one the exception (a laser);
                                   0 (the default) or 301..10000 */
    double max_ratio;           /* found when runner-up score <= max_ratio x score;
                                   default 0.7 (its choice:
                                   docs/design/relocalization.md) */
    double min_explained_pct;   /* found only when the answer explains at least this
                                   share of the valid readings; default 35 */
    double max_edge_ratio;      /* also found when the readings that favour the
                                   runner-up number at most this many times those that
                                   favour the answer (result's runner_edge, edge), and
                                   those are a tenth of the readings or more: the readings
                                   both explain tell nothing apart; 0..1, default 0 (off:
                                   the ratio of scores alone) */
    uint16_t scans;             /* the scans a lost tracker searches together (slam.h),
                                   1..HL_RELOC_MAX_SCANS; default 3 */
} hl_reloc_params_t;

/** Fills @p p with the defaults above. */
void hl_reloc_params_default(hl_reloc_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_reloc_params_error(const hl_reloc_params_t *p);

typedef struct hl_reloc hl_reloc_t;

/**
 * @param p     the search's own parameters.
 * @param fine  the tracking localizer's parameters, used by stage 3 (its max_cells is
 *              set for the fine window; max_map_vectors bounds the maps accepted).
 * @return NULL when a parameter is invalid or memory is short.
 */
hl_reloc_t *hl_reloc_create(const hl_reloc_params_t *p, const hl_loc_params_t *fine);
/** Accepts NULL. */
void hl_reloc_destroy(hl_reloc_t *r);
/** Bytes allocated. */
size_t hl_reloc_mem_bytes(const hl_reloc_t *r);

/**
 * Searches the whole map for the pose of @p scan, heading unknown.
 * @return HL_OK (result->found tells found from ambiguous); HL_ERR_EMPTY when the map
 *         or the scan's valid readings are empty or nothing voted; HL_ERR_CAPACITY when
 *         the map exceeds max_map_vectors or its bounding box the coarse raster budget;
 *         HL_ERR_RANGE for a bad scan; HL_ERR_ARG for NULL.
 */
hl_status_t hl_reloc_run(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                         const hl_scan_t *scan, hl_reloc_result_t *result);

/**
 * Searches the whole map for the pose of @p scans[0], heading unknown, with
 * @p scans[1 .. count - 1] taken by the same robot at the odometry poses
 * @p odometry[1 ..] (@p odometry[0] is the first scan's: only the moves between them
 * count). The result's scores and readings are summed over the scans; its poses are the
 * first scan's. count 1 is hl_reloc_run.
 * @return as hl_reloc_run; HL_ERR_ARG also for count outside 1..HL_RELOC_MAX_SCANS;
 *         HL_ERR_RANGE for a bad scan or an odometry move off the coordinate range.
 */
hl_status_t hl_reloc_run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                               const hl_scan_t *const *scans, const hl_pose_t *odometry,
                               uint32_t count, hl_reloc_result_t *result);

/**
 * The score hl_reloc_run gives a pose (readings explained less readings contradicted, see
 * above) for @p scan placed at @p pose: to weigh another pose, such as tracking's,
 * against the search's answer. @return the score; 0 for bad arguments or an empty map.
 */
uint32_t hl_reloc_judge(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                        const hl_scan_t *scan, hl_pose_t pose);
/** hl_reloc_judge at each of @p poses[0 .. count - 1] into @p scores (0 for a pose out of
 *  range, all 0 for bad arguments), hashing the map once. */
void hl_reloc_judge_poses(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                          const hl_scan_t *scan, const hl_pose_t *poses, uint32_t count,
                          uint32_t *scores);

#ifdef __cplusplus
}
#endif
#endif
