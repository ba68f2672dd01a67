/*
 * cycle_lost.c - the daemon's side of the LOST state: the tracker (hl_slam_update,
 * src/core/slam_lost.c) decides when the robot is lost and when it is found again; the
 * daemon logs each change, shows it in STATUS, and lets an operator (RELOCALIZE) or the
 * robot (its soundings while lost, HL_CONFIG_LOST_SOUNDINGS) start or end it. A scan's POSE goes out first, then its
 * log lines, then the STATUS of the state it leaves (hl_cycle_scan_state: the one place
 * a scan's state is derived).
 */
#include <stdio.h>

#include "cycle_internal.h"
#include "log.h"

bool hl_cycle_lost(const hl_cycle_t *c)
{
    return hl_slam_lost(c->slam);
}

uint32_t hl_cycle_lost_epoch(const hl_cycle_t *c)
{
    return hl_slam_lost_epoch(c->slam);
}

/* The tracker became lost (it is already): say why, once. */
static void report_entered(hl_cycle_t *c, bool was_lost, const char *why)
{
    if (!was_lost)
        hl_log(HL_LOG_NOTICE, "lost: %s; each scan now searches the whole map", why);
    hl_cycle_note_error(c, why);
}

void hl_cycle_enter_lost(hl_cycle_t *c, const char *why, int64_t now_us)
{
    bool was_lost = hl_slam_lost(c->slam);
    hl_slam_lose(c->slam);
    report_entered(c, was_lost, why);
    hl_cycle_set_state(c, HL_BUS_STATE_LOST, now_us);
}

void hl_cycle_scan_state(hl_cycle_t *c, int64_t now_us)
{
    int8_t state = hl_slam_lost(c->slam) ? HL_BUS_STATE_LOST : HL_BUS_STATE_LOCALIZING;
    if (c->state != state)
        hl_cycle_set_state(c, state, now_us);
}

void hl_cycle_give_up_lost(hl_cycle_t *c, const char *why, int64_t now_us)
{
    if (!hl_slam_lost(c->slam))
        return;
    hl_slam_stop_searching(c->slam);
    hl_log(HL_LOG_WARNING, "no longer lost: %s; tracking goes on from the estimate", why);
    hl_cycle_note_error(c, why);
    hl_cycle_set_state(c, HL_BUS_STATE_IDLE, now_us);
}

static void report_search(const hl_bus_scan_t *in, const hl_slam_step_t *step)
{
    const hl_reloc_result_t *f = &step->search;
    if (step->search_status != HL_OK) {
        hl_log(HL_LOG_INFO, "lost: scan seq %d: global search: %s", in->seq,
               hl_status_str(step->search_status));
        return;
    }
    hl_log(HL_LOG_INFO, "lost: scan seq %d: %s (%.3f, %.3f) m, %.1f deg explaining %.0f %% "
           "of the readings; runner-up (%.3f, %.3f) m, %.1f deg: %u against %u",
           in->seq, f->found ? "found" : "ambiguous", f->pose.x_mm / 1000.0,
           f->pose.y_mm / 1000.0, hl_bam_to_sdeg(f->pose.theta), f->explained_pct,
           f->runner_up.x_mm / 1000.0, f->runner_up.y_mm / 1000.0,
           hl_bam_to_sdeg(f->runner_up.theta), f->runner_up_score, f->score);
}

void hl_cycle_report_recovery(hl_cycle_t *c, const hl_bus_scan_t *in,
                              const hl_slam_step_t *step)
{
    char what[HL_BUS_TEXT_MAX];
    const hl_reloc_result_t *f = &step->search;
    switch (step->lost_why) {
    case HL_SLAM_LOST_ELSEWHERE:
        snprintf(what, sizeof what, "scan seq %d: the global search puts the robot at "
                 "(%.3f, %.3f) m, %.1f deg (%u readings explained), not at (%.3f, %.3f) m "
                 "(%u)", in->seq, f->pose.x_mm / 1000.0, f->pose.y_mm / 1000.0,
                 hl_bam_to_sdeg(f->pose.theta), f->score, step->tracked.x_mm / 1000.0,
                 step->tracked.y_mm / 1000.0, step->tracked_score);
        report_entered(c, false, what);
        break;
    case HL_SLAM_LOST_DOUBTFUL:
        snprintf(what, sizeof what, "%d doubtful scans in a row (slam.lost_after)",
                 step->doubtful_run);
        report_entered(c, false, what);
        break;
    case HL_SLAM_LOST_NOT:
        break;
    }
    if (step->dropped_candidate)
        hl_log(HL_LOG_INFO, "lost: scan seq %d does not confirm the candidate", in->seq);
    if (step->searched_lost)
        report_search(in, step);
    static const char *const how[] = {
        [HL_SLAM_FOUND_CONFIRMED] = "confirms the global search's pose",
        [HL_SLAM_FOUND_AGREES] = "where the global search puts it too",
        [HL_SLAM_FOUND_TRACKED] = "ends a run of scans that tracking matched well",
    };
    if (step->found_how == HL_SLAM_FOUND_NOT)
        return;
    hl_log(HL_LOG_NOTICE, "relocalized: scan seq %d at (%.3f, %.3f) m, %.1f deg %s; tracking "
           "again", in->seq, step->pose.x_mm / 1000.0, step->pose.y_mm / 1000.0,
           hl_bam_to_sdeg(step->pose.theta), how[step->found_how]);
}
