/* slam.c - the tracker's life (create, reset, state) and tracking: the online
 * localize-then-extend cycle of the paper (sections 2 and 7), in its stages; its searches
 * are slam_search.c's. */
#include "houghloc/slam.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/closure.h"
#include "houghloc-internal/params.h"
#include "slam_internal.h"
#include "valid_scan.h"

hl_slam_t *hl_slam_create(const hl_params_t *p)
{
    if (!p)
        return NULL;
    hl_params_t checked = *p;   /* hl_params_check writes its error line */
    if (hl_params_check(&checked) != HL_OK)
        return NULL;
    return hl_slam_create_with(hl_params_slam_const(p));
}

hl_slam_t *hl_slam_create_with(const hl_slam_params_t *p)
{
    if (hl_slam_params_error(p))
        return NULL;
    hl_slam_t *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->p = *p;
    hl_map_params_t mp;
    hl_slam_map_params(p, &mp);
    s->map = hl_map_create_with(&mp);
    /* The localizer only ever sees this map: one bound for both (slam.h). */
    hl_loc_params_t lp = p->loc;
    lp.max_map_vectors = p->map_capacity;
    s->p.loc.max_map_vectors = p->map_capacity;
    s->loc = hl_loc_create(&lp);
    s->echoed = p->echo_bearings ? malloc(sizeof *s->echoed) : NULL;
    s->fitted = p->fit_normals ? malloc(sizeof *s->fitted) : NULL;
    s->search_echoed = p->echo_bearings ? calloc(HL_RELOC_MAX_SCANS, sizeof(hl_scan_t)) : NULL;
    s->search_fitted = p->fit_normals ? calloc(HL_RELOC_MAX_SCANS, sizeof(hl_scan_t)) : NULL;
    s->kept_scans = p->reloc.scans > 1 ? calloc(p->reloc.scans, sizeof(hl_scan_t)) : NULL;
    if (p->multiscan_mm > 0) {
        s->multi = hl_multiscan_create(HL_MULTISCAN_MAX_SCANS, p->multiscan_mm,
                                       p->multiscan_turn);
        s->assembled = malloc(sizeof *s->assembled);
    }
    s->refiner = p->refine ? hl_refine_create(&p->refine_params, p->map_capacity) : NULL;
    s->reloc = hl_reloc_create(&p->reloc, &lp);
    s->closure = p->close_loops ? hl_closure_create(p->closure_stops, p->map_capacity, p->seed)
                                : NULL;
    bool spread = p->close_loops && p->closure_redraw_readings > 0;
    s->shadow = spread ? hl_map_create_with(&mp) : NULL;
    if (!s->map || (spread && !s->shadow) ||
        !s->loc || (p->echo_bearings && !s->echoed) ||
        (p->fit_normals && !s->fitted) || (p->refine && !s->refiner) ||
        (p->echo_bearings && !s->search_echoed) || (p->fit_normals && !s->search_fitted) ||
        (p->reloc.scans > 1 && !s->kept_scans) ||
        (p->multiscan_mm > 0 && (!s->multi || !s->assembled)) ||
        !s->reloc || (p->close_loops && !s->closure)) {
        hl_slam_destroy(s);
        return NULL;
    }
    if (p->square_walls)
        hl_closure_square_walls(s->closure,
                                hl_bam_to_rad(hl_bam_from_deg(HL_SLAM_WALL_AXIS_DEG)));
    if (s->closure)     /* cannot fail: the params were checked */
        hl_closure_weigh_matches(s->closure, p->closure_match_weight);
    if (s->closure && s->shadow) {
        hl_closure_redraw_beyond(s->closure, p->closure_redraw_mm);
        hl_closure_redraw_stops_beyond(s->closure, p->closure_redraw_stop_mm);
    }
    return s;
}

void hl_slam_destroy(hl_slam_t *s)
{
    if (!s)
        return;
    hl_map_destroy(s->map);
    hl_map_destroy(s->shadow);
    hl_loc_destroy(s->loc);
    free(s->echoed);
    free(s->fitted);
    free(s->search_echoed);
    free(s->search_fitted);
    free(s->kept_scans);
    hl_multiscan_destroy(s->multi);
    free(s->assembled);
    hl_refine_destroy(s->refiner);
    hl_reloc_destroy(s->reloc);
    hl_closure_destroy(s->closure);
    free(s);
}

void hl_slam_reset(hl_slam_t *s, hl_pose_t start)
{
    hl_map_clear(s->map);
    s->started = false;
    s->pose = start;
    s->peak_avg = 0;
    if (s->multi)
        hl_multiscan_clear(s->multi);
    if (s->closure)
        hl_slam_closure_reset(s);
}

/* Guarded mode: is this localization believable? */
static bool plausible(const hl_slam_t *s, hl_pose_t pose, hl_pose_t predicted,
                      const hl_loc_result_t *r)
{
    bool high_enough = s->peak_avg == 0 || r->peak >= HL_SLAM_MIN_PEAK_RATIO * s->peak_avg;
    return hl_slam_dist2(pose, predicted) <= (int64_t)HL_SLAM_WILD_MM * HL_SLAM_WILD_MM &&
           hl_loc_confidence(r) >= HL_SLAM_MIN_CONFIDENCE &&
           r->votes >= HL_SLAM_MIN_VOTES &&
           high_enough;
}

/* floor(sqrt(a * b)), exactly, in integers. */
static uint32_t geometric_mean(uint32_t a, uint32_t b)
{
    uint64_t p = (uint64_t)a * b;
    uint64_t lo = 0, hi = a > b ? a : b;    /* sqrt(a b) <= max(a, b) */
    while (lo < hi) {   /* the largest r with r * r <= p */
        uint64_t mid = lo + (hi - lo + 1) / 2;
        if (mid * mid <= p)
            lo = mid;
        else
            hi = mid - 1;
    }
    return (uint32_t)lo;
}

/* The recent-peak average after a localization with @p peak: a quarter of the way to an
 * accepted peak (an exponential average over about four scans), the geometric mean with
 * a rejected one. A scan entering unmapped space may have a peak ten or a hundred times
 * below the average, and the peaks after it stay low; an arithmetic step of a quarter
 * would take many scans to come down, and every one of them would be rejected and kept
 * out of the map (slam.h). */
static uint32_t tracked_peak(uint32_t avg, uint32_t peak, bool accepted)
{
    if (avg == 0)
        return peak;
    if (!accepted)
        return geometric_mean(avg, peak);
    return (uint32_t)((int64_t)avg + ((int64_t)peak - avg) / 4);
}

const hl_scan_t *hl_slam_prepare_valid(const hl_slam_params_t *p, const hl_scan_t *scan,
                                       hl_scan_t *echoed, hl_scan_t *fitted)
{
    if (p->echo_bearings && hl_echo_correct_valid(&p->echo, scan, echoed) == HL_OK)
        scan = echoed;
    if (p->fit_normals && hl_normals_fit_valid(&p->normals, scan, fitted) == HL_OK)
        scan = fitted;
    return scan;
}

const hl_scan_t *hl_slam_prepare(const hl_slam_params_t *p, const hl_scan_t *scan,
                                 hl_scan_t *echoed, hl_scan_t *fitted)
{
    /* every step refuses a scan hl_scan_check refuses, and leaves its input */
    return hl_scan_check(scan) == HL_OK ? hl_slam_prepare_valid(p, scan, echoed, fitted) : scan;
}

const hl_scan_t *hl_slam_ready(hl_slam_t *s, const hl_scan_t *scan)
{
    return hl_slam_prepare_valid(&s->p, scan, s->echoed, s->fitted);
}

bool hl_slam_predict(const hl_slam_t *s, hl_pose_t odometry, hl_pose_t *out)
{
    if (!s->started) {
        *out = s->pose;
        return hl_pose_in_range(s->pose);
    }
    return hl_pose_predict(s->pose, s->odom, odometry, out);
}

/* Hough, then the optional refinement, against @p map (the slam's, or a loop closure's
 * map of one earlier stop); @p scan is checked (closure's stops are scans the map took). */
hl_status_t hl_slam_localize_in(hl_slam_t *s, const hl_map_t *map, const hl_scan_t *scan,
                                hl_pose_t predicted, hl_loc_result_t *loc, hl_pose_t *pose)
{
    hl_loc_query_t q = { .predicted = predicted, .window_mm = s->p.window_mm,
                         .search_theta = true, .use_prior = s->p.use_prior };
    hl_status_t st = hl_loc_run_valid(s->loc, hl_map_vectors(map), hl_map_count(map), scan,
                                      &q, loc);
    if (st != HL_OK)
        return st;
    *pose = s->p.interpolate ? loc->pose : loc->cell_pose;
    if (s->refiner)  /* a refused refinement leaves the Hough pose */
        hl_refine_run_valid(s->refiner, hl_map_vectors(map), hl_map_count(map), scan, *pose,
                            s->p.refine_heading, pose);
    return HL_OK;
}

/* A turned drive is taken only when the judge (reloc.h) explains this many times as many
 * readings there, and a few more, as at the tracker's own pose: its score is the evidence
 * against the odometry, and at an unmapped place both scores are small. */
#define TURN_MARGIN 1.2
#define TURN_MIN_GAIN 3u

/* Long drives (slam.h): after a drive of long_drive_mm or more since the last scan, the
 * scan is localized again with the drive turned about where it started, by each multiple
 * of HL_SLAM_DRIVE_TURN_DEG up to HL_SLAM_DRIVE_TURNS each way (odometry's heading error
 * swings the whole drive, so the position moves with the heading), and the judge picks.
 * When a turned drive wins, *found and *loc become its. @return whether one did. */
static bool turn_drive(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry,
                       hl_loc_result_t *loc, hl_pose_t *found)
{
    const hl_pose_t origin = { 0, 0, 0 };
    if (s->p.long_drive_mm == 0 || !s->started ||
        hl_slam_dist2(hl_pose_between(s->odom, odometry), origin) <
            (int64_t)s->p.long_drive_mm * s->p.long_drive_mm)
        return false;
    enum { MAX = 1 + 2 * HL_SLAM_DRIVE_TURNS };
    const int32_t turn = hl_bam_from_deg(HL_SLAM_DRIVE_TURN_DEG);
    hl_pose_t pose[MAX] = { *found };
    hl_loc_result_t res[MAX];
    uint32_t score[MAX], n = 1;
    res[0] = *loc;
    for (int k = -HL_SLAM_DRIVE_TURNS; k <= HL_SLAM_DRIVE_TURNS; k++) {
        hl_pose_t from = s->pose;
        from.theta = (hl_bam_t)(from.theta + k * turn);
        hl_pose_t pred;
        if (k != 0 && hl_pose_predict(from, s->odom, odometry, &pred) &&
            hl_slam_localize_in(s, s->map, scan, pred, &res[n], &pose[n]) == HL_OK)
            n++;
    }
    hl_reloc_judge_poses_valid(s->reloc, hl_map_vectors(s->map), hl_map_count(s->map), scan,
                               pose, n, score);
    uint32_t best = 0;
    for (uint32_t i = 1; i < n; i++)
        if (score[i] > score[best])
            best = i;
    if (best == 0 || score[best] < TURN_MARGIN * score[0] + TURN_MIN_GAIN)
        return false;
    *found = pose[best];
    *loc = res[best];
    return true;
}

hl_status_t hl_slam_localize(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t predicted,
                             hl_loc_result_t *loc, hl_pose_t *pose)
{
    if (!s || !scan || !loc || !pose)
        return HL_ERR_ARG;
    if (hl_scan_check(scan) != HL_OK || !hl_pose_in_range(predicted))
        return HL_ERR_RANGE;
    return hl_slam_localize_in(s, s->map, hl_slam_ready(s, scan), predicted, loc, pose);
}

/* ---- tracking: the stages of one scan ------------------------------------------------- */

/* Localize: the Hough vote around the prediction, refined, and after a long drive the
 * drive turned about its start. HL_ERR_EMPTY: nothing to vote against. */
static hl_status_t stage_localize(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry,
                                  hl_slam_proposal_t *p, hl_pose_t *found)
{
    hl_slam_step_t *step = &p->step;
    hl_status_t st = hl_slam_search_local(s, scan, step->predicted, &step->loc, found);
    if (st != HL_OK)
        return st;
    p->local = *found;
    step->turned = turn_drive(s, scan, odometry, &step->loc, found);
    return HL_OK;
}

/* Guard: accept or reject the pose found (guarded mode) in @p scan, the recent-peak
 * average moved with it; an accepted pose takes its heading by hl_slam_take_heading.
 * @return whether the scan extends the map. */
static bool stage_guard(const hl_slam_t *s, const hl_scan_t *scan, hl_pose_t found,
                        hl_slam_step_t *step, uint32_t *peak_avg)
{
    /* A turned drive's pose has passed the judge, which weighs more than the guard's
     * rules of thumb (its peak may be low against recent ones: the robot has driven into
     * a place it has mapped less). */
    bool accept = !s->p.guarded || step->turned ||
                  plausible(s, found, step->predicted, &step->loc);
    *peak_avg = tracked_peak(s->peak_avg, step->loc.peak, accept);
    if (!accept) {
        step->status = HL_SLAM_REJECTED_WILD;
        return false;
    }
    step->status = HL_SLAM_ACCEPTED;
    step->pose = found;
    step->pose.theta = hl_slam_take_heading(s, scan, step->predicted.theta, found.theta);
    return true;
}

/* Integrate: the scan into the map at the step's pose (culled to capacity), stamped for
 * loop closure. hl_map_add_scan refuses only a pose out of range, which the caller has
 * checked, so this cannot fail; the map is unchanged if it does. */
static hl_status_t stage_integrate(hl_slam_t *s, const hl_scan_t *scan, hl_slam_step_t *step,
                                   bool *stop)
{
    *stop = s->closure && hl_slam_closure_stamp(s, step->pose);
    return hl_map_add_scan(s->map, scan, step->pose, &step->added);
}

/* Integrate by motion: the scans the drive has taken out of the window go into the map,
 * and this one into the window (the first goes straight into an empty map). Each goes in
 * where the newest estimate puts it by the odometry between them: the window's scans
 * were localized together with the newest. */
static hl_status_t stage_integrate_window(hl_slam_t *s, const hl_scan_t *scan,
                                          hl_pose_t odometry, bool extend,
                                          hl_slam_step_t *step)
{
    if (hl_map_count(s->map) == 0)
        return extend ? hl_map_add_scan(s->map, scan, step->pose, &step->added) : HL_OK;
    const hl_scan_t *old;
    hl_pose_t old_odometry, old_pose;
    bool draw;
    while (hl_multiscan_pop_due(s->multi, odometry, &old, &old_odometry, &old_pose, &draw)) {
        uint32_t added = 0;
        hl_pose_predict(step->pose, odometry, old_odometry, &old_pose);
        if (draw && hl_map_add_scan(s->map, old, old_pose, &added) == HL_OK)
            step->added += added;
    }
    hl_multiscan_push(s->multi, scan, odometry, step->pose, extend);
    return HL_OK;
}

/* The stages that compute (predict, localize, guard) go into the proposal, and only
 * hl_slam_commit changes the tracker, so that every error return leaves it as it was
 * (slam_internal.h). The scratch buffers (s->echoed, the localizer's raster, the
 * refiner's hash) are not state: each use rewrites them. */
hl_status_t hl_slam_propose(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                            hl_slam_proposal_t *p)
{
    hl_pose_t predicted;
    bool in_range = hl_slam_predict(s, odometry, &predicted);
    *p = (hl_slam_proposal_t){ .local = predicted, .extend = true, .peak_avg = s->peak_avg };
    if (!in_range)
        return HL_ERR_RANGE;
    p->step = (hl_slam_step_t){ .pose = predicted, .predicted = predicted,
                                .status = HL_SLAM_ODOMETRY_ONLY };
    /* Sounding by motion: the newest scan with the window's, once there is a map. */
    const hl_scan_t *seen = ready;
    if (s->multi && hl_map_count(s->map) > 0) {
        hl_multiscan_assemble(s->multi, ready, odometry, s->assembled);
        seen = s->assembled;
    }
    hl_pose_t found;
    hl_status_t st = stage_localize(s, seen, odometry, p, &found);
    if (st == HL_OK)
        p->extend = stage_guard(s, seen, found, &p->step, &p->peak_avg);
    else if (st != HL_ERR_EMPTY)
        return st;
    /* HL_ERR_EMPTY: nothing to vote against. The first scan, or a scan that overlaps
     * nothing the map holds near the prediction: the paper's robot starts its map this
     * way, and this is how the map follows the robot where it has nothing yet (slam.h):
     * the scan goes in at the prediction. */

    /* A local window at the edge of the coordinate range can put the peak (or the
     * refinement) outside it. */
    if (p->extend && !hl_pose_in_range(p->step.pose))
        return HL_ERR_RANGE;
    return HL_OK;
}

hl_status_t hl_slam_commit(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                           hl_slam_proposal_t *p, hl_slam_step_t *out)
{
    hl_rng_t rng_before = hl_map_rng(s->map);
    bool stop = false;      /* a stop of its own for loop closure, or joins the last */
    hl_status_t st;
    if (s->multi)
        st = stage_integrate_window(s, ready, odometry, p->extend, &p->step);
    else
        st = p->extend ? stage_integrate(s, ready, &p->step, &stop) : HL_OK;
    if (st != HL_OK)
        return st;
    /* Closure: cannot fail (its memory is its own, from create). A rejected scan is not
     * remembered: its pose is odometry's alone. */
    if (s->closure)
        p->step.loops = hl_slam_closure_stage(s, p->extend ? ready : NULL, stop, rng_before,
                                              &p->step.pose);
    /* the map may have changed: what was searched against it no longer holds */
    if (p->extend || s->closure)
        s->memo = (hl_slam_memo_t){ .active = s->memo.active };
    s->started = true;
    s->odom = odometry;
    s->pose = p->step.pose;
    s->peak_avg = p->peak_avg;
    *out = p->step;
    return HL_OK;
}

hl_status_t hl_slam_track(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t odometry,
                          hl_slam_step_t *out)
{
    hl_slam_proposal_t p;
    hl_status_t st = hl_slam_propose(s, ready, odometry, &p);
    return st == HL_OK ? hl_slam_commit(s, ready, odometry, &p, out) : st;
}

void hl_slam_place(hl_slam_t *s, hl_pose_t pose, hl_pose_t odometry)
{
    s->pose = pose;
    if (s->multi)       /* the window's scans were placed from the pose before */
        hl_multiscan_clear(s->multi);
    if (s->closure)     /* no step joins the stops before to the ones after */
        hl_slam_closure_reset(s);
    /* Before the first scan there is no reference yet: the first scan's odometry
     * becomes it, at this pose. */
    if (s->started)
        s->odom = odometry;
}

hl_status_t hl_slam_set_pose(hl_slam_t *s, hl_pose_t pose, hl_pose_t odometry)
{
    if (!s)
        return HL_ERR_ARG;
    if (!hl_pose_in_range(pose) || !hl_pose_in_range(odometry))
        return HL_ERR_RANGE;
    hl_slam_place(s, pose, odometry);
    hl_slam_stop_searching(s);
    return HL_OK;
}

hl_pose_t hl_slam_pose(const hl_slam_t *s)
{
    return s->pose;
}

void hl_slam_get_state(const hl_slam_t *s, hl_slam_state_t *out)
{
    memset(out, 0, sizeof *out);    /* zero padding: callers may compare bytes */
    out->started = s->started;
    out->pose = s->pose;
    out->odom = s->odom;
    out->peak_avg = s->peak_avg;
    out->map_version = hl_map_version(s->map);
    out->cull_rng = hl_map_rng(s->map);
}

hl_status_t hl_slam_restore(hl_slam_t *s, const hl_slam_state_t *state,
                            const hl_vector_t *vectors, uint32_t n)
{
    if (!s || !state || (!vectors && n > 0))
        return HL_ERR_ARG;
    if (n > hl_map_capacity(s->map))
        return HL_ERR_CAPACITY;
    if (!hl_pose_in_range(state->pose) || !hl_pose_in_range(state->odom))
        return HL_ERR_RANGE;
    /* The map checks the vectors before it changes anything; the rest cannot fail. */
    hl_status_t st = hl_map_restore(s->map, vectors, n, state->map_version,
                                    state->cull_rng);
    if (st != HL_OK)
        return st;
    s->started = state->started;
    s->pose = state->pose;
    s->odom = state->odom;
    s->peak_avg = state->peak_avg;
    if (s->multi)       /* the window's scans belonged to the run before */
        hl_multiscan_clear(s->multi);
    /* unconfirmed until the watch's search agrees, at most until its next period */
    s->unconfirmed = s->p.search_every > 0 ? (uint32_t)s->p.search_every : 0;
    if (s->closure)     /* the stops are not saved: the restored vectors stay put */
        hl_slam_closure_reset(s);
    return HL_OK;
}

hl_map_t *hl_slam_map(hl_slam_t *s)
{
    return s->map;
}
