/*
 * slam_internal.h (private) - the tracker's state, shared by its files: slam.c (tracking:
 * the stages of one scan), slam_lost.c (the recovery around it, and hl_slam_update) and
 * slam_closure.c (the loop-closure stage).
 */
#ifndef HOUGHLOC_CORE_SLAM_INTERNAL_H
#define HOUGHLOC_CORE_SLAM_INTERNAL_H

#include "houghloc-internal/closure.h"
#include "houghloc-internal/multiscan.h"
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

/* Searches made within one hl_slam_update, kept so that none is made twice with the same
 * inputs (the scan as prepared, the map, the parameters, and for the local search the
 * prediction): a local search made to confirm a candidate or to compare tracking with
 * the global search is the one tracking then takes, and the global search the watch made
 * is the one a scan that makes the tracker lost takes. Valid only while `active` (inside
 * hl_slam_update); dropped whenever the map may have changed (hl_slam_commit). */
typedef struct hl_slam_memo {
    bool active;
    bool have_local;
    hl_pose_t local_from;       /* the prediction it searched from */
    const hl_scan_t *local_scan; /* ... and the scan (the newest alone, or assembled) */
    hl_status_t local_status;
    hl_loc_result_t local_loc;
    hl_pose_t local_pose;       /* valid when local_status is HL_OK */
    bool have_search;           /* the global search of the scan alone */
    hl_status_t search_status;
    hl_reloc_result_t search;
} hl_slam_memo_t;

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
    hl_multiscan_t *multi;  /* sounding by motion (multiscan_mm): the scans not yet
                               drawn into the map */
    hl_scan_t *assembled;   /* ... the newest scan with them, as localized */
    hl_scan_t *kept_scans;  /* reloc.scans copies when it is above 1: the scans the
                               recovery's search takes together, as prepared */
    hl_scan_t *search_echoed, *search_fitted;   /* HL_RELOC_MAX_SCANS each, as echoed and
                               fitted: the scans of hl_slam_relocalize_scans prepared */
    uint64_t scans;         /* hl_slam_update calls taken (search_every counts them) */
    uint32_t unconfirmed;   /* after hl_slam_restore, the scans left in which the watch
                               searches every scan until its search puts the robot where
                               tracking does: the robot may have moved while nothing
                               watched (slam_lost.c); 0 otherwise */
    hl_slam_memo_t memo;
};

/** The squared distance between two poses' positions (mm^2). */
static inline int64_t hl_slam_dist2(hl_pose_t a, hl_pose_t b)
{
    int64_t dx = (int64_t)a.x_mm - b.x_mm, dy = (int64_t)a.y_mm - b.y_mm;
    return dx * dx + dy * dy;
}

/** The prediction: the last estimate moved by the odometry since (hl_pose_predict; the
 *  start pose before the first scan). @return false when it is out of range (@p out is
 *  then the last estimate). */
bool hl_slam_predict(const hl_slam_t *s, hl_pose_t odometry, hl_pose_t *out);

/** hl_slam_prepare of a scan already checked (its buffers as there). */
const hl_scan_t *hl_slam_prepare_valid(const hl_slam_params_t *p, const hl_scan_t *scan,
                                       hl_scan_t *echoed, hl_scan_t *fitted);

/** @p scan (checked) as the localizer and the map see it: hl_slam_prepare into the
 *  tracker's own buffers, which hold it until the next call. */
const hl_scan_t *hl_slam_ready(hl_slam_t *s, const hl_scan_t *scan);

/* Tracking's answer for one scan before it is committed (hl_slam_propose). */
typedef struct hl_slam_proposal {
    hl_slam_step_t step;    /* pose, predicted, status, loc, turned */
    hl_pose_t local;        /* the local search's pose (refined), before a turned drive;
                               the prediction when it found none */
    bool extend;            /* the scan goes into the map */
    uint32_t peak_avg;      /* the recent-peak average after it */
} hl_slam_proposal_t;

/**
 * Tracking's computing stages of @p ready (a scan hl_slam_ready made) from the last
 * estimate moved by @p odometry: predict, localize, guard. Changes nothing but the memo.
 * @return HL_OK with @p p to commit; an error when tracking cannot localize the scan
 *         (p->local still says where the local search put it).
 */
hl_status_t hl_slam_propose(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                            hl_slam_proposal_t *p);

/** Commits @p p, which hl_slam_propose made of @p ready at @p odometry: integrate,
 *  closure, the tracker's state; the step into @p out. On an error return nothing
 *  changed and @p out is not written. */
hl_status_t hl_slam_commit(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                           hl_slam_proposal_t *p, hl_slam_step_t *out);

/**
 * Tracking, the stages of one scan (localize, guard, integrate, closure) of @p ready from
 * the last estimate moved by @p odometry: hl_slam_propose, then hl_slam_commit. Either all
 * of it happens or nothing changes: on an error return the map, the estimate, the
 * odometry reference and the peak average are as they were, and @p out is not written.
 */
hl_status_t hl_slam_track(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                          hl_slam_step_t *out);

/** The heading an accepted localization of @p ready takes (slam_heading.c): @p found's,
 *  or part of the way to it from @p predicted (slam.heading_gain), then turned toward
 *  walls square to the map's (slam.wall_gain). */
hl_bam_t hl_slam_take_heading(const hl_slam_t *s, const hl_scan_t *ready, hl_bam_t predicted,
                              hl_bam_t found);

/** The tracker's local search of @p ready against its map from @p predicted (memoized
 *  within hl_slam_update). */
hl_status_t hl_slam_search_local(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t predicted,
                                 hl_loc_result_t *loc, hl_pose_t *pose);

/** The global search of @p count prepared scans (hl_reloc_run_scans, refined when the
 *  params ask); of @p ready alone (count 1) memoized within hl_slam_update. */
hl_status_t hl_slam_search_global(hl_slam_t *s, const hl_scan_t *const *ready,
                                  const hl_pose_t *odometry, uint32_t count,
                                  hl_reloc_result_t *out);

/** The global search's judge of @p ready at @p pose against the map. */
uint32_t hl_slam_judge_ready(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t pose);

/** The estimate moved to @p pose with @p odometry there (hl_slam_set_pose, but the
 *  recovery's state is left alone). */
void hl_slam_place(hl_slam_t *s, hl_pose_t pose, hl_pose_t odometry);

/** Hough, then the optional refinement, of @p scan (checked) against @p map (the slam's,
 *  or a loop closure's map of one earlier stop) from @p predicted; never memoized. */
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
