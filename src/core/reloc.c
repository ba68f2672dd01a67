/*
 * reloc.c - global relocalization, heading unknown (reloc.h): candidate headings from the
 * correlation of normal histograms, a coarse Hough vote over the whole map for each, and
 * a fine local search of the best hypotheses. Allocation: create only.
 */
#include "houghloc-internal/reloc.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/params.h"
#include "judge.h"
#include "loc_params.h"
#include "reloc_headings.h"
#include "valid_scan.h"
#include "votesum.h"


typedef struct hypothesis {
    hl_pose_t pose;
    uint32_t score;
    uint32_t explained; /* readings a map vector explains at this pose */
    hl_pose_t at[HL_RELOC_MAX_SCANS];   /* stage 3: each scan's own pose (at[0] = pose) */
} hypothesis_t;

/* The scans searched together, each with its pose in the first scan's frame. */
typedef struct scan_set {
    const hl_scan_t *const *scans;
    hl_pose_t offset[HL_RELOC_MAX_SCANS];
    uint32_t count;
} scan_set_t;

struct hl_reloc {
    hl_reloc_params_t p;
    hl_loc_params_t coarse_p, fine_p;
    hl_localizer_t *coarse, *fine;
    size_t mem_bytes;
    /* stage 2: each xy cell's best score over the slice, and that slice */
    uint32_t *best_xy;
    uint8_t *best_it;
    uint32_t xy_cells;
    hl_judge_t judge;
    hl_votesum_t coarse_sum;    /* stage 2: the scans' rasters added */
    hypothesis_t hyp[HL_RELOC_MAX_HEADINGS * HL_RELOC_MAX_PEAKS];
    hypothesis_t fine_hyp[HL_RELOC_MAX_HYPOTHESES];
};

void hl_reloc_params_default(hl_reloc_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->heading_smooth = hl_bam_from_deg(HL_RELOC_HEADING_SMOOTH_DEG);
    p->coarse_theta_step = hl_bam_from_deg(HL_RELOC_COARSE_THETA_STEP_DEG);
    p->coarse_half_steps = HL_RELOC_COARSE_HALF_STEPS;
    p->coarse_blur_mm = HL_RELOC_COARSE_BLUR_MM;
    p->peaks_per_heading = HL_RELOC_PEAKS_PER_HEADING;
    p->fine_window_mm = HL_RELOC_FINE_WINDOW_MM;
    p->distinct_mm = HL_RELOC_DISTINCT_MM;
    p->distinct_theta = hl_bam_from_deg(HL_RELOC_DISTINCT_DEG);
    p->short_mm = HL_RELOC_SHORT_MM;
    /* the rest: reloc.* (params_table.c) */
    hl_params_fill_defaults(p, offsetof(hl_slam_params_t, reloc), sizeof *p);
}

const char *hl_reloc_params_error(const hl_reloc_params_t *p)
{
    if (!p)
        return "no relocalization parameters";
    if (p->headings < 1 || p->headings > HL_RELOC_MAX_HEADINGS)
        return "reloc headings must be in 1..64";
    if (p->heading_smooth > hl_bam_from_deg(45.0))
        return "reloc heading_smooth must be at most 45 degrees";
    if (p->coarse_cell_mm < 10 || p->coarse_cell_mm > HL_LOC_MAX_CELL_MM)
        return "reloc coarse_cell_mm must be in 10..1000";
    if (p->coarse_half_steps < 1 || p->coarse_half_steps > 32 ||
        2u * p->coarse_half_steps * p->coarse_theta_step < 64u ||
        (uint32_t)p->coarse_theta_step * (2u * p->coarse_half_steps + 1u) > 32768u)
        return "reloc coarse slice: half_steps in 1..32, spanning 0.35 deg to half a turn";
    if (p->coarse_blur_mm < 0 || p->coarse_blur_mm > 10 * p->coarse_cell_mm)
        return "reloc coarse_blur_mm must be in 0..10 coarse cells";
    if (p->coarse_group_mm != 0 && (p->coarse_group_mm < 8 || p->coarse_group_mm > 1000))
        return "reloc coarse_group_mm must be 0 or in 8..1000";
    if (p->coarse_stride > 64)
        return "reloc coarse_stride must be in 0..64";
    if (p->peaks_per_heading < 1 || p->peaks_per_heading > HL_RELOC_MAX_PEAKS)
        return "reloc peaks_per_heading must be in 1..32";
    if (p->coarse_max_cells < 1 || p->coarse_max_cells > HL_LOC_MAX_CELLS)
        return "reloc coarse_max_cells must be in 1..2^26";
    if (p->hypotheses < 1 || p->hypotheses > HL_RELOC_MAX_HYPOTHESES)
        return "reloc hypotheses must be in 1..64";
    if (p->fine_window_mm < 1 || p->fine_window_mm > 5000)
        return "reloc fine_window_mm must be in 1..5000";
    if (p->distinct_mm < 0 || p->distinct_mm > HL_RANGE_MAX_MM)
        return "reloc distinct_mm must be in 0..32767";
    if (p->verify_mm < 1 || p->verify_mm > 1000)
        return "reloc verify_mm must be in 1..1000";
    if (p->verify_along_mm < 1 || p->verify_along_mm > 1000)
        return "reloc verify_along_mm must be in 1..1000";
    if (p->short_mm != 0 && (p->short_mm <= 300 || p->short_mm > 10000))
        return "reloc short_mm must be 0 or in 301..10000";
    if (p->judge_gate > HL_BAM_HALF_TURN)
        return "reloc judge_gate must be at most 180 degrees";
    if (!(p->min_explained_pct >= 0.0 && p->min_explained_pct <= 100.0))
        return "reloc min_explained_pct must be in 0..100";
    if (!(p->max_ratio > 0.0 && p->max_ratio <= 1.0))
        return "reloc max_ratio must be in (0, 1]";
    if (!(p->max_edge_ratio >= 0.0 && p->max_edge_ratio <= 1.0))
        return "reloc max_edge_ratio must be in 0..1";
    if (p->scans < 1 || p->scans > HL_RELOC_MAX_SCANS)
        return "reloc scans must be in 1..4";
    return NULL;
}

double hl_reloc_confidence(const hl_reloc_result_t *r)
{
    if (!r || r->score == 0)
        return 0.0;
    double c = 1.0 - (double)r->runner_up_score / (double)r->score;
    return c < 0 ? 0 : c;
}

void hl_reloc_destroy(hl_reloc_t *r)
{
    if (!r)
        return;
    hl_loc_destroy(r->coarse);
    hl_loc_destroy(r->fine);
    free(r->best_xy);
    free(r->best_it);
    free(r->coarse_sum.cells);
    hl_judge_free(&r->judge);
    free(r);
}

size_t hl_reloc_mem_bytes(const hl_reloc_t *r)
{
    return r->mem_bytes;
}

hl_reloc_t *hl_reloc_create(const hl_reloc_params_t *p, const hl_loc_params_t *fine)
{
    if (hl_reloc_params_error(p) || hl_loc_params_error(fine))
        return NULL;
    hl_reloc_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->fine_p = *fine;
    r->fine_p.max_cells = hl_loc_cells_for_window(fine, p->fine_window_mm, true);
    r->coarse_p = *fine;
    r->coarse_p.cell_mm = p->coarse_cell_mm;
    r->coarse_p.theta_step = p->coarse_theta_step;
    r->coarse_p.theta_half_steps = p->coarse_half_steps;
    r->coarse_p.blur_sigma_mm = p->coarse_blur_mm;
    r->coarse_p.blur_sigma_theta = p->coarse_theta_step;
    r->coarse_p.peak_separation_mm = p->distinct_mm;
    r->coarse_p.max_cells = p->coarse_max_cells;
    r->coarse_p.group_mm = p->coarse_group_mm;
    r->coarse_p.vote_once = p->coarse_vote_once;
    r->coarse_p.reading_stride = p->coarse_stride > 0 ? p->coarse_stride : 1;
    r->xy_cells = p->coarse_max_cells;
    r->coarse = hl_loc_create(&r->coarse_p);
    r->fine = hl_loc_create(&r->fine_p);
    r->best_xy = calloc(r->xy_cells, sizeof *r->best_xy);
    r->best_it = calloc(r->xy_cells, sizeof *r->best_it);
    r->coarse_sum.max_cells = r->coarse_p.max_cells;
    r->coarse_sum.cells = calloc(r->coarse_sum.max_cells, sizeof *r->coarse_sum.cells);
    bool judge_ok = hl_judge_init(&r->judge, p, fine->max_map_vectors);
    if (!r->coarse || !r->fine || !r->best_xy || !r->best_it || !judge_ok ||
        !r->coarse_sum.cells ||
        hl_loc_params_error(&r->fine_p)) {
        hl_reloc_destroy(r);
        return NULL;
    }
    r->mem_bytes = sizeof *r + hl_loc_mem_bytes(r->coarse) + hl_loc_mem_bytes(r->fine) +
                   (size_t)r->xy_cells * (sizeof *r->best_xy + sizeof *r->best_it) +
                   (size_t)r->coarse_sum.max_cells * sizeof *r->coarse_sum.cells +
                   hl_judge_mem_bytes(&r->judge);
    return r;
}

/* ---- stage 2: coarse positions --------------------------------------------------------- */

static bool distinct(const hl_reloc_params_t *p, hl_pose_t a, hl_pose_t b)
{
    int64_t dx = (int64_t)a.x_mm - b.x_mm, dy = (int64_t)a.y_mm - b.y_mm;
    int32_t dt = hl_bam_diff(a.theta, b.theta);
    return dx * dx + dy * dy >= (int64_t)p->distinct_mm * p->distinct_mm ||
           (dt < 0 ? -dt : dt) >= p->distinct_theta;
}

/* The best peaks_per_heading cells of the scans' summed coarse rasters at least
 * distinct_mm apart in xy, appended to r->hyp; returns the new count. */
static uint32_t coarse_peaks(hl_reloc_t *r, uint32_t nhyp)
{
    const hl_loc_surface_t s = r->coarse_sum.geom;
    uint32_t plane = (uint32_t)(s.nx * s.ny);
    memset(r->best_xy, 0, plane * sizeof *r->best_xy);
    for (int32_t it = 0; it < s.nt; it++) {
        const uint32_t *c = s.cells + (size_t)it * plane;
        for (uint32_t k = 0; k < plane; k++)
            if (c[k] > r->best_xy[k]) {
                r->best_xy[k] = c[k];
                r->best_it[k] = (uint8_t)it;
            }
    }
    int64_t sep = (r->p.distinct_mm + s.cell_mm - 1) / s.cell_mm;
    uint32_t first = nhyp;
    for (uint32_t m = 0; m < r->p.peaks_per_heading; m++) {
        uint32_t best = 0, at = 0;
        for (uint32_t k = 0; k < plane; k++) {
            if (r->best_xy[k] <= best)
                continue;
            int64_t x = k % (uint32_t)s.nx, y = k / (uint32_t)s.nx;
            bool near = false;
            for (uint32_t j = first; j < nhyp && !near; j++) {
                int64_t jx = (r->hyp[j].pose.x_mm - s.x0_mm) / s.cell_mm;
                int64_t jy = (r->hyp[j].pose.y_mm - s.y0_mm) / s.cell_mm;
                near = (x - jx) * (x - jx) + (y - jy) * (y - jy) < sep * sep;
            }
            if (!near) {
                best = r->best_xy[k];
                at = k;
            }
        }
        if (best == 0)
            break;
        r->hyp[nhyp++] = (hypothesis_t){
            .pose = { s.x0_mm + (hl_mm_t)(at % (uint32_t)s.nx) * s.cell_mm + s.cell_mm / 2,
                      s.y0_mm + (hl_mm_t)(at / (uint32_t)s.nx) * s.cell_mm + s.cell_mm / 2,
                      (hl_bam_t)(s.theta0 + r->best_it[at] * s.theta_step) },
            .score = best };
    }
    return nhyp;
}

/* ---- stage 3 and the answer ------------------------------------------------------------- */

static void sort_by_explained(hypothesis_t *h, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++)          /* insertion sort, descending, stable */
        for (uint32_t j = i; j > 0 && (h[j].explained > h[j - 1].explained ||
                                       (h[j].explained == h[j - 1].explained &&
                                        h[j].score > h[j - 1].score)); j--) {
            hypothesis_t t = h[j];
            h[j] = h[j - 1];
            h[j - 1] = t;
        }
}

/* ---- the judge over the scans ------------------------------------------------------- */

static uint32_t set_explained(const hl_reloc_t *r, const scan_set_t *set, hl_pose_t pose,
                              int32_t tol_mm)
{
    uint32_t sum = 0;
    for (uint32_t k = 0; k < set->count; k++)
        sum += hl_judge_explained(&r->judge, set->scans[k],
                                  hl_pose_compose(pose, set->offset[k]), tol_mm, NULL, NULL);
    return sum;
}

static void set_edges(hl_reloc_t *r, const scan_set_t *set, const hypothesis_t *a,
                      const hypothesis_t *b, uint32_t *edge, uint32_t *b_edge)
{
    *edge = *b_edge = 0;
    for (uint32_t k = 0; k < set->count; k++) {
        uint32_t e, be;
        hl_judge_edges(&r->judge, set->scans[k], a->at[k], b->at[k], &e, &be);
        *edge += e;
        *b_edge += be;
    }
}

/* ---- the stages' votes over the scans -------------------------------------------------- */

/* Stage 2 of one heading window: every scan of @p set voted over the whole map with the
 * window's headings turned by its own, their blurred rasters added in the first scan's
 * frame (votesum.h). @return HL_OK when any scan voted; HL_ERR_EMPTY when none did;
 * another status as hl_loc_run's. */
static hl_status_t coarse_vote(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                               const scan_set_t *set, hl_bam_t heading)
{
    hl_votesum_t *sum = &r->coarse_sum;
    sum->started = false;
    for (uint32_t k = 0; k < set->count; k++) {
        hl_loc_query_t q = { .predicted = { 0, 0, (hl_bam_t)(heading + set->offset[k].theta) },
                             .window_mm = 0, .search_theta = true, .use_prior = false };
        hl_loc_result_t lr;
        hl_status_t st = hl_loc_run_valid(r->coarse, map, n, set->scans[k], &q, &lr);
        if (st == HL_ERR_EMPTY)
            continue;
        if (st != HL_OK)
            return st;
        hl_loc_surface_t s;
        hl_loc_get_surface(r->coarse, &s);
        if (!sum->started && !hl_votesum_start(sum, &s, set->offset[k], s.x0_mm, s.y0_mm))
            return HL_ERR_CAPACITY;
        hl_votesum_add(sum, &s, set->offset[k]);
    }
    return sum->started ? HL_OK : HL_ERR_EMPTY;
}

/* Stage 3 of one hypothesis: each scan searched finely around where the hypothesis puts
 * it, alone (the odometry between the scans errs by a few degrees after a turn: each scan
 * finds its own pose near its place), and judged together. @return false when no scan
 * voted. */
static bool fine_search(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                        const scan_set_t *set, hl_pose_t centre, hypothesis_t *h,
                        hl_status_t *error)
{
    bool any = false;
    h->explained = h->score = 0;
    for (uint32_t k = 0; k < set->count; k++) {
        hl_pose_t at = hl_pose_compose(centre, set->offset[k]);
        h->at[k] = at;
        if (!hl_pose_in_range(at))
            continue;
        hl_loc_query_t q = { .predicted = at, .window_mm = r->p.fine_window_mm,
                             .search_theta = true, .use_prior = false };
        hl_loc_result_t lr;
        hl_status_t st = hl_loc_run_valid(r->fine, map, n, set->scans[k], &q, &lr);
        if (st != HL_OK && st != HL_ERR_EMPTY) {
            *error = st;
            return false;
        }
        if (st == HL_OK) {
            h->at[k] = lr.pose;
            if (k == 0)
                h->score = lr.peak;
            any = true;
        }
        h->explained += hl_judge_score(&r->judge, set->scans[k], h->at[k]);
    }
    h->pose = h->at[0];
    return any;
}

/* Checks the arguments (the scans too when @p check) and gathers the scans with their
 * poses in the first's frame. */
static hl_status_t make_set(const hl_reloc_t *r, uint32_t n, const hl_scan_t *const *scans,
                            const hl_pose_t *odometry, uint32_t count, bool check,
                            scan_set_t *set, uint32_t *nvalid)
{
    if (count < 1 || count > HL_RELOC_MAX_SCANS || !scans || (count > 1 && !odometry))
        return HL_ERR_ARG;
    set->scans = scans;
    set->count = count;
    *nvalid = 0;
    for (uint32_t k = 0; k < count; k++) {
        if (!scans[k])
            return HL_ERR_ARG;
        if (check && hl_scan_check(scans[k]) != HL_OK)
            return HL_ERR_RANGE;
        set->offset[k] = (hl_pose_t){ 0, 0, 0 };
        if (k > 0) {
            if (!hl_pose_in_range(odometry[0]) || !hl_pose_in_range(odometry[k]))
                return HL_ERR_RANGE;
            set->offset[k] = hl_pose_between(odometry[0], odometry[k]);
        }
        *nvalid += hl_scan_valid_count(scans[k]);
    }
    return n > r->fine_p.max_map_vectors ? HL_ERR_CAPACITY : HL_OK;
}

static hl_status_t run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                             const hl_scan_t *const *scans, const hl_pose_t *odometry,
                             uint32_t count, bool check, hl_reloc_result_t *result)
{
    if (!r || (!map && n > 0) || !result)
        return HL_ERR_ARG;
    memset(result, 0, sizeof *result);
    scan_set_t set;
    uint32_t nvalid;
    hl_status_t st = make_set(r, n, scans, odometry, count, check, &set, &nvalid);
    if (st != HL_OK)
        return st;
    result->readings = nvalid;
    result->scans = (uint16_t)count;
    hl_bam_t headings[HL_RELOC_MAX_HEADINGS];
    uint32_t nh = hl_reloc_headings(&r->p, map, n, set.scans, set.offset, set.count, headings,
                                    r->p.headings);
    if (n == 0 || nvalid == 0)
        return HL_ERR_EMPTY;
    result->headings_tried = (uint16_t)nh;
    hl_judge_build(&r->judge, map, n);

    /* stage 2: coarse hypotheses, ranked by what they explain within a coarse cell */
    uint32_t nhyp = 0;
    for (uint32_t i = 0; i < nh; i++) {
        st = coarse_vote(r, map, n, &set, headings[i]);
        if (st == HL_ERR_EMPTY)
            continue;
        if (st != HL_OK)
            return st;
        nhyp = coarse_peaks(r, nhyp);
    }
    for (uint32_t i = 0; i < nhyp; i++)
        r->hyp[i].explained = set_explained(r, &set, r->hyp[i].pose, r->p.coarse_cell_mm);
    sort_by_explained(r->hyp, nhyp);

    /* stage 3: the best of them searched finely, and judged by what they explain */
    uint32_t nfine = 0;
    for (uint32_t i = 0; i < nhyp && nfine < r->p.hypotheses; i++) {
        st = HL_OK;
        if (fine_search(r, map, n, &set, r->hyp[i].pose, &r->fine_hyp[nfine], &st))
            nfine++;
        else if (st != HL_OK)
            return st;
    }
    result->hypotheses_tried = (uint16_t)nfine;
    if (nfine == 0)
        return HL_ERR_EMPTY;
    sort_by_explained(r->fine_hyp, nfine);
    result->pose = r->fine_hyp[0].pose;
    result->score = r->fine_hyp[0].explained;
    result->explained_pct = 100.0 * result->score / nvalid;
    const hypothesis_t *runner = NULL;
    for (uint32_t i = 1; i < nfine && !runner; i++)
        if (distinct(&r->p, r->fine_hyp[i].pose, result->pose))
            runner = &r->fine_hyp[i];
    if (runner) {
        result->have_runner_up = true;
        result->runner_up = runner->pose;
        result->runner_up_score = runner->explained;
        set_edges(r, &set, &r->fine_hyp[0], runner, &result->edge, &result->runner_edge);
    }
    else
        result->edge = result->score;
    result->found = result->explained_pct >= r->p.min_explained_pct &&
                    ((double)result->runner_up_score <= r->p.max_ratio * result->score ||
                     (r->p.max_edge_ratio > 0.0 && 10u * result->edge >= nvalid &&
                      (double)result->runner_edge <= r->p.max_edge_ratio * result->edge));
    return HL_OK;
}

hl_status_t hl_reloc_run_scans(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                               const hl_scan_t *const *scans, const hl_pose_t *odometry,
                               uint32_t count, hl_reloc_result_t *result)
{
    return run_scans(r, map, n, scans, odometry, count, true, result);
}

hl_status_t hl_reloc_run_scans_valid(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                                     const hl_scan_t *const *scans, const hl_pose_t *odometry,
                                     uint32_t count, hl_reloc_result_t *result)
{
    return run_scans(r, map, n, scans, odometry, count, false, result);
}

hl_status_t hl_reloc_run(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                         const hl_scan_t *scan, hl_reloc_result_t *result)
{
    if (!scan)
        return HL_ERR_ARG;
    return hl_reloc_run_scans(r, map, n, &scan, NULL, 1, result);
}

void hl_reloc_judge_poses(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                          const hl_scan_t *scan, const hl_pose_t *poses, uint32_t count,
                          uint32_t *scores)
{
    if (scan && hl_scan_check(scan) != HL_OK) {
        if (scores)
            memset(scores, 0, (size_t)count * sizeof *scores);
        return;
    }
    hl_reloc_judge_poses_valid(r, map, n, scan, poses, count, scores);
}

void hl_reloc_judge_poses_valid(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                                const hl_scan_t *scan, const hl_pose_t *poses, uint32_t count,
                                uint32_t *scores)
{
    if (!scores)
        return;
    memset(scores, 0, (size_t)count * sizeof *scores);
    if (!r || !map || !scan || !poses || n == 0 || n > r->fine_p.max_map_vectors)
        return;
    hl_judge_build(&r->judge, map, n);
    for (uint32_t i = 0; i < count; i++)
        if (hl_pose_in_range(poses[i]))
            scores[i] = hl_judge_score(&r->judge, scan, poses[i]);
}

uint32_t hl_reloc_judge(hl_reloc_t *r, const hl_vector_t *map, uint32_t n,
                        const hl_scan_t *scan, hl_pose_t pose)
{
    uint32_t score;
    hl_reloc_judge_poses(r, map, n, scan, &pose, 1, &score);
    return score;
}
