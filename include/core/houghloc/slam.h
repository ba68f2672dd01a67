/*
 * slam.h - the tracker: the online cycle of the paper (sections 2 and 7), localize each
 * new scan against the map, then add it to the map at the computed pose; and, not in the
 * paper, the recovery of a robot whose pose is lost.
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
 * Two modes:
 *  - paper:    every localization is accepted and extends the map (the paper's method);
 *  - guarded:  the search is centred on the odometry prediction, and a pose is rejected
 *              when it lands farther than wild_mm from it, when its peak is not distinct
 *              (min_confidence, min_votes), or when its peak (before the prior) is below
 *              min_peak_ratio of the recent-peak average. A rejected scan falls back to
 *              the prediction and does not extend the map (the paper's section 9).
 * The recent-peak average moves a quarter of the way to each accepted peak and to the
 * geometric mean of itself and a rejected one, so a peak that falls and stays low (the
 * robot entering unmapped space) passes at the next scan when it fell by up to 16 times,
 * at the one after by up to 256. A scan with nothing to vote against is added to the map
 * at the prediction, as the first scan is: this is how the map follows the robot.
 *
 * Around the vote, in either mode when the parameters ask: readings moved to their
 * estimated echo bearings (echo.h; default on), surface normals fitted (normals.h; a
 * laser), the Hough pose polished (refine.h; default on). The scan added to the map is
 * the prepared one.
 *
 * Not in the paper, each off by default:
 *  - loop closure (close_loops): each stop is remembered (closure_stops of them); a stop
 *    that comes back near an earlier one is also matched against that stop's own map,
 *    every remembered stop is fitted to its steps and matches at once, and the map is
 *    drawn again at the fitted poses. Forgotten stops and a loaded map's vectors stay
 *    put; a restore, a reset or a pose set from outside starts the record afresh;
 *  - square walls (square_walls, with close_loops): in a building whose walls run along
 *    wall_axis and square to it, each stop's readings also tie its heading to the world
 *    in that fit. Leave it off where walls meet at other angles;
 *  - long drives (long_drive_mm): after such a drive the scan is also localized from the
 *    drive turned about the last estimate by +-1 .. +-long_drive_turns multiples of
 *    long_drive_turn, and a turned answer replaces the tracker's when the global search's
 *    judge (reloc.h) scores it 1.2 times as high and 3 more; 2 x long_drive_turns more
 *    localizations on such a scan only.
 * Why, and the measurements behind the defaults: docs/design/cycle.md,
 * docs/design/localizer.md, docs/design/loop-closure.md.
 */
#ifndef HOUGHLOC_SLAM_H
#define HOUGHLOC_SLAM_H

#include <stdbool.h>

#include "houghloc/export.h"
#include "houghloc/echo.h"
#include "houghloc/normals.h"
#include "houghloc/localize.h"
#include "houghloc/map.h"
#include "houghloc/refine.h"
#include "houghloc/reloc.h"
#include "houghloc/rng.h"

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
    HL_SLAM_LOST_ELSEWHERE = 1, /* the watch's global search (search_every) found the
                                   robot elsewhere, explaining the scan clearly better */
    HL_SLAM_LOST_DOUBTFUL = 2,  /* lost_after doubtful scans in a row */
} hl_slam_lost_why_t;

/* How the tracker found the robot again with a scan (hl_slam_step_t.found_how). */
typedef enum hl_slam_found_how {
    HL_SLAM_FOUND_NOT = 0,      /* it did not */
    HL_SLAM_FOUND_CONFIRMED = 1,/* the scan confirms the global search's candidate */
    HL_SLAM_FOUND_AGREES = 2,   /* the search puts the robot where tracking does */
    HL_SLAM_FOUND_TRACKED = 3,  /* a run of scans that tracking matched well */
} hl_slam_found_how_t;

/* The most turns of a long drive tried each way (long_drive_turns). */
#define HL_SLAM_MAX_DRIVE_TURNS 4

typedef struct hl_slam_params {
    hl_loc_params_t loc;        /* loc.max_map_vectors is not read: the slam's localizer
                                   is made for map_capacity vectors */
    uint32_t map_capacity;      /* vectors the map keeps, 1..HL_MAP_MAX_CAPACITY; the one
                                   bound on the map's size. Default 1500 (paper) */
    uint32_t map_per_place;     /* the map's density bound (map.h, hl_map_params_t):
                                   at most this many vectors of one map_square_mm square
                                   seen from one side; 0 = none (paper); default 0 */
    hl_mm_t map_square_mm;      /* default 50 */
    uint32_t cull_choices;      /* the map's evidence cull (map.h, hl_map_params_t):
                                   a full map drops the least confirmed of this many
                                   vectors drawn at random; 1 = uniform (paper); default 1 */
    hl_mm_t confirm_mm;         /* ... a new vector confirms an old one this close;
                                   default 100 */
    bool cull_crowded;          /* with cull_choices > 1: drop the most crowded of them
                                   instead (map.h, hl_map_params_t; needs
                                   map_per_place); default false */
    hl_mm_t crowd_square_mm;    /* ... crowding counted in squares of this side (0 or
                                   HL_MAP_MIN_SQUARE_MM..HL_MAP_MAX_SQUARE_MM); 0 (the
                                   default): the density square and the 8 around it */
    uint64_t seed;              /* map culling seed; default 1 */
    double heading_gain;        /* of an accepted localization's heading correction, the
                                   part taken (the rest stays with the odometry): a
                                   complementary filter for sensors whose heading is
                                   noisier than the odometry's over one step, such as a
                                   sonar ring; 0..1, default 1 (all of it) */
    bool guarded;               /* false = paper mode; default true */
    bool interpolate;           /* sub-cell interpolation; default true */
    bool use_prior;             /* odometry prior attenuation; default true */
    hl_mm_t window_mm;          /* local search half-width; 0 = global; default 1000 */
    bool search_theta;          /* default true */
    hl_mm_t wild_mm;            /* guarded: reject farther than this from the
                                   prediction; default 500 (the paper's wild error) */
    double min_confidence;      /* guarded: reject a peak less distinct; default 0.05 */
    uint32_t min_votes;         /* guarded: reject a peak with fewer raw votes in the
                                   whole raster; default 20 */
    double min_peak_ratio;      /* guarded: reject a peak (before the prior) lower than
                                   this fraction of the recent average (above); default
                                   0.25; 0 = off */
    bool echo_bearings;         /* move each reading to its estimated echo bearing
                                   (echo.h) before localizing and mapping; default true */
    hl_echo_params_t echo;
    bool fit_normals;           /* give each reading its surface's normal from its
                                   neighbours (normals.h; a laser) before localizing and
                                   mapping, after the echo bearings; default false */
    hl_normals_params_t normals;
    bool refine;                /* polish the Hough pose (refine.h); default true */
    bool refine_heading;        /* ... in heading too; default true */
    hl_refine_params_t refine_params;
    bool close_loops;           /* loop closure (not in the paper): match each stop against
                                   the earlier stops near it and fit every stop to all the
                                   matches, moving the map with them (below); default
                                   false */
    uint32_t closure_stops;     /* ... the stops it remembers, 2..4096; default 256 */
    hl_mm_t keyframe_mm;        /* ... a mapped scan is a stop of its own when the robot
                                   has moved this far since the last stop, 0..100000 ... */
    hl_bam_t keyframe_turn;     /* ... or turned this much; the scans between join the
                                   stop before them. Both 0 (the default): every mapped
                                   scan is a stop (a robot that sounds at stops) */
    double closure_match_weight; /* ... a match counts this share of a step in the fit,
                                   (0, 1]; default 1 (a continuous sensor's keyframes,
                                   joined by many scans' tracking, are surer of their
                                   steps than of a match against a few stops) */
    uint32_t closure_matches_per_scan; /* ... seek this many of a stop's matches a scan,
                                   in the scans after it, then fit in the next (a stop
                                   made meanwhile seeks none); 0 (the default): all at
                                   once, in the scan that made the stop */
    uint32_t closure_match_readings; /* ... a stop is matched with at most this many of its
                                   readings, taken evenly through its scan (a keyframe's
                                   holds up to 1,024, and a match's time grows with
                                   them); 0..1024, 0 (the default): all */
    hl_mm_t closure_redraw_mm;  /* ... with closure_redraw_readings, a fit is drawn only when
                                   it moves some stop more than this from where its vectors
                                   lie (or turns it as much at 5 m); 0..1000, 0 (the
                                   default): every fit */
    uint32_t closure_redraw_readings; /* ... after a fit, draw the map again aside, about
                                   this many readings a scan, and put it in place when
                                   done, so that no scan pays for a whole map; 0 (the
                                   default): at once, in the scan that fitted */
    bool square_walls;          /* ... and the building's walls run along wall_axis and
                                   square to it, so that each stop's readings tie its
                                   heading to the world (below); needs close_loops;
                                   default false */
    hl_bam_t wall_axis;         /* ... in the map's frame; default 0 */
    hl_mm_t long_drive_mm;      /* after a drive at least this long since the last scan,
                                   also try the drive turned about where it started and
                                   let the global search's judge pick (below); 0..1000000,
                                   0 (the default) = off */
    hl_bam_t long_drive_turn;   /* ... by multiples of this; default 6 degrees */
    uint16_t long_drive_turns;  /* ... up to this many each way,
                                   1..HL_SLAM_MAX_DRIVE_TURNS; default 2 */
    hl_reloc_params_t reloc;    /* the global search (reloc.h); its fine stage uses `loc` */
    /* Recovery (slam_lost.c): */
    int32_t lost_after;         /* doubtful scans in a row that make the tracker lost (a
                                   rejected scan, or an accepted one whose peak is below
                                   lost_peak_ratio of the recent average); it also ends
                                   the lost state after that many scans tracked well in a
                                   row; 0..1000000, 0 (the default): never lost by doubt */
    double lost_peak_ratio;     /* 0..1; default 0.5 */
    int32_t search_every;       /* the watch: while tracking, every this many scans, and
                                   on every scan tracking is in doubt about (after
                                   hl_slam_restore, each until the search puts the robot
                                   where tracking does, at most this many; one it cannot
                                   localize against a map that holds something; one
                                   rejected or with a peak below lost_peak_ratio of the
                                   recent average),
                                   also run the global search: a robot carried away is
                                   lost when it finds the scan clearly better explained
                                   elsewhere; 0..1000000, 0 (the default): never */
} hl_slam_params_t;

HL_API void hl_slam_params_default(hl_slam_params_t *p);

/** The params hl_slam_create makes its map with (capacity, seed, density bound, cull), for
 *  programs that build maps beside a tracker (hl_map_create_with). */
HL_API void hl_slam_map_params(const hl_slam_params_t *p, hl_map_params_t *out);

/** A one-line description of what is wrong, or NULL. */
HL_API const char *hl_slam_params_error(const hl_slam_params_t *p);

/**
 * @p scan as the slam's localizer and map see it: at its echo bearings when @p p asks
 * (into @p echoed), then with its surface normals when @p p asks (into @p fitted).
 * Returns the last of @p scan, @p echoed, @p fitted written; a step fails only for a scan
 * hl_scan_check refuses, and then leaves its input (the localizer refuses it itself).
 * The buffers are used only when their step is asked for (NULL is fine otherwise).
 */
HL_API const hl_scan_t *hl_slam_prepare(const hl_slam_params_t *p, const hl_scan_t *scan,
                                        hl_scan_t *echoed, hl_scan_t *fitted);

typedef struct hl_slam_step {
    hl_pose_t pose;             /* the estimate after this scan */
    hl_pose_t predicted;        /* last estimate moved by the odometry difference */
    hl_slam_status_t status;
    hl_loc_result_t loc;        /* valid when status is ACCEPTED or REJECTED_WILD */
    uint32_t added;             /* vectors added to the map */
    uint32_t loops;             /* matches with earlier stops taken (close_loops); when
                                   any, pose is the fitted one and the map has moved */
    bool turned;                /* the pose is a turned drive's (long_drive_mm), taken
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

/** @return NULL on invalid parameters or no memory. */
HL_API hl_slam_t *hl_slam_create(const hl_slam_params_t *p);
HL_API void hl_slam_destroy(hl_slam_t *s);   /* accepts NULL */

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
