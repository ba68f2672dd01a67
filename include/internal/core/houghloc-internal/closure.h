/*
 * closure.h (private) - loop closure for the slam (slam.h, slam.close_loops): a record of
 * the last stops (pose and the scan as mapped), the earlier stops each new one should be
 * matched against, and the fit of every stop to its steps and matches (posegraph.h),
 * after which the map is drawn again at the fitted poses (map.h, stamps).
 *
 * Not in the paper: its tracker puts every localization's error into the map the next
 * scan is matched against, and nothing takes it back. Here, when the robot comes back
 * within HL_CLOSURE_RADIUS_MM of a stop made at least HL_CLOSURE_GAP stops before, the new
 * scan is matched against that stop and its neighbours alone, and all the stops are
 * fitted to all such matches at once. A continuous sensor's keyframes are matched instead
 * by a correlative search of the region their drift allows (hl_closure_seek, corrmatch.h),
 * held until all of a keyframe's are found and taken when two agree (hl_closure_settle).
 * The study and the figures behind the constants below: docs/design/loop-closure.md.
 *
 * The record holds `stops` stops (each with its scan: about 12 KB a stop); when full, the
 * oldest is forgotten with its matches, and the oldest left is held where it is. Vectors
 * of forgotten stops stay in the map where they are (a redraw starts their evidence
 * counts again, map.h's hl_map_restore).
 * Memory: create only.
 */
#ifndef HOUGHLOC_CORE_CLOSURE_H
#define HOUGHLOC_CORE_CLOSURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc-internal/corrmatch.h"
#include "houghloc-internal/localize.h"
#include "houghloc-internal/map.h"
#include "houghloc/rng.h"
#include "houghloc/scan.h"

/* Which stops are matched, and when a match counts. */
#define HL_CLOSURE_GAP 5            /* stops between a stop and those it is matched with */
#define HL_CLOSURE_RADIUS_MM 1500   /* ... whose poses lie this near */
#define HL_CLOSURE_SIDE 1           /* the matched stop's neighbours drawn with it */
#define HL_CLOSURE_MAX_MATCHES 16   /* matches sought a stop, oldest stops first */
/* ... and taken at most, the first found (so with the oldest stops): each stop adds at
 * most nine edges to the graph, its step and its matches, so that the edges grow with
 * the stops alone. On hl-bench-posegraph's corridor of 4,096 stops (each near dozens of
 * earlier ones) that halves the edges against taking all 16; on the real buildings the
 * laser keeps its error (taking 4 cost freiburg-101 a centimetre)
 * (docs/results/pose-graph-solver.md). */
#define HL_CLOSURE_MAX_TAKEN 8
#define HL_CLOSURE_MIN_CONFIDENCE 0.3 /* a match's peak at least this distinct
                                       (hl_loc_confidence), far above the guard's 0.05 as
                                       a match moves every stop */
/* The fit. A match is weighed down by a Cauchy kernel (posegraph.h), so one that
 * disagrees with the rest bends the fit little and the gate can be wide. */
#define HL_CLOSURE_GATE_MM 500      /* a match moving the stop farther is not taken ... */
#define HL_CLOSURE_GATE_DEG 8.0     /* ... nor one turning it more */
#define HL_CLOSURE_KERNEL 1.0       /* a match's Cauchy kernel, in standard deviations */
#define HL_CLOSURE_SIGMA_MM 50.0    /* every step and match: one localization's error */
#define HL_CLOSURE_SIGMA_DEG 1.5
#define HL_CLOSURE_OUTLIER 3.0      /* a match this many sigmas off the fit is dropped */
#define HL_CLOSURE_MAX_STOPS 4096

/* The correlative search (slam.closure_correlative, corrmatch.h): its region is the
 * drift the tracking may have gathered since the last match taken, so that it grows with
 * the path driven since then (the graph's own uncertainty, as the steps between add it
 * up), and the candidates are the stops within HL_CLOSURE_RADIUS_MM of that region. */
#define HL_CLOSURE_SEARCH_MM 300.0          /* +- in x and y, just after a match ... */
#define HL_CLOSURE_SEARCH_GROWTH 0.05       /* ... and a twentieth of the path since */
#define HL_CLOSURE_SEARCH_MAX_MM 3000.0
#define HL_CLOSURE_SEARCH_DEG 3.0           /* +- in heading, just after a match ... */
#define HL_CLOSURE_SEARCH_DEG_PER_M 0.5     /* ... and this a metre driven since */
#define HL_CLOSURE_SEARCH_MAX_DEG 20.0
#define HL_CLOSURE_CORR_MIN_SCORE 0.4       /* a match's points at least this near the
                                               submap's on average (corrmatch.h) ... */
#define HL_CLOSURE_CORR_RUNNER_UP 0.9       /* ... and the best pose elsewhere in the region
                                               at most this share of its score */
#define HL_CLOSURE_CORR_DISTINCT_MM 250.0   /* elsewhere: this far from it, ... */
#define HL_CLOSURE_CORR_DISTINCT_DEG 5.0    /* ... or turned this much */
#define HL_CLOSURE_CORR_AGREEING 2          /* and at least this many of a stop's matches
                                               put it at one place in the map: */
#define HL_CLOSURE_CORR_AGREE_MM 150.0      /* ... within this */
#define HL_CLOSURE_CORR_AGREE_DEG 2.0       /* ... and this */
#define HL_CLOSURE_CORR_POLISH_MM 100       /* the tracker's search polishes a match found
                                               when it lands this near it */

/* Square walls (hl_closure_square_walls). A stop's readings, their normals folded four
 * times round (a wall and the walls square to it alike), point along the building's axis
 * in the robot's frame: with the stop's heading, a heading of the stop against the
 * world, good to within a quarter turn. Its error grows as the folded normals' mean
 * resultant length R falls (corners and clutter), so each stop's heading is weighed with
 * a sigma of HL_CLOSURE_WALL_SIGMA_R / R degrees, within the bounds below (no kernel). */
#define HL_CLOSURE_WALL_SIGMA_R 0.5
#define HL_CLOSURE_WALL_SIGMA_MIN_DEG 1.5
#define HL_CLOSURE_WALL_SIGMA_MAX_DEG 7.5
#define HL_CLOSURE_WALL_MIN_READINGS 8  /* a stop with fewer says nothing of the walls ... */
#define HL_CLOSURE_WALL_MIN_R 0.1       /* ... nor one whose R is less (its heading is
                                           near a uniform spread's) */

typedef struct hl_closure hl_closure_t;

/** A record of @p stops stops (2..HL_CLOSURE_MAX_STOPS), each matched against maps of up
 *  to @p map_capacity vectors. NULL on a bad size or no memory. */
hl_closure_t *hl_closure_create(uint32_t stops, uint32_t map_capacity, uint64_t seed);
void hl_closure_destroy(hl_closure_t *c);   /* accepts NULL */
size_t hl_closure_mem_bytes(const hl_closure_t *c);

/** Tells the fit that the building's walls run along @p axis_rad and square to it, so
 *  that each stop's readings give a heading of its own against the world (above): what
 *  keeps a map from turning as a whole about its first stop, which only the first
 *  sounding ties to the world otherwise. For stops recorded from now on. */
void hl_closure_square_walls(hl_closure_t *c, double axis_rad);

/** Each match counts @p weight (0..1] of a step in the fits (hl_posegraph_weigh_matches).
 *  @return false on a weight out of range. */
bool hl_closure_weigh_matches(hl_closure_t *c, double weight);

/** Forgets every stop (a new map, or a pose set from outside: no step joins them). */
void hl_closure_reset(hl_closure_t *c);

/** The stamp the next recorded stop's vectors are to carry (hl_map_set_stamp). */
uint32_t hl_closure_next_stamp(const hl_closure_t *c);

/** Records the next stop: @p placed, the scan as the map saw it, taken at @p pose, drawn
 *  into the map when its culling generator was @p rng_before. The step from the stop
 *  before becomes part of the fit. */
void hl_closure_record(hl_closure_t *c, const hl_scan_t *placed, hl_pose_t pose,
                       hl_rng_t rng_before);

/** Whether a scan mapped at @p pose should be a stop of its own (hl_closure_record) rather
 *  than join the newest stop (hl_closure_append): the first, or one at least @p mm from
 *  the newest stop or turned at least @p turn from it. A robot that scans continuously
 *  makes its stops this way (keyframes); with both 0, every scan is a stop (a robot that
 *  sounds at stops). */
bool hl_closure_is_stop(const hl_closure_t *c, hl_pose_t pose, hl_mm_t mm, hl_bam_t turn);

/** Joins @p placed, mapped at @p pose, to the newest stop: its readings go into the
 *  stop's scan, in the stop's frame, as far as the scan has room (HL_SCAN_MAX_READINGS),
 *  so that a redraw draws them again with the stop. Nothing without a stop. */
void hl_closure_append(hl_closure_t *c, const hl_scan_t *placed, hl_pose_t pose);

/** The newest stop's stamp (its vectors' and those of the scans joined to it). */
uint32_t hl_closure_newest_stamp(const hl_closure_t *c);

/** Where the newest stop's vectors lie in the map: its recorded pose, its fitted one once
 *  a fit is drawn. */
hl_pose_t hl_closure_newest(const hl_closure_t *c);

/** The earlier stops (their stamps, oldest first, at most @p max) that the stop stamped
 *  @p query should be matched against. @return how many (0 if it is not recorded). */
uint32_t hl_closure_candidates(const hl_closure_t *c, uint32_t query, uint32_t *stamps,
                               uint32_t max);

/** As hl_closure_candidates, the stops within @p radius_mm. */
uint32_t hl_closure_candidates_within(const hl_closure_t *c, uint32_t query, double radius_mm,
                                      uint32_t *stamps, uint32_t max);

/** The region a correlative search for stop @p query's matches covers (+- @p mm in x and
 *  y, +- @p rad in heading): HL_CLOSURE_SEARCH_* from the path driven since the newest
 *  stop a match was taken for. */
void hl_closure_search_region(const hl_closure_t *c, uint32_t query, double *mm, double *rad);

/** The points of the stop stamped @p stamp and its neighbours (as hl_closure_submap's),
 *  at their places in the map, into @p out (at most @p max). @return how many. */
uint32_t hl_closure_submap_points(const hl_closure_t *c, uint32_t stamp, uint32_t query,
                                  hl_corr_point_t *out, uint32_t max);

/** A map of the stop stamped @p stamp and its neighbours at their poses in the map (those
 *  at least HL_CLOSURE_GAP before the stop @p query, the one to be matched), valid until
 *  the next call; NULL if either is not recorded. */
const hl_map_t *hl_closure_submap(hl_closure_t *c, uint32_t stamp, uint32_t query);

/** The scan of the stop stamped @p stamp as recorded (with the scans joined to it), and
 *  where it lies in the map; NULL and the origin if it is not recorded. */
const hl_scan_t *hl_closure_scan(hl_closure_t *c, uint32_t stamp);
hl_pose_t hl_closure_pose(const hl_closure_t *c, uint32_t stamp);

/** The scan of the stop stamped @p stamp thinned to @p max_readings (0: all), readings
 *  taken evenly through it, for matching: valid until the next call; NULL if the stop is
 *  not recorded. */
const hl_scan_t *hl_closure_query(hl_closure_t *c, uint32_t stamp, uint32_t max_readings);

/** Whether a localization against a submap (@p loc, its pose @p found) is a match at
 *  all: as distinct as HL_CLOSURE_MIN_CONFIDENCE, with the guard's @p min_votes, within
 *  its @p wild_mm of @p estimate (the stop's own pose). The gate comes after
 *  (hl_closure_match). */
bool hl_closure_counts(const hl_loc_result_t *loc, hl_pose_t found, hl_pose_t estimate,
                       uint32_t min_votes, hl_mm_t wild_mm);

/**
 * The stop @p query found at @p found in stop @p stamp's submap. Taken as a match unless it
 * lies farther than the gate from the query's fitted pose (or the two are nearer than
 * HL_CLOSURE_GAP, or either is not recorded, or the query has taken HL_CLOSURE_MAX_TAKEN).
 * @return whether it was taken.
 */
bool hl_closure_match(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found);

/** As hl_closure_match, with the gate @p gate_mm and @p gate_rad (a correlative search's
 *  region). */
bool hl_closure_match_within(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found,
                             double gate_mm, double gate_rad);

/**
 * Stop @p query sought in stop @p stamp's submap by a correlative search (corrmatch.h)
 * over the region hl_closure_search_region gives, with at most @p max_readings of its
 * readings (0: all): found (at *@p found, in the map's frame) when its score is
 * HL_CLOSURE_CORR_MIN_SCORE or more and no pose distinct from it scores
 * HL_CLOSURE_CORR_RUNNER_UP of it. @return whether it was found.
 */
bool hl_closure_seek(hl_closure_t *c, uint32_t stamp, uint32_t query, uint32_t max_readings,
                     hl_pose_t *found);

/** Holds the match of stop @p query at @p found in stop @p stamp's submap until
 *  hl_closure_settle (the matches held for another query are dropped). */
void hl_closure_pend(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found);

/** The matches held for stop @p query (hl_closure_pend) taken (hl_closure_match_within,
 *  the region its gate) when HL_CLOSURE_CORR_AGREEING or more of them agree where the
 *  stop lies in the map: those of the largest group that agree, and only when every one
 *  of them passes the gate. One place can look like another to one submap, seldom to
 *  several along the robot's earlier path. The rest are dropped. @return how many were
 *  taken. */
uint32_t hl_closure_settle(hl_closure_t *c, uint32_t query);

/**
 * Fits every recorded stop to its steps and matches, and draws @p map again: its vectors
 * of stops no longer recorded (or of none) as they are, then each recorded stop's scan
 * at its fitted pose. @return the matches dropped as outliers.
 */
uint32_t hl_closure_fit(hl_closure_t *c, hl_map_t *map);

/**
 * As hl_closure_fit, but the map is not drawn again at once: the stops are fitted now and
 * drawn into @p shadow (a map made with @p map's capacity and settings) a few at a time
 * by the hl_closure_redraw_step calls that follow, one a scan, so that no scan pays for a
 * whole map. Until the last of them puts the shadow in place the slam keeps tracking in
 * the frame before the fit (its map is still that one); the stops it records meanwhile
 * are carried into the fit's frame (hl_closure_carry). Nothing while a redraw is under
 * way. @return the matches dropped as outliers.
 */
uint32_t hl_closure_fit_spread(hl_closure_t *c, const hl_map_t *map, hl_map_t *shadow);

/** A spread fit is drawn only when it moves some stop more than @p mm from where its
 *  vectors lie in the map (or turns it enough to move a wall 5 m away that far); until
 *  then the map and the slam stay in the frame before the fits, the stops recorded are
 *  carried into the fits' frame, and the next fit is measured from the map. 0 (from
 *  create): every fit is drawn. */
void hl_closure_redraw_beyond(hl_closure_t *c, double mm);

/** A fit that moves a sixteenth of the stops or fewer more than @p mm from where their
 *  vectors lie (or turns them enough to move a wall 5 m away that far) draws again only
 *  those and the newest; the others' vectors stay in the map as they are, and the
 *  culling generator goes on from where the map's is. Any other fit, and every fit with
 *  0 (from create), draws every stop, with the generator as it was before the oldest
 *  was drawn (the map the slam would hold had the stops always been where the fit puts
 *  them). */
void hl_closure_redraw_stops_beyond(hl_closure_t *c, double mm);

/** Whether a spread redraw is under way (no new fit, no matching meanwhile). */
bool hl_closure_redrawing(const hl_closure_t *c);

/** Draws the next stops into @p shadow, about @p readings readings (at least one stop);
 *  once every stop is drawn, swaps @p map and @p shadow (hl_map_swap) and ends the
 *  redraw. @return whether it did: the slam's pose then goes through hl_closure_carry. */
bool hl_closure_redraw_step(hl_closure_t *c, hl_map_t *map, hl_map_t *shadow, uint32_t readings);

/** @p pose, tracked in the frame before the last fit (at once or spread), in the frame
 *  after it: moved as the newest stop fitted then was moved by the fit. */
hl_pose_t hl_closure_carry(const hl_closure_t *c, hl_pose_t pose);

#endif
