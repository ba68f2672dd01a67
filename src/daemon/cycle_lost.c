/*
 * cycle_lost.c - the LOST state: the daemon no longer knows where the robot is, and each
 * scan searches the whole map (hl_slam_relocalize) until a pose is found and the next scan
 * confirms it.
 *
 * Entered when the global search, run on every daemon.search_every-th scan while
 * tracking, finds the robot clearly elsewhere (it was carried away: tracking may match a
 * wrong place of a corridor well enough); after daemon.lost_after doubtful scans in a
 * row (rejected, or accepted with a peak below daemon.lost_peak_ratio of the recent
 * average: the estimate drifted off the map, or the robot entered unmapped space); or on
 * a RELOCALIZE command. While lost:
 *  - a scan with no candidate runs the global search. A pose found (distinct from the
 *    runner-up) becomes the candidate, published with status RELOCALIZED. Otherwise the
 *    scan goes through the ordinary cycle (the robot may only have entered space the map
 *    does not cover yet, where tracking extends the map as it always does) and is
 *    published LOST, with the search's best and runner-up so that a client sees the
 *    ambiguity; lost_after acceptances in a row end the lost state;
 *  - a scan with a candidate is localized around the candidate moved by the odometry
 *    since (the ordinary local search): when that agrees (within wild_mm, a distinct
 *    peak, enough votes), the estimate is set there and the scan goes through the
 *    ordinary cycle; accepted, tracking resumes. Otherwise the candidate is dropped and
 *    this scan runs the global search.
 * A found pose wins over tracking: a kidnapped robot's tracking may lock onto a wrong
 * place once the recent peaks have fallen (slam.h), and the search is what notices.
 */
#include <stdio.h>

#include "cycle_internal.h"
#include "log.h"

/* Scans tracking must match well in a row to end the lost state when daemon.lost_after
 * is 0 (the automatic entry off; lost by RELOCALIZE): its recommended value. */
#define LOST_EXIT_RUN 2

bool hl_cycle_lost(const hl_cycle_t *c)
{
    return c->lost;
}

uint32_t hl_cycle_lost_epoch(const hl_cycle_t *c)
{
    return c->lost_epoch;
}

void hl_cycle_clear_lost(hl_cycle_t *c)
{
    c->lost = false;
    c->have_candidate = false;
    c->doubtful_run = 0;
    c->accepted_run = 0;
}

void hl_cycle_enter_lost(hl_cycle_t *c, const char *why, int64_t now_us)
{
    c->lost_epoch++;
    if (!c->lost)
        hl_log(HL_LOG_NOTICE, "lost: %s; each scan now searches the whole map", why);
    hl_cycle_clear_lost(c);
    c->lost = true;
    hl_cycle_note_error(c, why);
    hl_cycle_set_state(c, HL_BUS_STATE_LOST, now_us);
}

bool hl_cycle_track(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                    hl_slam_step_t *step)
{
    hl_slam_state_t before;
    hl_slam_get_state(c->slam, &before);
    hl_status_t st = hl_slam_update(c->slam, &in->scan, in->odometry, step);
    if (st != HL_OK) {
        /* nothing changed (slam.h); answer with the prediction, as for an empty map */
        char what[HL_BUS_TEXT_MAX];
        snprintf(what, sizeof what, "SONAR: scan seq %d not localized: %s", in->seq,
                 hl_status_str(st));
        hl_cycle_fault(c, NULL, "sonar update", what);
        *step = (hl_slam_step_t){ .pose = prediction, .status = HL_SLAM_ODOMETRY_ONLY };
        return false;
    }
    /* A robot carried away matches the map far worse at its predicted pose; the guard
     * rejects the first such scans, but its recent-peak average falls with each (slam.h,
     * so that the map can follow a robot into unmapped space), and it soon accepts them */
    bool low = before.peak_avg > 0 &&
               step->loc.peak < c->p.lost_peak_ratio * (double)before.peak_avg;
    return step->status == HL_SLAM_REJECTED_WILD || (step->status == HL_SLAM_ACCEPTED && low);
}

void hl_cycle_give_up_lost(hl_cycle_t *c, const char *why, int64_t now_us)
{
    if (!c->lost)
        return;
    hl_cycle_clear_lost(c);
    hl_log(HL_LOG_WARNING, "no longer lost: %s; tracking goes on from the estimate", why);
    hl_cycle_note_error(c, why);
    hl_cycle_set_state(c, HL_BUS_STATE_IDLE, now_us);
}

static int64_t dist2(hl_pose_t a, hl_pose_t b)
{
    int64_t dx = (int64_t)a.x_mm - b.x_mm, dy = (int64_t)a.y_mm - b.y_mm;
    return dx * dx + dy * dy;
}

/* Two poses within wild_mm and the search's distinct_theta of each other. */
static bool agree(const hl_cycle_t *c, hl_pose_t a, hl_pose_t b)
{
    int32_t dt = hl_bam_diff(a.theta, b.theta);
    return dist2(a, b) <= (int64_t)c->p.slam.wild_mm * c->p.slam.wild_mm &&
           (dt < 0 ? -dt : dt) < c->p.slam.reloc.distinct_theta;
}

/* The ordinary local search around the candidate, moved by the odometry since: does this
 * scan agree with it? */
static bool confirms(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t *predicted)
{
    *predicted = hl_pose_compose(c->candidate,
                                 hl_pose_between(c->candidate_odometry, in->odometry));
    if (!hl_pose_in_range(*predicted))
        return false;
    hl_loc_result_t loc;
    hl_pose_t pose;
    if (hl_slam_localize(c->slam, &in->scan, *predicted, &loc, &pose) != HL_OK)
        return false;
    const hl_slam_params_t *sp = &c->p.slam;
    return dist2(pose, *predicted) <= (int64_t)sp->wild_mm * sp->wild_mm &&
           hl_loc_confidence(&loc) >= sp->min_confidence && loc.votes >= sp->min_votes;
}

static void leave_lost(hl_cycle_t *c, const hl_bus_scan_t *in, const hl_slam_step_t *step,
                       const char *why, int64_t now_us)
{
    hl_cycle_clear_lost(c);
    hl_log(HL_LOG_NOTICE, "relocalized: scan seq %d at (%.3f, %.3f) m, %.1f deg %s; tracking "
           "again", in->seq, step->pose.x_mm / 1000.0, step->pose.y_mm / 1000.0,
           hl_bam_to_sdeg(step->pose.theta), why);
    hl_cycle_set_state(c, HL_BUS_STATE_LOCALIZING, now_us);
}

/* The search's answer for this scan, to be confirmed by the next. */
static void set_candidate(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t pose)
{
    c->have_candidate = true;
    c->candidate = pose;
    c->candidate_odometry = in->odometry;
}

/* Where tracking's local search would put this scan, without changing anything; false
 * (and the prediction in @p out) when it finds nothing. */
static bool tracked_pose(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                         hl_pose_t *out)
{
    hl_loc_result_t loc;
    if (hl_slam_localize(c->slam, &in->scan, prediction, &loc, out) == HL_OK)
        return true;
    *out = prediction;
    return false;
}

/* The global search on this scan: true with a candidate. */
static bool search(hl_cycle_t *c, const hl_bus_scan_t *in, hl_reloc_result_t *found)
{
    hl_status_t st = hl_slam_relocalize(c->slam, &in->scan, found);
    if (st != HL_OK) {
        *found = (hl_reloc_result_t){ 0 };
        hl_log(HL_LOG_INFO, "lost: scan seq %d: global search: %s", in->seq, hl_status_str(st));
        return false;
    }
    hl_log(HL_LOG_INFO, "lost: scan seq %d: %s (%.3f, %.3f) m, %.1f deg explaining %.0f %% "
           "of the readings; runner-up (%.3f, %.3f) m, %.1f deg: %u against %u",
           in->seq, found->found ? "found" : "ambiguous", found->pose.x_mm / 1000.0,
           found->pose.y_mm / 1000.0, hl_bam_to_sdeg(found->pose.theta), found->explained_pct,
           found->runner_up.x_mm / 1000.0, found->runner_up.y_mm / 1000.0,
           hl_bam_to_sdeg(found->runner_up.theta), found->runner_up_score, found->score);
    if (!found->found)
        return false;
    set_candidate(c, in, found->pose);
    return true;
}

bool hl_cycle_kidnapped(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                        hl_slam_step_t *step, hl_reloc_result_t *found, int64_t now_us)
{
    *found = (hl_reloc_result_t){ 0 };
    if (hl_slam_relocalize(c->slam, &in->scan, found) != HL_OK || !found->found)
        return false;
    hl_pose_t local;
    tracked_pose(c, in, prediction, &local);
    if (agree(c, local, found->pose))
        return false;
    uint32_t here = hl_slam_judge(c->slam, &in->scan, local);
    if (here > c->p.slam.reloc.max_ratio * found->score)
        return false;   /* tracking's pose explains the scan about as well: keep it */
    char what[HL_BUS_TEXT_MAX];
    snprintf(what, sizeof what, "scan seq %d: the global search puts the robot at (%.3f, "
             "%.3f) m, %.1f deg (%u readings explained), not at (%.3f, %.3f) m (%u)",
             in->seq, found->pose.x_mm / 1000.0, found->pose.y_mm / 1000.0,
             hl_bam_to_sdeg(found->pose.theta), found->score, local.x_mm / 1000.0,
             local.y_mm / 1000.0, here);
    hl_cycle_enter_lost(c, what, now_us);
    set_candidate(c, in, found->pose);
    *step = (hl_slam_step_t){ .pose = found->pose, .status = HL_SLAM_ODOMETRY_ONLY };
    return true;
}

int8_t hl_cycle_lost_scan(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                          bool tracked, hl_slam_step_t *step, hl_reloc_result_t *found,
                          int64_t now_us)
{
    if (!tracked)
        *step = (hl_slam_step_t){ .pose = prediction, .status = HL_SLAM_ODOMETRY_ONLY };
    *found = (hl_reloc_result_t){ 0 };
    hl_pose_t predicted;
    if (c->have_candidate && confirms(c, in, &predicted)) {
        hl_slam_set_pose(c->slam, predicted, in->odometry);
        if (hl_slam_update(c->slam, &in->scan, in->odometry, step) == HL_OK &&
            step->status == HL_SLAM_ACCEPTED) {
            leave_lost(c, in, step, "confirms the global search's pose", now_us);
            return HL_SLAM_ACCEPTED;
        }
    }
    if (c->have_candidate)
        hl_log(HL_LOG_INFO, "lost: scan seq %d does not confirm the candidate", in->seq);
    c->have_candidate = false;
    if (search(c, in, found)) {
        /* Where tracking would put this scan: when the search agrees, the robot was not
         * carried away (it entered a part of the map seen less, or turned a corner) */
        hl_pose_t local = step->pose;
        bool have_local = tracked ? step->status != HL_SLAM_ODOMETRY_ONLY
                                  : tracked_pose(c, in, prediction, &local);
        if (have_local && agree(c, local, found->pose)) {
            c->have_candidate = false;
            if (!tracked)
                hl_cycle_track(c, in, prediction, step);
            leave_lost(c, in, step, "where the global search puts it too", now_us);
            return (int8_t)step->status;
        }
        step->pose = found->pose;
        return HL_BUS_POSE_RELOCALIZED;
    }
    /* Nothing stands out: the robot may just have entered space the map does not cover
     * yet (slam.h), where tracking extends the map as it always does; a run of scans it
     * tracks well ends the lost state. */
    if (tracked)
        return HL_BUS_POSE_LOST;
    bool doubtful = hl_cycle_track(c, in, prediction, step);
    c->accepted_run = step->status == HL_SLAM_ACCEPTED && !doubtful ? c->accepted_run + 1 : 0;
    if (c->accepted_run >= (c->p.lost_after > 0 ? c->p.lost_after : LOST_EXIT_RUN)) {
        leave_lost(c, in, step, "ends a run of scans that tracking matched well", now_us);
        return HL_SLAM_ACCEPTED;
    }
    return HL_BUS_POSE_LOST;
}
