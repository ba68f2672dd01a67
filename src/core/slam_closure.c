/* slam_closure.c - the slam's loop-closure stage (slam.h, closure.h): each stop recorded,
 * matched against the earlier stops near it, every stop fitted and the map drawn again.
 * At once, in the scan that made the stop (a robot that sounds at stops); or a share a
 * scan (closure_matches_per_scan, closure_redraw_readings), so that a robot scanning
 * several times a second never waits for a whole building: one scan seeks a few matches,
 * a later one fits, the ones after draw the map again aside, and the last puts it in
 * place. */
#include "slam_internal.h"

bool hl_slam_closure_stamp(hl_slam_t *s, hl_pose_t pose)
{
    hl_bam_t turn = s->p.keyframe_mm > 0 ? hl_bam_from_deg(HL_SLAM_KEYFRAME_DEG) : 0;
    bool stop = hl_closure_is_stop(s->closure, pose, s->p.keyframe_mm, turn);
    hl_map_set_stamp(s->map, stop ? hl_closure_next_stamp(s->closure)
                                  : hl_closure_newest_stamp(s->closure));
    return stop;
}

void hl_slam_closure_reset(hl_slam_t *s)
{
    hl_closure_reset(s->closure);
    s->matching = (hl_slam_matching_t){ 0 };
}

/* Stop @p query localized in stop @p stamp's submap by the tracker's own search from
 * @p from: whether it counts (hl_closure_counts) within @p wild_mm of it. */
static bool localize_in_submap(hl_slam_t *s, uint32_t stamp, uint32_t query, hl_pose_t from,
                               hl_mm_t wild_mm, hl_pose_t *found)
{
    const hl_map_t *sub = hl_closure_submap(s->closure, stamp, query);
    const hl_scan_t *scan = hl_closure_query(s->closure, query,
                                            s->p.closure_match_readings);
    hl_loc_result_t loc;
    return sub && scan && hl_slam_localize_in(s, sub, scan, from, &loc, found) == HL_OK &&
           hl_closure_counts(&loc, *found, from, HL_SLAM_MIN_VOTES, wild_mm);
}

/* Stop @p query matched with stop @p stamp: localized in its submap from where the map has
 * it, a match when it counts and passes the gate. With the correlative search: found
 * anywhere in the region, then, when the tracker polishes its own answers (slam.refine),
 * polished by the tracker's search from there (its peak and point-to-line fit are finer
 * than the search's 50 mm field; a sonar sounding's Hough peak is not) if that agrees, and
 * held
 * until the stop's matches are settled (hl_closure_settle). */
static bool match(hl_slam_t *s, uint32_t stamp, uint32_t query)
{
    hl_pose_t found, polished;
    if (s->p.closure_correlative) {
        if (!hl_closure_seek(s->closure, stamp, query, s->p.closure_match_readings, &found))
            return false;
        if (s->p.refine &&
            localize_in_submap(s, stamp, query, found, HL_CLOSURE_CORR_POLISH_MM, &polished))
            found = polished;
        hl_closure_pend(s->closure, stamp, query, found);
        return false;
    }
    return localize_in_submap(s, stamp, query, hl_closure_pose(s->closure, query),
                              HL_SLAM_WILD_MM, &found) &&
           hl_closure_match(s->closure, stamp, query, found);
}

/* The earlier stops stop @p query is to be matched against: those near it, or with a
 * correlative search those near the region it searches. */
static uint32_t candidates(const hl_slam_t *s, uint32_t query, uint32_t *stamps)
{
    double radius = HL_CLOSURE_RADIUS_MM, mm = 0, rad;
    if (s->p.closure_correlative)
        hl_closure_search_region(s->closure, query, &mm, &rad);
    return hl_closure_candidates_within(s->closure, query, radius + mm, stamps,
                                        HL_CLOSURE_MAX_MATCHES);
}

/* Every stop fitted to the matches; the map drawn again at once (*pose carried into the
 * fit's frame) or begun aside. */
static void fit(hl_slam_t *s, hl_pose_t *pose)
{
    if (s->shadow) {
        hl_closure_fit_spread(s->closure, s->map, s->shadow);
    } else {
        hl_closure_fit(s->closure, s->map);
        *pose = hl_closure_carry(s->closure, *pose);
    }
}

/* The stop whose matches are sought when a stop is made: that stop; with keyframes the one
 * before it, whose scan now holds the readings of every scan joined to it (the new stop's
 * holds one scan's). Against matching the new stop at once, over culling seeds 1-8, the
 * laser's ATE fell on four of the five real buildings and stayed within its spread on the
 * fifth; matching late only the stops that scans had joined did worse
 * (docs/results/real-buildings.md). */
static uint32_t query_stop(const hl_slam_t *s)
{
    uint32_t newest = hl_closure_newest_stamp(s->closure);
    bool keyframes = s->p.keyframe_mm > 0;
    return keyframes ? newest - 1 : newest;
}

/* The stop just recorded, all at once: its candidates sought, a fit if any was taken. */
static uint32_t close_at_once(hl_slam_t *s, hl_pose_t *pose)
{
    uint32_t stamps[HL_CLOSURE_MAX_MATCHES], query = query_stop(s);
    uint32_t n = candidates(s, query, stamps);
    uint32_t taken = 0;
    for (uint32_t k = 0; k < n; k++)
        taken += match(s, stamps[k], query);
    if (s->p.closure_correlative)
        taken = hl_closure_settle(s->closure, query);
    if (taken)
        fit(s, pose);
    return taken;
}

/* A share of the work a scan: the redraw under way, else the fit due, else the next
 * closure_matches_per_scan candidates (those of a new stop, when none are left). A stop
 * made while an earlier one's candidates are sought, its fit or its redraw under way
 * seeks none: matching during a redraw was measured to fit more often for nothing
 * (docs/results/real-buildings.md). */
static uint32_t close_a_share(hl_slam_t *s, bool stop, hl_pose_t *pose)
{
    hl_slam_matching_t *m = &s->matching;
    if (hl_closure_redrawing(s->closure)) {
        if (hl_closure_redraw_step(s->closure, s->map, s->shadow, s->p.closure_redraw_readings))
            *pose = hl_closure_carry(s->closure, *pose);
        return 0;
    }
    if (m->fit_due) {
        m->fit_due = false;
        fit(s, pose);
        return 0;
    }
    if (m->next == m->n && stop) {
        m->query = query_stop(s);
        m->n = candidates(s, m->query, m->stamps);
        m->next = m->taken = 0;
    }
    uint32_t taken = 0;
    for (uint32_t k = 0; k < s->p.closure_matches_per_scan && m->next < m->n; k++)
        taken += match(s, m->stamps[m->next++], m->query);
    if (s->p.closure_correlative)     /* found, to be settled once all are sought */
        taken = m->next == m->n ? hl_closure_settle(s->closure, m->query) : 0;
    m->taken += taken;
    if (m->next == m->n && m->taken) {
        m->fit_due = true;
        m->taken = 0;
    }
    return taken;
}

uint32_t hl_slam_closure_stage(hl_slam_t *s, const hl_scan_t *mapped, bool stop,
                               hl_rng_t rng_before, hl_pose_t *pose)
{
    if (mapped && stop)
        hl_closure_record(s->closure, mapped, *pose, rng_before);
    else if (mapped)
        hl_closure_append(s->closure, mapped, *pose);
    if (s->p.closure_matches_per_scan > 0 || hl_closure_redrawing(s->closure))
        return close_a_share(s, mapped && stop, pose);
    return mapped && stop ? close_at_once(s, pose) : 0;
}
