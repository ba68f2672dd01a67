/* slam_heading.c - the heading an accepted localization takes (slam_internal.h): the
 * heading gain, a complementary filter with the odometry, and square walls (walls.h), a
 * reference that does not drift. */
#include "houghloc-internal/walls.h"
#include "slam_internal.h"

#include <math.h>

#define PI 3.14159265358979323846

/* predicted + gain * (found - predicted), the short way round; gain 1 gives found. */
static hl_bam_t blend_heading(hl_bam_t predicted, hl_bam_t found, double gain)
{
    if (gain >= 1.0)
        return found;
    int32_t d = (int16_t)(uint16_t)(found - predicted);
    return (hl_bam_t)(predicted + (int32_t)lround(gain * d));
}

/* Square walls (slam.wall_gain): @p heading turned part of the way by which the wall
 * normals of @p scan lie off the map's axis. The map's axis does not drift; the heading
 * tracking gives a sparse scan does, by a degree or so a scan, and turns the map drawn
 * after it. The map's axis is counted afresh each scan (its bins make that 15,000
 * increments, no allocation): the map changes every scan. */
static hl_bam_t square_to_walls(const hl_slam_t *s, const hl_scan_t *scan, hl_bam_t heading)
{
    if (s->p.wall_gain <= 0)
        return heading;
    hl_walls_t map = hl_walls_of_vectors(hl_map_vectors(s->map), hl_map_count(s->map));
    hl_walls_t seen = hl_walls_of_scan(scan);
    if (map.n < HL_WALLS_MIN_READINGS || map.r < HL_WALLS_MIN_R ||
        seen.n < HL_WALLS_MIN_READINGS || seen.r < HL_WALLS_MIN_R)
        return heading;
    uint32_t inliers;
    double off = hl_walls_offset(scan, hl_bam_to_rad(heading), map.axis,
                                 HL_WALLS_WINDOW_DEG * (PI / 180), &inliers);
    if (inliers < HL_WALLS_MIN_READINGS)
        return heading;
    return (hl_bam_t)(heading - hl_bam_from_rad(s->p.wall_gain * off));
}

hl_bam_t hl_slam_take_heading(const hl_slam_t *s, const hl_scan_t *ready, hl_bam_t predicted,
                              hl_bam_t found)
{
    return square_to_walls(s, ready, blend_heading(predicted, found, s->p.heading_gain));
}
