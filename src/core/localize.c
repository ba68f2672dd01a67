/*
 * localize.c - the Hough vote (paper, sections 5-6): pairs of <test reading, map vector>
 * whose normals agree vote for the robot position map point - R(theta) * reading, into
 * an (x, y, theta) raster; blur; peak. Formats: houghloc/fixed.h. Allocation: create only.
 *
 * A search without a prior over a raster of at least TILED_MIN_CELLS (a whole map's)
 * blurs and searches only the tiles near its votes (tiles.h): the same surface and peak,
 * without passes over the millions of cells no vote reaches.
 */
#include "houghloc-internal/localize.h"
#include "houghloc-internal/fixed.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "blur.h"
#include "gate.h"
#include "peak.h"
#include "prior.h"
#include "simd.h"
#include "tiles.h"

#include "loc_params.h"
#include "valid_scan.h"
#include "vgroup.h"
#include "votecast.h"
#include "votelone.h"

struct hl_localizer {
    hl_loc_params_t p;
    hl_kernel_t kx, kt;
    size_t mem_bytes;

    /* the raster, [nt][ny][nx], max_cells each */
    uint16_t *votes;
    uint32_t *buf_a, *buf_b;
    const uint32_t *blurred;    /* buf_a or buf_b after the last run */
    uint32_t *wx, *wy, *wt;     /* prior weights, Q8 */
    int32_t wlen;               /* length of wx and wy */

    /* the map as the vote loop reads it, and the groups one reading can reach */
    hl_vgroups_t groups;
    uint32_t *cand;
    hl_votelone_t lone;     /* the loop of a map of lone vectors (votelone.h), if capacity */
    int32_t slice_diff[2 * HL_LOC_MAX_HALF_STEPS + 2];  /* a group's weights, differenced */

    /* the valid readings of the scan */
    int32_t *range;
    hl_bam_t *bearing;
    int16_t *tilt;      /* the readings' normals' turns from their beams (scan.h) */
    uint16_t *stamps;   /* vote_once: per cell, the last reading that voted there */

    hl_loc_surface_t surface;   /* geometry of the last run */

    /* The sparse path (tiles.h), allocated when max_cells reaches TILED_MIN_CELLS. The
     * vote raster is zero between runs but for what the last ones wrote: the tiles
     * listed as voted in `tiles`, and the first votes_dirty cells (a plain run's). */
    hl_tiles_t tiles;
    bool tiles_on;
    size_t votes_dirty;
    bool sparse;            /* the last run took the sparse path: its blurred tiles are in
                               buf_a, and surface.cells NULL until laid out in buf_b */
};

/* The smallest raster searched by the sparse path: smaller ones stay in the caches
 * anyway, and a window's raster is mostly voted. */
#define TILED_MIN_CELLS (1u << 18)

void hl_loc_destroy(hl_localizer_t *loc)
{
    if (!loc)
        return;
    free(loc->votes);
    free(loc->buf_a);
    free(loc->buf_b);
    free(loc->wx);
    free(loc->wy);
    free(loc->wt);
    hl_vgroups_free(&loc->groups);
    hl_votelone_free(&loc->lone);
    free(loc->cand);
    free(loc->range);
    free(loc->bearing);
    free(loc->tilt);
    free(loc->stamps);
    hl_tiles_free(&loc->tiles);
    free(loc);
}

static void *alloc_counted(hl_localizer_t *loc, size_t n, size_t size)
{
    loc->mem_bytes += n * size;
    return calloc(n, size);
}

hl_localizer_t *hl_loc_create(const hl_loc_params_t *params)
{
    if (hl_loc_params_error(params))
        return NULL;
    hl_localizer_t *loc = calloc(1, sizeof *loc);
    if (!loc)
        return NULL;
    loc->p = *params;
    loc->mem_bytes = sizeof *loc;
    const hl_loc_params_t *p = &loc->p;
    /* A raster side cannot exceed max_cells cells, nor HL_LOC_MAX_SIDE_MM. */
    int64_t side = HL_LOC_MAX_SIDE_MM / p->cell_mm + 2;
    loc->wlen = (int32_t)(side < p->max_cells ? side : p->max_cells);
    int32_t max_nt = hl_loc_slices(p, true);

    loc->votes = alloc_counted(loc, p->max_cells, sizeof *loc->votes);
    loc->buf_a = alloc_counted(loc, p->max_cells, sizeof *loc->buf_a);
    loc->buf_b = alloc_counted(loc, p->max_cells, sizeof *loc->buf_b);
    loc->wx = alloc_counted(loc, (size_t)loc->wlen, sizeof *loc->wx);
    loc->wy = alloc_counted(loc, (size_t)loc->wlen, sizeof *loc->wy);
    loc->wt = alloc_counted(loc, (size_t)max_nt, sizeof *loc->wt);
    bool groups_ok = hl_vgroups_init(&loc->groups, p->max_map_vectors, p->group_mm);
    loc->mem_bytes += hl_vgroups_mem_bytes(&loc->groups);
    loc->cand = alloc_counted(loc, p->max_map_vectors, sizeof *loc->cand);
    bool lone = p->group_mm == 0 && !p->vote_once;

    loc->range = alloc_counted(loc, HL_SCAN_MAX_READINGS, sizeof *loc->range);
    loc->bearing = alloc_counted(loc, HL_SCAN_MAX_READINGS, sizeof *loc->bearing);
    loc->tilt = alloc_counted(loc, HL_SCAN_MAX_READINGS, sizeof *loc->tilt);
    if (p->vote_once)
        loc->stamps = alloc_counted(loc, p->max_cells, sizeof *loc->stamps);
    bool tiles_ok = true;
    if (p->max_cells >= TILED_MIN_CELLS) {
        tiles_ok = loc->tiles_on = hl_tiles_init(&loc->tiles, p->max_cells, loc->wlen, max_nt);
        loc->mem_bytes += hl_tiles_mem_bytes(&loc->tiles);
    }
    bool lone_ok = !lone || hl_votelone_init(&loc->lone, p->max_map_vectors,
                                             loc->tiles_on ? loc->tiles.capacity : 0);
    loc->mem_bytes += hl_votelone_mem_bytes(&loc->lone);
    if (!loc->votes || !loc->buf_a || !loc->buf_b || !loc->wx || !loc->wy || !loc->wt ||
        !groups_ok || !lone_ok || !loc->cand || !loc->range || !loc->bearing || !loc->tilt ||
        (p->vote_once && !loc->stamps) || !tiles_ok) {
        hl_loc_destroy(loc);
        return NULL;
    }
    hl_kernel_gaussian(&loc->kx, (double)p->blur_sigma_mm / p->cell_mm);
    hl_kernel_gaussian(&loc->kt, p->theta_step ? (double)p->blur_sigma_theta / p->theta_step : 0);
    return loc;
}

const hl_loc_params_t *hl_loc_get_params(const hl_localizer_t *loc)
{
    return &loc->p;
}

size_t hl_loc_mem_bytes(const hl_localizer_t *loc)
{
    return loc->mem_bytes;
}

double hl_loc_confidence(const hl_loc_result_t *r)
{
    if (!r || r->score == 0)
        return 0.0;
    double c = 1.0 - (double)r->second_score / (double)r->score;
    return c < 0 ? 0 : c;
}

/* Copies the valid readings that vote (every reading_stride-th of the scan) out of it;
 * returns their count and longest range. */
static uint32_t gather_readings(hl_localizer_t *loc, const hl_scan_t *scan,
                                int32_t *max_range)
{
    uint32_t n = 0;
    *max_range = 0;
    for (uint32_t i = 0; i < scan->count; i++) {
        const hl_reading_t *r = &scan->readings[i];
        if (!r->valid)
            continue;
        if (i % loc->p.reading_stride)
            continue;
        loc->range[n] = r->range_mm;
        loc->bearing[n] = r->bearing;
        loc->tilt[n] = r->tilt;
        if (r->range_mm > *max_range)
            *max_range = r->range_mm;
        n++;
    }
    return n;
}

/* The xy raster: a window centred on the prediction, or the map's bounding box. */
static hl_status_t place_raster(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                                const hl_loc_query_t *q, hl_loc_surface_t *s)
{
    int32_t cell = loc->p.cell_mm;
    if (q->window_mm > 0) {
        s->nx = s->ny = hl_loc_window_cells(&loc->p, q->window_mm);
        s->x0_mm = q->predicted.x_mm - s->nx * cell / 2;
        s->y0_mm = q->predicted.y_mm - s->ny * cell / 2;
    } else {
        int32_t x0 = map[0].x_mm, x1 = x0, y0 = map[0].y_mm, y1 = y0;
        for (uint32_t i = 1; i < n; i++) {
            x0 = map[i].x_mm < x0 ? map[i].x_mm : x0;
            x1 = map[i].x_mm > x1 ? map[i].x_mm : x1;
            y0 = map[i].y_mm < y0 ? map[i].y_mm : y0;
            y1 = map[i].y_mm > y1 ? map[i].y_mm : y1;
        }
        s->nx = (x1 - x0) / cell + 1;
        s->ny = (y1 - y0) / cell + 1;
        s->x0_mm = x0;
        s->y0_mm = y0;
    }
    s->nt = hl_loc_slices(&loc->p, q->search_theta);
    s->cell_mm = cell;
    s->theta_step = q->search_theta ? loc->p.theta_step : 0;
    int32_t half = q->search_theta ? loc->p.theta_half_steps : 0;
    s->theta0 = (hl_bam_t)(q->predicted.theta - half * loc->p.theta_step);
    if ((int64_t)s->nx * cell >= HL_LOC_MAX_SIDE_MM || (int64_t)s->ny * cell >= HL_LOC_MAX_SIDE_MM ||
        (int64_t)s->nx * s->ny * s->nt > loc->p.max_cells)
        return HL_ERR_CAPACITY;
    return HL_OK;
}

/* Groups the map vectors that can vote inside the raster (vgroup.h). */
static void group_map(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                      const hl_loc_surface_t *s, int32_t max_range)
{
    /* A vote lands at map point - reading, so only vectors within the longest range of
     * the raster can land in it. */
    int64_t xlo = (int64_t)s->x0_mm - max_range - 1;
    int64_t xhi = (int64_t)s->x0_mm + (int64_t)s->nx * s->cell_mm + max_range + 1;
    int64_t ylo = (int64_t)s->y0_mm - max_range - 1;
    int64_t yhi = (int64_t)s->y0_mm + (int64_t)s->ny * s->cell_mm + max_range + 1;
    hl_vgroups_build(&loc->groups, map, n, xlo, xhi, ylo, yhi, s->x0_mm, s->y0_mm);
}

/* The score of one cell of the last run's grid (the sparse path's: its blocks). */
static uint32_t score_at(hl_localizer_t *loc, const hl_grid_t *g, int32_t ix, int32_t iy,
                         int32_t it)
{
    if (loc->sparse)
        return hl_tiles_cell(&loc->tiles, ix, iy, it);
    return hl_grid_score(g, ix, iy, it);
}

/* Interpolated offset along one axis of the grid, in units of `step`. */
static int32_t axis_offset(hl_localizer_t *loc, const hl_grid_t *g, const hl_peak_t *pk,
                           int axis, int32_t step)
{
    int32_t i[3] = { pk->ix, pk->iy, pk->it };
    int32_t n[3] = { g->nx, g->ny, g->nt };
    if (step == 0 || i[axis] == 0 || i[axis] == n[axis] - 1)
        return 0;
    int32_t lo[3] = { i[0], i[1], i[2] }, hi[3] = { i[0], i[1], i[2] };
    lo[axis]--;
    hi[axis]++;
    return hl_peak_offset(score_at(loc, g, lo[0], lo[1], lo[2]), pk->score,
                          score_at(loc, g, hi[0], hi[1], hi[2]), step);
}

static hl_status_t run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, const hl_loc_query_t *query, bool check,
                       hl_loc_result_t *result);

hl_status_t hl_loc_run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, const hl_loc_query_t *query,
                       hl_loc_result_t *result)
{
    return run(loc, map, n, scan, query, true, result);
}

hl_status_t hl_loc_run_valid(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                             const hl_scan_t *scan, const hl_loc_query_t *query,
                             hl_loc_result_t *result)
{
    return run(loc, map, n, scan, query, false, result);
}

/* hl_loc_run; the scan checked only when @p check. */
static hl_status_t run(hl_localizer_t *loc, const hl_vector_t *map, uint32_t n,
                       const hl_scan_t *scan, const hl_loc_query_t *query, bool check,
                       hl_loc_result_t *result)
{
    if (!loc || (!map && n > 0) || !scan || !query || !result)
        return HL_ERR_ARG;
    memset(result, 0, sizeof *result);
    if ((check && hl_scan_check(scan) != HL_OK) || !hl_pose_in_range(query->predicted) ||
        query->window_mm < 0 || query->window_mm > HL_LOC_MAX_SIDE_MM / 2)
        return HL_ERR_RANGE;
    if (n > loc->p.max_map_vectors)
        return HL_ERR_CAPACITY;
    int32_t max_range;
    uint32_t nread = gather_readings(loc, scan, &max_range);
    if (n == 0 || nread == 0)
        return HL_ERR_EMPTY;

    hl_loc_surface_t s;
    hl_status_t st = place_raster(loc, map, n, query, &s);
    if (st != HL_OK)
        return st;
    size_t cells = (size_t)s.nx * s.ny * s.nt;
    bool tiled = loc->tiles_on && !query->use_prior && cells >= TILED_MIN_CELLS &&
                 hl_tiles_fit(&loc->tiles, s.nx, s.ny, s.nt);
    /* The votes start from zero: what the last runs wrote is cleared. */
    memset(loc->votes, 0, loc->votes_dirty * sizeof *loc->votes);
    loc->votes_dirty = 0;
    if (loc->tiles_on)
        hl_tiles_clear_votes(&loc->tiles, loc->votes);
    if (tiled)
        hl_tiles_begin(&loc->tiles, s.nx, s.ny, s.nt);
    else
        loc->votes_dirty = cells;
    loc->sparse = false;
    if (loc->stamps)
        memset(loc->stamps, 0, cells * sizeof *loc->stamps);
    group_map(loc, map, n, &s, max_range);

    hl_vote_ctx_t c = { .nx = s.nx, .ny = s.ny, .nt = s.nt,
                        .width_q8 = (uint32_t)(s.nx * s.cell_mm) * 256u,
                        .height_q8 = (uint32_t)(s.ny * s.cell_mm) * 256u,
                        .recip = (1ull << 32) / (uint32_t)s.cell_mm + 1,
                        .most = tiled ? loc->tiles.most : NULL,
                        .ntx = tiled ? (uint32_t)loc->tiles.ntx : 0,
                        .cell_q8 = s.cell_mm * 256 };
    if (loc->lone.capacity)
        hl_votelone_prepare(&loc->lone, loc->groups.gx, loc->groups.gy, loc->groups.ngroups,
                            c.cell_q8);
    hl_vote_inputs_t in = { &loc->groups, loc->cand, loc->slice_diff, loc->stamps,
                            &loc->lone, loc->votes, loc->range, loc->bearing, loc->tilt,
                            loc->p.normal_gate };
    hl_vote_cast(&in, nread, &s, &c);
    if (tiled && loc->lone.capacity)
        hl_votelone_fold(&loc->lone, loc->tiles.most, (uint32_t)(loc->tiles.ntx * loc->tiles.nty));
    if (tiled)
        hl_tiles_take_votes(&loc->tiles);
    result->votes = c.votes;
    result->pairs = c.pairs;
    if (c.votes == 0)
        return HL_ERR_EMPTY;

    if (tiled) {    /* blurred as the search needs it (hl_tiles_search) */
        loc->blurred = loc->buf_a;  /* the tiles' blocks, not a raster */
        s.cells = NULL;
    } else {
        loc->blurred = hl_blur3(loc->votes, s.nx, s.ny, s.nt, &loc->kx, &loc->kx, &loc->kt,
                                loc->buf_a, loc->buf_b);
        s.cells = loc->blurred;
    }
    s.votes = loc->votes;
    loc->surface = s;
    loc->sparse = tiled;

    /* The blur's other buffer is free now: hl_peak_find keeps its row maxima there
     * (ny * nt <= max_cells). */
    hl_grid_t g = { .cells = loc->blurred, .nx = s.nx, .ny = s.ny, .nt = s.nt,
                    .row_max = loc->blurred == loc->buf_a ? loc->buf_b : loc->buf_a };
    if (query->use_prior) {
        hl_prior_weights(&s, query->predicted, loc->p.prior_sigma_mm, loc->p.prior_sigma_theta,
                         loc->wx, loc->wy, loc->wt);
        g.wx = loc->wx;
        g.wy = loc->wy;
        g.wt = loc->wt;
    }
    hl_peak_t pk;
    int found = tiled ? hl_tiles_search(&loc->tiles, loc->votes, &loc->kx, &loc->kx, &loc->kt,
                                        loc->buf_a, s.cell_mm, loc->p.peak_separation_mm, &pk)
                      : hl_peak_find(&g, s.cell_mm, loc->p.peak_separation_mm, &pk);
    if (!found)
        return HL_ERR_EMPTY;
    result->ix = pk.ix;
    result->iy = pk.iy;
    result->it = pk.it;
    result->score = pk.score;
    result->second_score = pk.second;
    result->peak = pk.score;
    result->second = pk.second;
    if (query->use_prior) {     /* the same cells without the prior's weights */
        hl_grid_t votes_only = { .cells = s.cells, .nx = s.nx, .ny = s.ny, .nt = s.nt };
        result->peak = hl_grid_score(&votes_only, pk.ix, pk.iy, pk.it);
        result->second = hl_peak_second(&votes_only, s.cell_mm, loc->p.peak_separation_mm,
                                        pk.ix, pk.iy);
    }
    result->cell_pose.x_mm = s.x0_mm + pk.ix * s.cell_mm + s.cell_mm / 2;
    result->cell_pose.y_mm = s.y0_mm + pk.iy * s.cell_mm + s.cell_mm / 2;
    result->cell_pose.theta = (hl_bam_t)(s.theta0 + pk.it * s.theta_step);
    result->pose.x_mm = result->cell_pose.x_mm + axis_offset(loc, &g, &pk, 0, s.cell_mm);
    result->pose.y_mm = result->cell_pose.y_mm + axis_offset(loc, &g, &pk, 1, s.cell_mm);
    result->pose.theta = (hl_bam_t)(result->cell_pose.theta +
                                    axis_offset(loc, &g, &pk, 2, s.theta_step));
    return HL_OK;
}

void hl_loc_get_surface(hl_localizer_t *loc, hl_loc_surface_t *out)
{
    if (loc->sparse && !loc->surface.cells) {
        /* the sparse path's blocks laid out as a raster, the first time one is asked for */
        const hl_loc_surface_t *s = &loc->surface;
        memset(loc->buf_b, 0, (size_t)s->nx * s->ny * s->nt * sizeof *loc->buf_b);
        hl_tiles_lay_out(&loc->tiles, loc->buf_b);
        loc->surface.cells = loc->buf_b;
    }
    *out = loc->surface;
}
