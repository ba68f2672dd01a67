/*
 * slam_params.h (internal) - the tracker's parameters as the core holds them: the values
 * of params.h's table (src/core/params_table.c names each field's key, range and
 * default), the stage modules' own params within, and the constants that were settings
 * once, each with its reason. The tracker (slam.c), the laboratory and the tests read and
 * change them here; a program goes through params.h.
 */
#ifndef HOUGHLOC_INTERNAL_SLAM_PARAMS_H
#define HOUGHLOC_INTERNAL_SLAM_PARAMS_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc-internal/echo.h"
#include "houghloc-internal/localize.h"
#include "houghloc-internal/map.h"
#include "houghloc-internal/normals.h"
#include "houghloc-internal/refine.h"
#include "houghloc-internal/reloc.h"
#include "houghloc/slam.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The guard (slam.guarded). Every study kept these, and none gave a reason to move them
 * (docs/design/expert-keys.md has the measurements): */
#define HL_SLAM_WILD_MM 500             /* reject farther than this from the prediction:
                                           the paper's wild error; 300 changed nothing */
#define HL_SLAM_MIN_CONFIDENCE 0.05     /* ... a peak less distinct, after the prior */
#define HL_SLAM_MIN_VOTES 20            /* ... fewer raw votes in the whole raster */
#define HL_SLAM_MIN_PEAK_RATIO 0.25     /* ... a peak, before the prior, below this share
                                           of the recent average: 0.3-0.5 broke some tours
                                           and mended others */
/* The recovery: an accepted peak below this share of the recent average is doubtful. */
#define HL_SLAM_LOST_PEAK_RATIO 0.5
/* Long drives: turned by multiples of 6 degrees, up to 2 each way (4-12 degrees were
 * within noise of each other on the tours; 3 and 4 turns only cost time). */
#define HL_SLAM_DRIVE_TURN_DEG 6
#define HL_SLAM_DRIVE_TURNS 2
/* Keyframes (keyframe_mm > 0) also start after this much turning: both continuous
 * profiles took 20 degrees, and no study moved it. */
#define HL_SLAM_KEYFRAME_DEG 20
/* Square walls run along the map frame's x axis and square to it: the map frame is the
 * start pose's, so a building at an angle to it is squared by the start heading. */
#define HL_SLAM_WALL_AXIS_DEG 0

typedef struct hl_slam_params {
    hl_loc_params_t loc;        /* loc.max_map_vectors is not read: the slam's localizer
                                   is made for map_capacity vectors */
    uint32_t map_capacity;      /* vectors the map keeps, 1..HL_MAP_MAX_CAPACITY; the one
                                   bound on the map's size */
    uint32_t map_per_place;     /* the map's density bound (hl_map_params_t): at most this
                                   many vectors of one map_square_mm square seen from one
                                   side; 0 = none (paper) */
    hl_mm_t map_square_mm;
    bool map_round_places;      /* ... its places round (hl_map_params_t) */
    uint32_t cull_choices;      /* the map's evidence cull (hl_map_params_t): a full map
                                   drops the least confirmed of this many vectors drawn
                                   at random; 1 = uniform (paper) */
    bool cull_crowded;          /* with cull_choices > 1: drop the most crowded of them
                                   instead (needs map_per_place) */
    hl_mm_t crowd_square_mm;    /* ... crowding counted in squares of this side; 0: the
                                   density square and the 8 around it */
    uint64_t seed;              /* map culling seed */
    double heading_gain;        /* of an accepted localization's heading correction, the
                                   part taken (the rest stays with the odometry): a
                                   complementary filter for sensors whose heading is
                                   noisier than the odometry's over one step, such as a
                                   sonar ring sounded often; 0..1 */
    double wall_gain;           /* square walls for tracking (walls.h): of the turn that
                                   puts an accepted scan's walls square to the map's, the
                                   part taken; 0 = off, 0..1 */
    bool guarded;               /* false = the paper's method: accept every pose */
    bool interpolate;           /* sub-cell interpolation */
    bool use_prior;             /* odometry prior attenuation */
    hl_mm_t window_mm;          /* local search half-width; 0 = global */
    bool echo_bearings;         /* move each reading to its estimated echo bearing
                                   (echo.h) before localizing and mapping */
    hl_echo_params_t echo;
    bool fit_normals;           /* give each reading its surface's normal from its
                                   neighbours (normals.h; a laser) before localizing and
                                   mapping, after the echo bearings */
    hl_normals_params_t normals;
    bool refine;                /* polish the Hough pose (refine.h) */
    bool refine_heading;        /* ... in heading too */
    hl_refine_params_t refine_params;
    bool close_loops;           /* loop closure (slam.h, closure.h) */
    uint32_t closure_stops;     /* ... the stops it remembers, 2..HL_CLOSURE_MAX_STOPS */
    hl_mm_t keyframe_mm;        /* ... a mapped scan is a stop of its own when the robot
                                   has moved this far since the last stop (or turned
                                   HL_SLAM_KEYFRAME_DEG); the scans between join the stop
                                   before them. 0: every mapped scan is a stop (a robot
                                   that sounds at stops) */
    bool closure_correlative;   /* ... matches by a correlative search over a region that
                                   grows with the path since the last match (corrmatch.h,
                                   hl_closure_seek) rather than the tracker's Hough vote */
    double closure_match_weight; /* ... a match counts this share of a step in the fit,
                                   (0, 1] */
    uint32_t closure_matches_per_scan; /* ... seek this many of a stop's matches a scan,
                                   in the scans after it, then fit in the next; 0: all at
                                   once, in the scan that made the stop */
    uint32_t closure_match_readings; /* ... a stop is matched with at most this many of its
                                   readings, taken evenly through its scan; 0: all */
    hl_mm_t closure_redraw_mm;  /* ... with closure_redraw_readings, a fit is drawn only when
                                   it moves some stop more than this from where its vectors
                                   lie (or turns it as much at 5 m); 0: every fit */
    hl_mm_t closure_redraw_stop_mm; /* ... and a fit that moves a sixteenth of the stops
                                   or fewer more than this (or turns them as much at 5 m)
                                   draws again only those and the newest, the others'
                                   vectors staying as they lie; 0: every stop */
    uint32_t closure_redraw_readings; /* ... after a fit, draw the map again aside, about
                                   this many readings a scan, and put it in place when
                                   done; 0: at once, in the scan that fitted */
    bool square_walls;          /* ... and the building's walls run along the map frame's
                                   axes, so that each stop's readings tie its heading to
                                   the world; needs close_loops */
    hl_mm_t multiscan_mm;       /* sounding by motion (multiscan.h): each scan is
                                   localized with the readings of the last this much
                                   travel, which go into the map only after it; 0 = off */
    hl_bam_t multiscan_turn;    /* ... or this much turning */
    hl_mm_t long_drive_mm;      /* after a drive at least this long since the last scan,
                                   also try the drive turned about where it started and
                                   let the global search's judge pick; 0 = off */
    hl_reloc_params_t reloc;    /* the global search (reloc.h); its fine stage uses `loc` */
    /* Recovery (slam_lost.c): */
    int32_t lost_after;         /* doubtful scans in a row that make the tracker lost (a
                                   rejected scan, or an accepted one whose peak is below
                                   HL_SLAM_LOST_PEAK_RATIO of the recent average); it also
                                   ends the lost state after that many scans tracked well
                                   in a row; 0: never lost by doubt */
    int32_t search_every;       /* while tracking, every this many scans also run the
                                   global search: a robot carried away is lost when it
                                   finds the scan clearly better explained elsewhere;
                                   0: never */
} hl_slam_params_t;

/** The defaults: params.h's table (hl_params_default). */
void hl_slam_params_default(hl_slam_params_t *p);

/** A one-line description of what is wrong, or NULL (the table's ranges and
 *  hl_params_check's rules, without the keys' names). */
const char *hl_slam_params_error(const hl_slam_params_t *p);

/** The params hl_slam_create makes its map with (capacity, seed, density bound, culls),
 *  for programs that build maps beside a tracker (hl_map_create_with). */
void hl_slam_map_params(const hl_slam_params_t *p, hl_map_params_t *out);

/** A tracker made with @p p as they are (hl_slam_create goes through here). NULL on
 *  invalid parameters (hl_slam_params_error) or no memory. */
hl_slam_t *hl_slam_create_with(const hl_slam_params_t *p);

/**
 * @p scan as the slam's localizer and map see it: at its echo bearings when @p p asks
 * (into @p echoed), then with its surface normals when @p p asks (into @p fitted).
 * Returns the last of @p scan, @p echoed, @p fitted written; a step fails only for a scan
 * hl_scan_check refuses, and then leaves its input (the localizer refuses it itself).
 * The buffers are used only when their step is asked for (NULL is fine otherwise).
 */
const hl_scan_t *hl_slam_prepare(const hl_slam_params_t *p, const hl_scan_t *scan,
                                 hl_scan_t *echoed, hl_scan_t *fitted);

#ifdef __cplusplus
}
#endif
#endif
