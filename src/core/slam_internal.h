/*
 * slam_internal.h (private) - the tracker's state, shared by its files: slam.c (tracking:
 * the stages of one scan), slam_lost.c (the recovery around it, and hl_slam_update) and
 * slam_closure.c (the loop-closure stage).
 */
#ifndef HOUGHLOC_CORE_SLAM_INTERNAL_H
#define HOUGHLOC_CORE_SLAM_INTERNAL_H

#include "houghloc-internal/closure.h"
#include "houghloc-internal/slam_params.h"
#include "houghloc-internal/slam_search.h"
#include "houghloc/slam.h"

/* The matches a stop seeks, when they are spread over the scans that follow it
 * (closure_matches_per_scan). */
typedef struct hl_slam_matching {
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES];    /* the candidates, oldest first */
    uint32_t n, next;       /* how many, and the next to localize against */
    uint32_t query;         /* the stop they are for */
    uint32_t taken;         /* matches taken so far */
    bool fit_due;           /* all sought, some taken: the next scan fits */
} hl_slam_matching_t;

/* The recovery's state (slam_lost.c). */
typedef struct hl_slam_recovery {
    bool lost;
    uint32_t epoch;             /* times lost was entered */
    int32_t doubtful_run;       /* doubtful tracked scans in a row */
    int32_t accepted_run;       /* ... and well-matched ones while lost */
    bool have_candidate;        /* the global search found this, to be confirmed */
    hl_pose_t candidate, candidate_odometry;
    uint32_t kept;              /* lost scans kept for the search (kept_scans), oldest
                                   first, each apart from the one before */
    hl_pose_t kept_odometry[HL_RELOC_MAX_SCANS];
} hl_slam_recovery_t;

struct hl_slam {
    hl_slam_params_t p;
    hl_map_t *map;
    hl_localizer_t *loc;
    bool started;       /* a scan has been seen since the last reset */
    hl_pose_t pose;     /* the last estimate (or the start pose) */
    hl_pose_t odom;     /* the odometry that went with it */
    uint32_t peak_avg;  /* average of recent peaks (votes x 256, before the prior), 0 = none
                           yet: tracked_peak */
    hl_scan_t *echoed;  /* the scan at its echo bearings, when the params ask for it */
    hl_scan_t *fitted;  /* ... with its surface normals, when the params ask for them */
    hl_refiner_t *refiner;  /* when the params ask for refinement */
    hl_reloc_t *reloc;      /* the global search (hl_slam_relocalize) */
    hl_closure_t *closure;  /* loop closure, when the params ask for it */
    hl_map_t *shadow;       /* ... the map drawn again aside (closure_redraw_readings) */
    hl_slam_matching_t matching;
    hl_slam_recovery_t recovery;
    hl_scan_t *kept_scans;  /* reloc.scans copies when it is above 1: the scans the
                               recovery's search takes together */
    hl_scan_t *search_echoed, *search_fitted;   /* HL_RELOC_MAX_SCANS each, as echoed and
                               fitted: the scans of hl_slam_relocalize_scans prepared */
    uint64_t scans;         /* hl_slam_update calls taken (search_every counts them) */
};

/** The squared distance between two poses' positions (mm^2). */
static inline int64_t hl_slam_dist2(hl_pose_t a, hl_pose_t b)
{
    int64_t dx = (int64_t)a.x_mm - b.x_mm, dy = (int64_t)a.y_mm - b.y_mm;
    return dx * dx + dy * dy;
}

/**
 * Tracking, the stages of one scan (prepare, localize, guard, integrate, closure) from
 * the last estimate moved by @p odometry. Either all of it happens or nothing changes:
 * on an error return the map, the estimate, the odometry reference and the peak average
 * are as they were, and @p out is not written.
 */
hl_status_t hl_slam_track(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry,
                          hl_slam_step_t *out);

/** The estimate moved to @p pose with @p odometry there (hl_slam_set_pose, but the
 *  recovery's state is left alone). */
void hl_slam_place(hl_slam_t *s, hl_pose_t pose, hl_pose_t odometry);

/** Hough, then the optional refinement, of @p scan against @p map (the slam's, or a loop
 *  closure's map of one earlier stop) from @p predicted. */
hl_status_t hl_slam_localize_in(hl_slam_t *s, const hl_map_t *map, const hl_scan_t *scan,
                                hl_pose_t predicted, hl_loc_result_t *loc, hl_pose_t *pose);

/** Before a scan mapped at @p pose goes into the map: whether it is a stop of its own
 *  (closure.h, keyframes), and the map's stamp set for it. */
bool hl_slam_closure_stamp(hl_slam_t *s, hl_pose_t pose);

/**
 * Loop closure's stage of a scan (after the map took it): @p mapped (NULL if the scan was
 * not mapped) recorded as a new stop (@p stop) or joined to the last, rng_before the map's
 * culling generator before it; then the matching, fit and redraw due, at once or a share
 * a scan. *@p pose moves with a fit put in place. @return the matches taken.
 */
uint32_t hl_slam_closure_stage(hl_slam_t *s, const hl_scan_t *mapped, bool stop,
                               hl_rng_t rng_before, hl_pose_t *pose);

/** Forgets the record and any matching or redraw under way. */
void hl_slam_closure_reset(hl_slam_t *s);

#endif
