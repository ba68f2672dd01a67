/*
 * slam_lost.c - hl_slam_update: tracking, and the recovery of a robot whose pose is lost.
 *
 * One pass: hl_slam_update checks and prepares the scan once; tracking's answer is
 * computed first (hl_slam_propose) and committed only after the watch has decided, so the
 * watch compares the search with the very local search tracking takes; the searches made
 * to confirm or compare are memoized for the scan (slam_internal.h), so none runs twice
 * with the same inputs.
 *
 * The tracker is lost when the watch's global search (search_every > 0: on every scan
 * tracking is in doubt about, and every search_every-th scan) finds the robot clearly
 * elsewhere (it was carried away: tracking may match a wrong place of a corridor well
 * enough); after lost_after doubtful scans in a row
 * (rejected, or accepted with a peak below HL_SLAM_LOST_PEAK_RATIO of the recent average: the
 * estimate drifted off the map, or the robot entered unmapped space); or when told
 * (hl_slam_lose). While lost:
 *  - a scan with no candidate runs the global search. A pose found (distinct from the
 *    runner-up) becomes the candidate: RELOCALIZED. Otherwise the scan is tracked as
 *    always (the robot may only have entered space the map does not cover yet, where
 *    tracking extends the map) and is LOST, with the search's best and runner-up so that
 *    a client sees the ambiguity; lost_after acceptances in a row end the lost state;
 *  - a scan with a candidate is localized around the candidate moved by the odometry
 *    since (the ordinary local search): when that agrees (within wild_mm, a distinct
 *    peak, enough votes), the estimate is set there and the scan is tracked; accepted,
 *    tracking resumes. Otherwise the candidate is dropped and this scan runs the search.
 * A found pose wins over tracking: a kidnapped robot's tracking may lock onto a wrong
 * place once the recent peaks have fallen (slam.h), and the search is what notices.
 *
 * While lost the search takes the lost scan alone and, when that is ambiguous, up to
 * reloc.scans scans together (reloc.h): the lost scan and those kept before it, each
 * kept where the odometry had moved KEEP_APART_MM or turned KEEP_APART_DEG since the one
 * before (a scan nearer than that replaces the newest kept: the same view, fresher). Views from places apart are what tell one stretch of a
 * corridor from the next; the odometry between them is good to a few centimetres.
 */
#include <string.h>

#include "slam_internal.h"

#define KEEP_APART_MM 500
#define KEEP_APART_DEG 30.0

/* Scans tracking must match well in a row to end the lost state when lost_after is 0
 * (lost only when told): its recommended value. */
#define LOST_EXIT_RUN 2

/* One scan through the recovery: its inputs, and what the stages found so far. */
typedef struct cycle {
    hl_slam_t *s;
    const hl_scan_t *scan;  /* checked and prepared once (hl_slam_ready) */
    hl_pose_t odometry;
    hl_pose_t prediction;   /* the pose a scan tracking cannot localize gets */
    hl_slam_step_t step;
    hl_reloc_result_t found;    /* the global search's answer, when one ran */
    hl_status_t error;      /* tracking's, when it could not localize the scan */
    /* for the caller's log (hl_slam_step_t) */
    hl_slam_lost_why_t lost_why;
    int32_t doubtful_run;
    hl_pose_t tracked;
    uint32_t tracked_score;
    hl_slam_found_how_t found_how;
    bool dropped_candidate, searched_lost, watched;
    hl_status_t search_status;
} cycle_t;

static void clear_lost(hl_slam_t *s)
{
    uint32_t epoch = s->recovery.epoch;
    s->recovery = (hl_slam_recovery_t){ .epoch = epoch };
}

static void enter_lost(hl_slam_t *s)
{
    s->recovery.epoch++;
    clear_lost(s);
    s->recovery.lost = true;
    s->unconfirmed = 0;     /* the lost state's searches take over */
}

bool hl_slam_lost(const hl_slam_t *s)
{
    return s && s->recovery.lost;
}

uint32_t hl_slam_lost_epoch(const hl_slam_t *s)
{
    return s ? s->recovery.epoch : 0;
}

void hl_slam_lose(hl_slam_t *s)
{
    if (s)
        enter_lost(s);
}

void hl_slam_stop_searching(hl_slam_t *s)
{
    if (s && s->recovery.lost)
        clear_lost(s);
}

/* Two poses within wild_mm and the search's distinct_theta of each other. */
static bool agree(const hl_slam_t *s, hl_pose_t a, hl_pose_t b)
{
    int32_t dt = hl_bam_diff(a.theta, b.theta);
    return hl_slam_dist2(a, b) <= (int64_t)HL_SLAM_WILD_MM * HL_SLAM_WILD_MM &&
           (dt < 0 ? -dt : dt) < s->p.reloc.distinct_theta;
}

/* The recovery's doubt about a tracked scan: rejected, or accepted with a peak far below
 * the recent ones (@p peak_avg, the average before it). */
static bool doubtful(const hl_slam_step_t *step, uint32_t peak_avg)
{
    /* A robot carried away matches the map far worse at its predicted pose; the guard
     * rejects the first such scans, but its recent-peak average falls with each (slam.h,
     * so that the map can follow a robot into unmapped space), and it soon accepts them */
    bool low = peak_avg > 0 && step->loc.peak < HL_SLAM_LOST_PEAK_RATIO * (double)peak_avg;
    return step->status == HL_SLAM_REJECTED_WILD || (step->status == HL_SLAM_ACCEPTED && low);
}

/* Tracking on this scan: @p p, which hl_slam_propose made (@p st its answer), committed;
 * a failure answers the prediction. @return true when the scan is doubtful. */
static bool track_proposed(cycle_t *c, hl_status_t st, hl_slam_proposal_t *p)
{
    hl_slam_t *s = c->s;
    uint32_t peak_avg = s->peak_avg;
    if (st == HL_OK)
        st = hl_slam_commit(s, c->scan, c->odometry, p, &c->step);
    if (st != HL_OK) {
        c->error = st;
        c->step = (hl_slam_step_t){ .pose = c->prediction, .status = HL_SLAM_ODOMETRY_ONLY };
        return false;
    }
    return doubtful(&c->step, peak_avg);
}

static bool track(cycle_t *c)
{
    hl_slam_proposal_t p;
    hl_status_t st = hl_slam_propose(c->s, c->scan, c->odometry, &p);
    return track_proposed(c, st, &p);
}

/* Where tracking's local search would put this scan from @p from, without changing
 * anything; false (and @p from in @p out) when it finds nothing. */
static bool tracked_pose(cycle_t *c, hl_pose_t from, hl_pose_t *out)
{
    hl_loc_result_t loc;
    if (hl_slam_search_local(c->s, c->scan, from, &loc, out) == HL_OK)
        return true;
    *out = from;
    return false;
}

/* Keeps the lost @p scan for the search (see above). */
static void keep_scan(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry)
{
    hl_slam_recovery_t *r = &s->recovery;
    if (!s->kept_scans)
        return;
    uint32_t at = r->kept;
    if (at > 0) {
        hl_pose_t newest = r->kept_odometry[at - 1];
        int32_t turn = hl_bam_diff(odometry.theta, newest.theta);
        bool apart = hl_slam_dist2(odometry, newest) >= (int64_t)KEEP_APART_MM * KEEP_APART_MM ||
                     (turn < 0 ? -turn : turn) >= hl_bam_from_deg(KEEP_APART_DEG);
        if (!apart)
            at--;
        else if (at == s->p.reloc.scans) {    /* full: the oldest goes */
            memmove(&s->kept_scans[0], &s->kept_scans[1], (at - 1) * sizeof *s->kept_scans);
            memmove(&r->kept_odometry[0], &r->kept_odometry[1],
                    (at - 1) * sizeof *r->kept_odometry);
            at--;
        }
    }
    s->kept_scans[at] = *scan;
    r->kept_odometry[at] = odometry;
    r->kept = at + 1;
}

/* The global search on this lost scan: alone, and when that is ambiguous, with the
 * scans kept before it. Alone first: a sum of scores dilutes one distinctive view with
 * the ambiguous ones before it (a runner-up explains those as well as the answer), and a
 * found candidate is confirmed by the next scan anyway. */
static hl_status_t relocalize(cycle_t *c)
{
    hl_slam_t *s = c->s;
    keep_scan(s, c->scan, c->odometry);
    hl_status_t alone = hl_slam_search_global(s, &c->scan, NULL, 1, &c->found);
    if (s->recovery.kept < 2 || (alone == HL_OK && c->found.found))
        return alone;
    const hl_scan_t *scans[HL_RELOC_MAX_SCANS];
    hl_pose_t odometry[HL_RELOC_MAX_SCANS];
    uint32_t n = s->recovery.kept;
    for (uint32_t i = 0; i < n; i++) {      /* newest (this scan) first: its pose answers */
        scans[i] = &s->kept_scans[n - 1 - i];
        odometry[i] = s->recovery.kept_odometry[n - 1 - i];
    }
    return hl_slam_search_global(s, scans, odometry, n, &c->found);
}

static void set_candidate(cycle_t *c, hl_pose_t pose)
{
    c->s->recovery.have_candidate = true;
    c->s->recovery.candidate = pose;
    c->s->recovery.candidate_odometry = c->odometry;
}

/* The ordinary local search around the candidate moved by the odometry since: does this
 * scan agree with it? */
static bool confirms(cycle_t *c, hl_pose_t *predicted)
{
    hl_slam_t *s = c->s;
    if (!hl_pose_predict(s->recovery.candidate, s->recovery.candidate_odometry, c->odometry,
                         predicted))
        return false;
    hl_loc_result_t loc;
    hl_pose_t pose;
    if (hl_slam_search_local(s, c->scan, *predicted, &loc, &pose) != HL_OK)
        return false;
    return hl_slam_dist2(pose, *predicted) <= (int64_t)HL_SLAM_WILD_MM * HL_SLAM_WILD_MM &&
           hl_loc_confidence(&loc) >= HL_SLAM_MIN_CONFIDENCE && loc.votes >= HL_SLAM_MIN_VOTES;
}

/* The global search while lost: true with a candidate. */
static bool search(cycle_t *c)
{
    c->searched_lost = true;
    c->search_status = relocalize(c);
    if (c->search_status != HL_OK) {
        c->found = (hl_reloc_result_t){ 0 };
        return false;
    }
    if (!c->found.found)
        return false;
    set_candidate(c, c->found.pose);
    return true;
}

static hl_slam_status_t found_again(cycle_t *c, hl_slam_found_how_t how,
                                    hl_slam_status_t status)
{
    clear_lost(c->s);
    c->found_how = how;
    return status;
}

/* One scan while lost: confirms the candidate or searches the whole map. @p tracked:
 * this scan was already tracked (it made the tracker lost), with its result in c->step. */
static hl_slam_status_t lost_scan(cycle_t *c, bool tracked)
{
    hl_slam_t *s = c->s;
    if (!tracked)
        c->step = (hl_slam_step_t){ .pose = c->prediction, .status = HL_SLAM_ODOMETRY_ONLY };
    c->found = (hl_reloc_result_t){ 0 };
    hl_pose_t predicted;
    if (s->recovery.have_candidate && confirms(c, &predicted)) {
        hl_slam_place(s, predicted, c->odometry);
        if (hl_slam_track(s, c->scan, c->odometry, &c->step) == HL_OK &&
            c->step.status == HL_SLAM_ACCEPTED)
            return found_again(c, HL_SLAM_FOUND_CONFIRMED, HL_SLAM_ACCEPTED);
    }
    c->dropped_candidate = s->recovery.have_candidate;
    s->recovery.have_candidate = false;
    if (search(c)) {
        /* Where tracking would put this scan: when the search agrees, the robot was not
         * carried away (it entered a part of the map seen less, or turned a corner) */
        hl_pose_t local = c->step.pose;
        bool have_local = tracked ? c->step.status != HL_SLAM_ODOMETRY_ONLY
                                  : tracked_pose(c, c->prediction, &local);
        if (have_local && agree(s, local, c->found.pose)) {
            s->recovery.have_candidate = false;
            if (!tracked)
                track(c);
            return found_again(c, HL_SLAM_FOUND_AGREES, c->step.status);
        }
        c->step.pose = c->found.pose;
        return HL_SLAM_RELOCALIZED;
    }
    /* Nothing stands out: the robot may just have entered space the map does not cover
     * yet (slam.h), where tracking extends the map as it always does; a run of scans it
     * tracks well ends the lost state. */
    if (tracked)
        return HL_SLAM_LOST;
    bool doubtful = track(c);
    s->recovery.accepted_run = c->step.status == HL_SLAM_ACCEPTED && !doubtful
                                   ? s->recovery.accepted_run + 1 : 0;
    if (s->recovery.accepted_run >= (s->p.lost_after > 0 ? s->p.lost_after : LOST_EXIT_RUN))
        return found_again(c, HL_SLAM_FOUND_TRACKED, HL_SLAM_ACCEPTED);
    return HL_SLAM_LOST;
}

/* The watch while tracking: the global search on this scan, and whether it finds the
 * robot somewhere else that explains the scan clearly better than @p local, where
 * tracking's local search puts it. If so the tracker is lost with that candidate, to be
 * confirmed by the next scan, and nothing is tracked. */
static bool kidnapped(cycle_t *c, hl_pose_t local)
{
    hl_slam_t *s = c->s;
    c->watched = true;
    c->found = (hl_reloc_result_t){ 0 };
    if (hl_slam_search_global(s, &c->scan, NULL, 1, &c->found) != HL_OK || !c->found.found)
        return false;
    if (agree(s, local, c->found.pose)) {
        s->unconfirmed = 0;     /* the search puts the robot where tracking does */
        return false;
    }
    uint32_t here = hl_slam_judge_ready(s, c->scan, local);
    if (here > s->p.reloc.max_ratio * c->found.score)
        return false;   /* tracking's pose explains the scan about as well: keep it */
    enter_lost(s);
    keep_scan(s, c->scan, c->odometry);
    c->lost_why = HL_SLAM_LOST_ELSEWHERE;
    c->tracked = local;
    c->tracked_score = here;
    set_candidate(c, c->found.pose);
    c->step = (hl_slam_step_t){ .pose = c->found.pose, .status = HL_SLAM_ODOMETRY_ONLY };
    return true;
}

/* Whether the watch searches this scan (search_every > 0): every search_every-th scan,
 * and every scan tracking is in doubt about: one after a restore until a search confirms
 * tracking's pose (the robot may have moved while nothing watched; at most search_every
 * scans), one tracking could not localize against a map that holds something, or a
 * doubtful one (@p doubt: rejected, or a peak far below the recent ones). A scan tracked
 * well between the periodic ones is not searched. */
static bool watch_due(const cycle_t *c, uint64_t scan_index, hl_status_t tracked, bool doubt)
{
    const hl_slam_t *s = c->s;
    if (s->p.search_every == 0)
        return false;
    return scan_index % (uint64_t)s->p.search_every == 0 || s->unconfirmed > 0 || doubt ||
           (tracked != HL_OK && hl_map_count(s->map) > 0);
}

/* Tracking, with the recovery's watch over it: tracking's answer computed once; the
 * global search when due, which may find the robot elsewhere (then nothing is tracked);
 * else the answer committed, and the doubtful run. */
static hl_slam_status_t tracking_scan(cycle_t *c, uint64_t scan_index)
{
    hl_slam_t *s = c->s;
    hl_slam_proposal_t p;
    hl_status_t st = hl_slam_propose(s, c->scan, c->odometry, &p);
    bool doubt = st == HL_OK && doubtful(&p.step, s->peak_avg);
    if (watch_due(c, scan_index, st, doubt) && kidnapped(c, p.local))
        return HL_SLAM_RELOCALIZED;
    bool doubtful_scan = track_proposed(c, st, &p);
    s->recovery.doubtful_run = doubtful_scan ? s->recovery.doubtful_run + 1 : 0;
    if (s->p.lost_after == 0 || s->recovery.doubtful_run < s->p.lost_after)
        return c->step.status;
    c->doubtful_run = s->recovery.doubtful_run;
    c->lost_why = HL_SLAM_LOST_DOUBTFUL;
    enter_lost(s);
    return lost_scan(c, true);
}

hl_status_t hl_slam_update(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t odometry,
                           hl_slam_step_t *out)
{
    if (!s || !scan || !out)
        return HL_ERR_ARG;
    /* the scan's one check: every stage after takes it as checked (valid_scan.h) */
    if (hl_scan_check(scan) != HL_OK || !hl_pose_in_range(odometry)) {
        *out = (hl_slam_step_t){ .pose = s->pose, .predicted = s->pose,
                                 .status = HL_SLAM_ODOMETRY_ONLY };
        return HL_ERR_RANGE;
    }
    cycle_t c = { .s = s, .odometry = odometry };
    hl_slam_predict(s, odometry, &c.prediction);
    c.scan = hl_slam_ready(s, scan);    /* prepared once: echo bearings, normals */
    s->memo = (hl_slam_memo_t){ .active = true };
    uint64_t scan_index = s->scans++;
    hl_slam_status_t status = s->recovery.lost ? lost_scan(&c, false)
                                               : tracking_scan(&c, scan_index);
    s->memo = (hl_slam_memo_t){ 0 };
    if (s->unconfirmed > 0)
        s->unconfirmed--;
    *out = c.step;
    out->status = status;
    if (status == HL_SLAM_RELOCALIZED || status == HL_SLAM_LOST)
        out->search = c.found;
    out->lost_why = c.lost_why;
    out->doubtful_run = c.doubtful_run;
    out->tracked = c.tracked;
    out->tracked_score = c.tracked_score;
    out->found_how = c.found_how;
    out->dropped_candidate = c.dropped_candidate;
    out->searched_lost = c.searched_lost;
    out->watched = c.watched;
    out->search_status = c.search_status;
    return c.error;
}
