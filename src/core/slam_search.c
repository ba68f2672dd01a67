/* slam_search.c - the tracker's searches on its own map: the local search around a
 * prediction, the global search (relocalization) and the judge's scores, each computed
 * once within a scan (the memo, slam_internal.h) and given again when asked again with
 * the same inputs. */
#include <string.h>

#include "houghloc-internal/slam_search.h"
#include "slam_internal.h"
#include "valid_scan.h"

static bool same_pose(hl_pose_t a, hl_pose_t b)
{
    return a.x_mm == b.x_mm && a.y_mm == b.y_mm && a.theta == b.theta;
}

hl_status_t hl_slam_search_local(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t predicted,
                                 hl_loc_result_t *loc, hl_pose_t *pose)
{
    hl_slam_memo_t *m = &s->memo;
    if (m->active && m->have_local && m->local_scan == ready &&
        same_pose(m->local_from, predicted)) {
        *loc = m->local_loc;
        if (m->local_status == HL_OK)
            *pose = m->local_pose;
        return m->local_status;
    }
    hl_status_t st = hl_slam_localize_in(s, s->map, ready, predicted, loc, pose);
    if (m->active) {
        m->have_local = true;
        m->local_from = predicted;
        m->local_scan = ready;
        m->local_status = st;
        m->local_loc = *loc;
        if (st == HL_OK)
            m->local_pose = *pose;
    }
    return st;
}

hl_status_t hl_slam_relocalize(hl_slam_t *s, const hl_scan_t *scan, hl_reloc_result_t *out)
{
    return hl_slam_relocalize_scans(s, &scan, NULL, 1, out);
}

hl_status_t hl_slam_relocalize_scans(hl_slam_t *s, const hl_scan_t *const *scans,
                                     const hl_pose_t *odometry, uint32_t count,
                                     hl_reloc_result_t *out)
{
    if (!s || !scans || !out || count < 1 || count > HL_RELOC_MAX_SCANS)
        return HL_ERR_ARG;
    const hl_scan_t *ready[HL_RELOC_MAX_SCANS];
    for (uint32_t k = 0; k < count; k++) {
        if (!scans[k])
            return HL_ERR_ARG;
        if (hl_scan_check(scans[k]) != HL_OK)
            return HL_ERR_RANGE;
        ready[k] = hl_slam_prepare_valid(&s->p, scans[k],
                                         s->search_echoed ? &s->search_echoed[k] : NULL,
                                         s->search_fitted ? &s->search_fitted[k] : NULL);
    }
    return hl_slam_search_global(s, ready, odometry, count, out);
}

hl_status_t hl_slam_search_global(hl_slam_t *s, const hl_scan_t *const *ready,
                                  const hl_pose_t *odometry, uint32_t count,
                                  hl_reloc_result_t *out)
{
    hl_slam_memo_t *m = &s->memo;
    bool alone = count == 1;
    if (alone && m->active && m->have_search) {
        *out = m->search;
        return m->search_status;
    }
    const hl_vector_t *map = hl_map_vectors(s->map);
    uint32_t n = hl_map_count(s->map);
    hl_status_t st = hl_reloc_run_scans_valid(s->reloc, map, n, ready, odometry, count, out);
    if (st == HL_OK && s->refiner)  /* a refused refinement leaves the search's pose */
        hl_refine_run_valid(s->refiner, map, n, ready[0], out->pose, s->p.refine_heading,
                            &out->pose);
    if (alone && m->active) {
        m->have_search = true;
        m->search_status = st;
        m->search = *out;
    }
    return st;
}

uint32_t hl_slam_judge_ready(hl_slam_t *s, const hl_scan_t *ready, hl_pose_t pose)
{
    uint32_t score;
    hl_reloc_judge_poses_valid(s->reloc, hl_map_vectors(s->map), hl_map_count(s->map), ready,
                               &pose, 1, &score);
    return score;
}

void hl_slam_judge_poses(hl_slam_t *s, const hl_scan_t *scan, const hl_pose_t *poses,
                         uint32_t count, uint32_t *scores)
{
    if (!s || !scan || hl_scan_check(scan) != HL_OK) {
        if (scores)
            memset(scores, 0, (size_t)count * sizeof *scores);
        return;
    }
    hl_reloc_judge_poses_valid(s->reloc, hl_map_vectors(s->map), hl_map_count(s->map),
                               hl_slam_ready(s, scan), poses, count, scores);
}

uint32_t hl_slam_judge(hl_slam_t *s, const hl_scan_t *scan, hl_pose_t pose)
{
    uint32_t score;
    hl_slam_judge_poses(s, scan, &pose, 1, &score);
    return score;
}
