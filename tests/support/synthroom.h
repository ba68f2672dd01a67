/*
 * synthroom.h - synthetic cluttered rooms for tests and benchmarks: walls and boxes as
 * segments, an ideal range sensor (nearest hit along each bearing, optional Gaussian
 * noise), maps built from soundings at random free positions. Deterministic from a seed.
 * Not a sonar model (tools/sim is); this is the minimal world in which the true pose is
 * known exactly.
 */
#ifndef HOUGHLOC_TEST_SUPPORT_SYNTHROOM_H
#define HOUGHLOC_TEST_SUPPORT_SYNTHROOM_H

#include <stdint.h>

#include "houghloc/map.h"
#include "houghloc/rng.h"
#include "houghloc/scan.h"

#define SR_MAX_SEGMENTS 512

typedef struct sr_segment {
    double x1, y1, x2, y2;  /* millimetres */
} sr_segment_t;

typedef struct sr_room {
    double width_mm, height_mm; /* walls from (x0, y0) to (x0 + width, y0 + height) */
    double x0_mm, y0_mm;
    int nseg;
    sr_segment_t seg[SR_MAX_SEGMENTS];
    hl_rng_t rng;
} sr_room_t;

/**
 * A rectangular room of the given size with its corner at (x0, y0) and @p nboxes
 * random axis-aligned and rotated boxes (0.2 to 1 m) inside.
 */
void sr_room_make(sr_room_t *room, double x0_mm, double y0_mm, double width_mm,
                  double height_mm, int nboxes, uint64_t seed);

/** Distance along a ray to the nearest segment, or a negative number if none. */
double sr_cast(const sr_room_t *room, double x, double y, double angle_rad);

/** Distance from (x, y) to the nearest segment. */
double sr_clearance(const sr_room_t *room, double x, double y);
/** True if (x, y) is inside one of the boxes. */
int sr_inside_box(const sr_room_t *room, double x, double y);

/**
 * The next stop of a random walk: a step of @p step_mm from @p from in a direction
 * near its heading, keeping @p clearance_mm from everything. Heading = direction.
 */
hl_pose_t sr_walk(sr_room_t *room, hl_pose_t from, double step_mm, double clearance_mm);

/** A random pose at least @p clearance_mm from every segment. */
hl_pose_t sr_free_pose(sr_room_t *room, double clearance_mm);

/**
 * A scan of @p n readings evenly spaced in bearing, taken at @p pose. Readings beyond
 * @p max_range_mm are invalid; @p noise_mm is the Gaussian range noise sigma.
 */
void sr_sound(sr_room_t *room, hl_pose_t pose, int n, double max_range_mm,
              double noise_mm, hl_scan_t *out);

/**
 * Fills @p out with @p count map vectors: soundings of @p n readings from random free
 * positions, pooled and sampled uniformly without replacement.
 * @return the number of vectors written (count unless the room yields too few).
 */
uint32_t sr_make_map(sr_room_t *room, uint32_t count, int n, double max_range_mm,
                     double noise_mm, hl_vector_t *out);

/** Standard normal deviate from the room's generator. */
double sr_gauss(sr_room_t *room);

/** The same from any generator (Box-Muller, so results match across libcs). */
double sr_gauss_rng(hl_rng_t *rng);

#endif
