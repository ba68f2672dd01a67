/*
 * slam.h - the tracker: the online cycle of the paper (sections 2 and 7), localize each
 * new scan against the map, then add it to the map at the computed pose; and, not in the
 * paper, the recovery of a robot whose pose is lost. Its settings are params.h's table.
 *
 * One call, hl_slam_update, is the whole cycle of one scan, in stages (src/core/slam.c):
 * prepare (echo bearings, surface normals), localize (the Hough vote around the odometry's
 * prediction, refined), guard (accept or reject), integrate (the scan into the map at the
 * pose, culled), closure (loop closure's record, matches, fit and redraw); and around
 * them the recovery (src/core/slam_lost.c), which decides when the robot is lost, searches
 * the whole map for it while it is, and confirms what the search finds. Its answer is one
 * status, hl_slam_status_t, and the global search's fields when one ran.
 *
 * The cycle is one pass: the scan is checked and prepared once, the prediction has one
 * definition (hl_pose_predict), and no search runs twice with the same inputs within a
 * scan (tracking's local search, computed before the recovery decides, is the one it
 * compares and the one committed).
 *
 * Two methods (slam.guarded):
 *  - paper:    every localization is accepted and extends the map (the paper's method,
 *              slam.profile = paper);
 *  - guarded:  the search is centred on the odometry prediction, and a pose is rejected
 *              when it lands farther than the paper's wild error (500 mm) from it, when
 *              its peak is not distinct, or when its peak (before the prior) is below a
 *              quarter of the recent-peak average. A rejected scan falls back to the
 *              prediction and does not extend the map (the paper's section 9).
 * The recent-peak average moves a quarter of the way to each accepted peak and to the
 * geometric mean of itself and a rejected one, so a peak that falls and stays low (the
 * robot entering unmapped space) passes at the next scan when it fell by up to 16 times,
 * at the one after by up to 256. A scan with nothing to vote against is added to the map
 * at the prediction, as the first scan is: this is how the map follows the robot.
 *
 * Around the vote, when the parameters ask: readings moved to their estimated echo
 * bearings (slam.echo_bearings, default on), surface normals fitted (slam.fit_normals; a
 * laser), the Hough pose polished (slam.refine, default on). The scan added to the map is
 * the prepared one.
 *
 * Not in the paper, each off by default:
 *  - loop closure (slam.close_loops): each stop is remembered; a stop that comes back
 *    near an earlier one is also matched against that stop's own map, every remembered
 *    stop is fitted to its steps and matches at once, and the map is drawn again at the
 *    fitted poses. Forgotten stops and a loaded map's vectors stay put; a restore, a reset
 *    or a pose set from outside starts the record afresh;
 *  - square walls (slam.square_walls, with loop closure): in a building whose walls run
 *    along the map frame's axes, each stop's readings also tie its heading to the world
 *    in that fit. Leave it off where walls meet at other angles;
 *  - long drives (slam.long_drive_mm): after such a drive the scan is also localized from
 *    the drive turned about the last estimate by +-6 and +-12 degrees, and a turned
 *    answer replaces the tracker's when the global search's judge scores it 1.2 times as
 *    high and 3 more.
 * The recovery (slam.lost_after, slam.search_every) is on by default.
 *
 * Ownership: hl_slam_create allocates everything the tracker uses; hl_slam_update
 * allocates nothing but what loop closure's fit asks of its solver (docs/design/
 * loop-closure.md). The map (hl_slam_map) is the tracker's. One tracker is used by one
 * thread at a time; trackers are independent.
 * Why, and the measurements behind the defaults: docs/design/cycle.md,
 * docs/design/localizer.md, docs/design/loop-closure.md; the API: docs/design/api.md.
 */
#ifndef HOUGHLOC_SLAM_H
#define HOUGHLOC_SLAM_H

#include <stdbool.h>

#include "houghloc/export.h"
#include "houghloc/localize.h"
#include "houghloc/map.h"
#include "houghloc/params.h"
#include "houghloc/reloc.h"
#include "houghloc/rng.h"
#include "houghloc/scan.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What became of a scan: the pose it gives, and whether the map took it. */
typedef enum hl_slam_status {
    HL_SLAM_ACCEPTED = 0,       /* localized; the map took the scan */
    HL_SLAM_REJECTED_WILD = 1,  /* localized, but the guard refused the pose: the estimate
                                   is the prediction, the map did not take the scan */
    HL_SLAM_ODOMETRY_ONLY = 2,  /* nothing to localize against (an empty or unmapped
                                   place: the map took the scan at the prediction), or the
                                   scan could not be localized (an error return) */
    HL_SLAM_RELOCALIZED = 3,    /* the global search found the robot, lost or carried
                                   away, at the step's pose; the next scan must confirm it
                                   before tracking goes on from there */
    HL_SLAM_LOST = 4,           /* lost, and the global search found nothing that stands
                                   out: the scan is tracked as usual (the robot may only
                                   have entered unmapped space), so the pose is tracking's
                                   (the prediction when tracking rejected the scan) and a
                                   scan tracking accepted extends the map; a run of
                                   well-tracked scans ends the lost state */
} hl_slam_status_t;

/* Why the tracker became lost with a scan (hl_slam_step_t.lost_why). */
typedef enum hl_slam_lost_why {
    HL_SLAM_LOST_NOT = 0,       /* it did not */
    HL_SLAM_LOST_ELSEWHERE = 1, /* the watch's global search (slam.search_every) found the
                                   robot elsewhere, explaining the scan clearly better */
    HL_SLAM_LOST_DOUBTFUL = 2,  /* slam.lost_after doubtful scans in a row */
} hl_slam_lost_why_t;

/* How the tracker found the robot again with a scan (hl_slam_step_t.found_how). */
typedef enum hl_slam_found_how {
    HL_SLAM_FOUND_NOT = 0,      /* it did not */
    HL_SLAM_FOUND_CONFIRMED = 1,/* the scan confirms the global search's candidate */
    HL_SLAM_FOUND_AGREES = 2,   /* the search puts the robot where tracking does */
    HL_SLAM_FOUND_TRACKED = 3,  /* a run of scans that tracking matched well */
} hl_slam_found_how_t;

typedef struct hl_slam_step {
    hl_pose_t pose;             /* the estimate after this scan */
    hl_pose_t predicted;        /* last estimate moved by the odometry difference */
    hl_slam_status_t status;
    hl_loc_result_t loc;        /* valid when status is ACCEPTED or REJECTED_WILD */
    uint32_t added;             /* vectors added to the map */
    uint32_t loops;             /* matches with earlier stops taken (slam.close_loops); when
                                   any, pose is the fitted one and the map has moved */
    bool turned;                /* the pose is a turned drive's (slam.long_drive_mm), taken
                                   over the tracker's own by the judge, not the guard */
    /* The global search, when status is RELOCALIZED or LOST: its answer and runner-up
     * (zero when it had nothing to search) */
    hl_reloc_result_t search;
    /* Recovery, for the caller's log: */
    hl_slam_lost_why_t lost_why;    /* the tracker became lost with this scan ... */
    int32_t doubtful_run;           /* ... after this many doubtful scans (DOUBTFUL) */
    hl_pose_t tracked;              /* ... tracking's pose, and its judge's score, */
    uint32_t tracked_score;         /*     that the search's answer beat (ELSEWHERE) */
    hl_slam_found_how_t found_how;  /* the tracker found the robot again with this scan */
    bool dropped_candidate;         /* the scan did not confirm the last search's answer */
    bool searched_lost;             /* the global search ran because the tracker is lost
                                       (also when it became lost with this scan) ... */
    hl_status_t search_status;      /* ... and returned this (HL_OK: see search) */
    bool watched;                   /* the watch (search_every) ran the global search on
                                       this scan while tracking */
} hl_slam_step_t;

typedef struct hl_slam hl_slam_t;

/**
 * A tracker with the parameters @p p (params.h; copied: @p p may go after the call),
 * its map empty, its first scan to be placed at the origin (hl_slam_reset).
 * @return NULL when @p p fails hl_params_check or memory is short.
 */
HL_API hl_slam_t *hl_slam_create(const hl_params_t *p);
/** Frees the tracker and its map. Accepts NULL. */
HL_API void hl_slam_destroy(hl_slam_t *s);

/** Starts over: empty map, the next scan is at @p start. */
HL_API void hl_slam_reset(hl_slam_t *s, hl_pose_t start);

/**
 * The whole cycle of one scan taken at @p odometry (the base's dead-reckoned pose when
 * the scan was taken): tracking (predict, localize, accept or reject, extend the map,
 * close loops) while the tracker knows where the robot is; while it is lost, the global
 * search and the confirmation of its answer (above). @p out says what became of the scan.
 * @return HL_OK; HL_ERR_ARG for NULL; HL_ERR_RANGE for a scan hl_scan_check refuses or
 *         odometry out of range (nothing changes; @p out holds the last estimate, or the
 *         prediction, as ODOMETRY_ONLY). Another error means tracking could not localize
 *         the scan (a prediction or a pose out of range, a map too wide for the
 *         localizer's raster): the map, the estimate, the odometry reference and the peak
 *         average are as they were, @p out holds the prediction as ODOMETRY_ONLY, and the
 *         recovery counts the scan as one that was not doubtful.
 */
HL_API hl_status_t hl_slam_update(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry,
                                hl_slam_step_t *out);

/** The tracker's map (map.h): the tracker's own, valid until hl_slam_destroy. */
HL_API hl_map_t *hl_slam_map(hl_slam_t *s);

/** Whether the tracker is lost (searching the whole map with each scan). */
HL_API bool hl_slam_lost(const hl_slam_t *s);
/** How many times it became lost since it was created (a robot sounds again for each). */
HL_API uint32_t hl_slam_lost_epoch(const hl_slam_t *s);
/** Makes the tracker lost now (an operator who knows the robot was moved): the next scans
 *  search the whole map. */
HL_API void hl_slam_lose(hl_slam_t *s);
/** Ends the lost state without a pose found: tracking goes on from the estimate (a robot
 *  that cannot move to see more). Nothing happens when it is not lost. */
HL_API void hl_slam_stop_searching(hl_slam_t *s);

/**
 * Moves the estimate to @p pose and takes @p odometry as the base's odometry there
 * (an operator placing the robot by hand); the tracker is no longer lost. The map is
 * kept. Before the first scan this sets the start pose instead, and the first scan's
 * odometry is still the reference.
 * @return HL_ERR_RANGE when a position is out of range (nothing changes).
 */
HL_API hl_status_t hl_slam_set_pose(hl_slam_t *s, hl_pose_t pose, hl_pose_t odometry);

/** The current estimate (the start pose before the first scan). */
HL_API hl_pose_t hl_slam_pose(const hl_slam_t *s);

/**
 * Everything besides the map's vectors that the next hl_slam_update depends on: with it
 * and the vectors, a restarted process continues exactly as this one would (but for
 * loop closure's record of stops, which a restore starts afresh).
 */
typedef struct hl_slam_state {
    bool started;           /* a scan has been integrated since the last reset */
    hl_pose_t pose;         /* the last estimate, or the start pose */
    hl_pose_t odom;         /* the odometry that went with it */
    uint32_t peak_avg;      /* recent peak average (guarded mode), votes x 256, before
                               the prior; 0 = none yet */
    uint64_t map_version;   /* 0..HL_COUNT_MAX (count.h) */
    hl_rng_t cull_rng;      /* the map's culling generator */
} hl_slam_state_t;

HL_API void hl_slam_get_state(const hl_slam_t *s, hl_slam_state_t *out);

/**
 * Replaces the map and the state with a saved one. The vectors are checked (count at
 * most the map's capacity, every field in range) before anything changes.
 * @return HL_OK; HL_ERR_CAPACITY when @p n exceeds the capacity; HL_ERR_RANGE for a
 *         vector or pose out of range, or a map version above HL_COUNT_MAX. On error
 *         nothing changes.
 */
HL_API hl_status_t hl_slam_restore(hl_slam_t *s, const hl_slam_state_t *state,
                                   const hl_vector_t *vectors, uint32_t n);

#ifdef __cplusplus
}
#endif
#endif
