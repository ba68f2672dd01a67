/* closure_seek.c - a stop's matches found by a correlative search of the region its
 * drift allows, held until all are sought and taken when two agree (closure.h). */
#include "houghloc-internal/closure.h"

#include <math.h>
#include <stdlib.h>

#include "closure_internal.h"

#define PI 3.14159265358979323846

void hl_closure_search_region(const hl_closure_t *c, uint32_t query, double *mm, double *rad)
{
    uint32_t k = query - c->first;
    double driven = k < c->count ? fmax(0, c->path[k] - c->closed_path) : 0;
    *mm = fmin(HL_CLOSURE_SEARCH_MAX_MM,
               HL_CLOSURE_SEARCH_MM + HL_CLOSURE_SEARCH_GROWTH * driven);
    *rad = fmin(HL_CLOSURE_SEARCH_MAX_DEG,
                HL_CLOSURE_SEARCH_DEG + HL_CLOSURE_SEARCH_DEG_PER_M * driven / 1000) *
           (PI / 180);
}

uint32_t hl_closure_submap_points(const hl_closure_t *c, uint32_t stamp, uint32_t query,
                                  hl_corr_point_t *out, uint32_t max)
{
    uint32_t i = stamp - c->first, k = query - c->first, n = 0;
    if (i >= c->count || k >= c->count)
        return 0;
    uint32_t q;
    for (int32_t d = -HL_CLOSURE_SIDE; d <= HL_CLOSURE_SIDE; d++)
        if (submap_stop(i, d, k, &q))
            n = hl_corr_points(scan_of(c, q), hl_pg_from_pose(c->placed[q]),
                               out, n, max);
    return n;
}

bool hl_closure_seek(hl_closure_t *c, uint32_t stamp, uint32_t query, uint32_t max_readings,
                     hl_pose_t *found)
{
    const hl_scan_t *scan = hl_closure_query(c, query, max_readings);
    uint32_t n_sub = hl_closure_submap_points(c, stamp, query, c->sub_points, HL_CORR_MAX_POINTS);
    uint32_t n_query = scan ? hl_corr_points(scan, (hl_pg_pose_t){ 0, 0, 0 }, c->query_points,
                                             0, HL_CORR_MAX_POINTS)
                            : 0;
    double mm, rad;
    hl_closure_search_region(c, query, &mm, &rad);
    /* From where the map has the query, as the submap is drawn where the map has its
     * stops. */
    hl_pg_pose_t center = hl_pg_from_pose(hl_closure_pose(c, query));
    hl_corr_params_t search = { mm, rad, HL_CLOSURE_CORR_MIN_SCORE, HL_CLOSURE_CORR_RUNNER_UP,
                                HL_CLOSURE_CORR_DISTINCT_MM,
                                HL_CLOSURE_CORR_DISTINCT_DEG * (PI / 180) };
    hl_corr_result_t r;
    if (!hl_corr_search(c->corr, c->sub_points, n_sub, c->query_points, n_query, center,
                        &search, &r) ||
        !r.matched)
        return false;
    *found = hl_pg_to_pose(r.pose);
    return true;
}

void hl_closure_pend(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found)
{
    if (c->n_pending > 0 && c->pending_query != query)
        c->n_pending = 0;
    if (c->n_pending == HL_CLOSURE_MAX_MATCHES)
        return;
    double mm, rad;
    hl_closure_search_region(c, query, &mm, &rad);
    /* The region is a square about the centre, and a polish may leave it by a cell. */
    c->pending[c->n_pending++] = (struct pending){ stamp, found, mm * sqrt(2) + HL_CORR_CELL_MM,
                                                   rad * 1.1 };
    c->pending_query = query;
}

/* Whether pending matches @p a and @p b put the query at the same place in the map. */
static bool agree(const struct pending *a, const struct pending *b)
{
    double dx = (double)a->found.x_mm - b->found.x_mm, dy = (double)a->found.y_mm - b->found.y_mm;
    return hypot(dx, dy) <= HL_CLOSURE_CORR_AGREE_MM &&
           abs(hl_bam_diff(a->found.theta, b->found.theta)) <=
               hl_bam_from_deg(HL_CLOSURE_CORR_AGREE_DEG);
}

uint32_t hl_closure_settle(hl_closure_t *c, uint32_t query)
{
    uint32_t n = c->pending_query == query ? c->n_pending : 0, best = 0, size = 0;
    c->n_pending = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t m = 0;
        for (uint32_t j = 0; j < n; j++)
            m += agree(&c->pending[i], &c->pending[j]);
        if (m > size) {
            size = m;
            best = i;
        }
    }
    if (size < HL_CLOSURE_CORR_AGREEING)
        return 0;
    /* The group is taken whole or not at all: a group some of whose matches lie beyond
     * the gate agrees on a place the fit does not allow. Taking the rest left one match
     * of such a group on intel, 1.3 m wrong (a corridor's alias: its two partners just
     * beyond the gate), which nothing right was there to outweigh. */
    hl_pg_pose_t said;
    for (uint32_t j = 0; j < n; j++) {
        const struct pending *p = &c->pending[j];
        if (agree(&c->pending[best], p) &&
            !hl_closure_gate(c, p->stamp, query, p->found, p->gate_mm, p->gate_rad, &said))
            return 0;
    }
    uint32_t taken = 0;
    for (uint32_t j = 0; j < n; j++) {
        const struct pending *p = &c->pending[j];
        if (agree(&c->pending[best], p))
            taken += hl_closure_match_within(c, p->stamp, query, p->found, p->gate_mm,
                                             p->gate_rad);
    }
    return taken;
}
