/* closure.c - loop closure's record of stops, their candidates and matches (closure.h;
 * the correlative search in closure_seek.c, the fit and redraw in closure_fit.c). */
#include "houghloc-internal/closure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "closure_internal.h"
#include "houghloc-internal/walls.h"

#define PI 3.14159265358979323846
#define MAX_EDGES_A_STOP (1 + HL_CLOSURE_MAX_TAKEN)   /* its step and its matches */

hl_closure_t *hl_closure_create(uint32_t stops, uint32_t map_capacity, uint64_t seed)
{
    if (stops < 2 || stops > HL_CLOSURE_MAX_STOPS)
        return NULL;
    hl_closure_t *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->cap = stops;
    c->max_edges = stops * MAX_EDGES_A_STOP;
    c->scans = malloc((size_t)stops * sizeof *c->scans);
    c->poses = malloc((size_t)stops * sizeof *c->poses);
    c->placed = malloc((size_t)stops * sizeof *c->placed);
    c->rng_before = malloc((size_t)stops * sizeof *c->rng_before);
    c->wall_axis = malloc((size_t)stops * sizeof *c->wall_axis);
    c->wall_sigma = malloc((size_t)stops * sizeof *c->wall_sigma);
    c->path = malloc((size_t)stops * sizeof *c->path);
    c->to_draw = malloc((size_t)stops * sizeof *c->to_draw);
    c->headings = malloc((size_t)stops * sizeof *c->headings);
    c->edges = malloc((size_t)c->max_edges * sizeof *c->edges);
    c->graph = hl_posegraph_create(stops, c->max_edges);
    c->map_capacity = map_capacity;
    c->kept = malloc((size_t)map_capacity * sizeof *c->kept);
    c->kept_stamps = malloc((size_t)map_capacity * sizeof *c->kept_stamps);
    c->sub = hl_map_create(map_capacity, seed);
    c->query = malloc(sizeof *c->query);
    c->corr = hl_corr_create();
    c->sub_points = malloc(HL_CORR_MAX_POINTS * sizeof *c->sub_points);
    c->query_points = malloc(HL_CORR_MAX_POINTS * sizeof *c->query_points);
    hl_rng_seed(&c->sub_rng, seed);
    if (!c->scans || !c->poses || !c->placed || !c->rng_before || !c->wall_axis ||
        !c->wall_sigma || !c->path || !c->to_draw || !c->headings || !c->edges ||
        !c->graph || !c->kept || !c->kept_stamps || !c->sub ||
        !c->query || !c->corr || !c->sub_points || !c->query_points) {
        hl_closure_destroy(c);
        return NULL;
    }
    hl_closure_reset(c);
    return c;
}

void hl_closure_destroy(hl_closure_t *c)
{
    if (!c)
        return;
    free(c->scans);
    free(c->poses);
    free(c->placed);
    free(c->rng_before);
    free(c->wall_axis);
    free(c->wall_sigma);
    free(c->path);
    free(c->to_draw);
    free(c->headings);
    free(c->edges);
    free(c->kept);
    free(c->kept_stamps);
    hl_corr_destroy(c->corr);
    free(c->sub_points);
    free(c->query_points);
    hl_posegraph_destroy(c->graph);
    hl_map_destroy(c->sub);
    free(c->query);
    free(c);
}

size_t hl_closure_mem_bytes(const hl_closure_t *c)
{
    return sizeof *c +
           (size_t)c->cap * (sizeof *c->scans + sizeof *c->poses + sizeof *c->placed +
                             sizeof *c->rng_before + sizeof *c->wall_axis +
                             sizeof *c->wall_sigma + sizeof *c->headings +
                             sizeof *c->to_draw) +
           (size_t)c->max_edges * sizeof *c->edges +
           (size_t)c->map_capacity * (sizeof *c->kept + sizeof *c->kept_stamps) +
           hl_posegraph_mem_bytes(c->cap, c->max_edges) + hl_map_mem_bytes(c->sub) +
           sizeof *c->query + (size_t)c->cap * sizeof *c->path + hl_corr_mem_bytes(c->corr) +
           2 * HL_CORR_MAX_POINTS * sizeof *c->sub_points;
}

void hl_closure_square_walls(hl_closure_t *c, double axis_rad)
{
    c->square_walls = true;
    c->building_axis = axis_rad;
}

void hl_closure_redraw_beyond(hl_closure_t *c, double mm)
{
    c->redraw_mm = mm;
}

void hl_closure_redraw_stops_beyond(hl_closure_t *c, double mm)
{
    c->redraw_stop_mm = mm;
}

bool hl_closure_weigh_matches(hl_closure_t *c, double weight)
{
    return hl_posegraph_weigh_matches(c->graph, weight);
}

void hl_closure_reset(hl_closure_t *c)
{
    /* Stamps go on rising, so that vectors of the stops forgotten are never taken for
     * the new ones'. */
    if (c->next == 0)
        c->next = 1;
    c->first = c->next;
    c->count = 0;
    c->n_edges = 0;
    c->n_pending = 0;
    c->redrawing = false;
    c->undrawn = false;
}

uint32_t hl_closure_next_stamp(const hl_closure_t *c)
{
    return c->next;
}

/* Forgets the oldest stop and its edges; the next oldest becomes pose 0, held. */
static void forget_oldest(hl_closure_t *c)
{
    memmove(c->poses, c->poses + 1, (c->count - 1) * sizeof *c->poses);
    memmove(c->placed, c->placed + 1, (c->count - 1) * sizeof *c->placed);
    memmove(c->rng_before, c->rng_before + 1, (c->count - 1) * sizeof *c->rng_before);
    memmove(c->wall_axis, c->wall_axis + 1, (c->count - 1) * sizeof *c->wall_axis);
    memmove(c->wall_sigma, c->wall_sigma + 1, (c->count - 1) * sizeof *c->wall_sigma);
    memmove(c->path, c->path + 1, (c->count - 1) * sizeof *c->path);
    memmove(c->to_draw, c->to_draw + 1, (c->count - 1) * sizeof *c->to_draw);
    uint32_t kept = 0;
    for (uint32_t k = 0; k < c->n_edges; k++) {
        hl_pg_edge_t e = c->edges[k];
        if (e.from == 0)
            continue;
        e.from--;
        e.to--;
        c->edges[kept++] = e;
    }
    c->n_edges = kept;
    c->first++;
    c->count--;
    hl_posegraph_shift(c->graph, 1);
}

/* The axis of the walls in the frame of the scan @p placed (header, "Square walls"), and
 * its sigma; 0 when the scan has too few readings to tell. */
static double walls_seen(const hl_scan_t *placed, double *sigma)
{
    hl_walls_t w = hl_walls_of_scan(placed);
    *sigma = 0;
    if (w.n < HL_CLOSURE_WALL_MIN_READINGS || w.r < HL_CLOSURE_WALL_MIN_R)
        return 0;
    double deg = HL_CLOSURE_WALL_SIGMA_R / w.r;
    *sigma = fmin(HL_CLOSURE_WALL_SIGMA_MAX_DEG, fmax(HL_CLOSURE_WALL_SIGMA_MIN_DEG, deg)) *
             (PI / 180);
    return w.axis;
}

void hl_closure_record(hl_closure_t *c, const hl_scan_t *placed, hl_pose_t pose,
                       hl_rng_t rng_before)
{
    if (c->count == c->cap)
        forget_oldest(c);
    hl_scan_t *s = &c->scans[c->next % c->cap];
    s->count = placed->count;
    memcpy(s->readings, placed->readings, placed->count * sizeof *placed->readings);
    uint32_t i = c->count++;
    c->next++;
    /* While a redraw is spread, the slam tracks in the frame before the fit (its map is
     * still that one) and the fit's poses are in the frame after it. */
    c->poses[i] = c->redrawing || c->undrawn ? hl_pg_from_pose(hl_closure_carry(c, pose))
                                             : hl_pg_from_pose(pose);
    c->placed[i] = pose;
    c->rng_before[i] = rng_before;
    c->to_draw[i] = true;   /* recorded during a redraw: drawn with it, at its fitted pose */
    c->wall_sigma[i] = 0;
    c->wall_axis[i] = c->square_walls ? walls_seen(placed, &c->wall_sigma[i]) : 0;
    c->path[i] = i > 0 ? c->path[i - 1] + hypot(c->poses[i].x - c->poses[i - 1].x,
                                                 c->poses[i].y - c->poses[i - 1].y)
                       : 0;
    if (i == 0)
        c->closed_path = 0;
    if (i > 0 && c->n_edges < c->max_edges)
        c->edges[c->n_edges++] = (hl_pg_edge_t){ i - 1, i,
                                                 hl_pg_between(c->poses[i - 1], c->poses[i]),
                                                 false };
}

bool hl_closure_is_stop(const hl_closure_t *c, hl_pose_t pose, hl_mm_t mm, hl_bam_t turn)
{
    if (c->count == 0 || (mm == 0 && turn == 0))
        return true;
    hl_pose_t last = c->placed[c->count - 1];
    double moved = hypot((double)pose.x_mm - last.x_mm, (double)pose.y_mm - last.y_mm);
    int32_t turned = abs(hl_bam_diff(pose.theta, last.theta));
    return (mm > 0 && moved >= mm) || (turn > 0 && turned >= turn);
}

/* Reading @p r of a scan taken at @p at, as the stop at @p key would have read it:
 * the same point and surface normal, its range and bearing from the stop. false when
 * it cannot be one (out of range, or a normal facing away from the stop). */
static bool reading_from(hl_pose_t key, hl_pose_t at, const hl_reading_t *r, hl_reading_t *out)
{
    double world = hl_bam_to_rad((hl_bam_t)(at.theta + r->bearing));
    double px = at.x_mm + r->range_mm * cos(world) - key.x_mm;
    double py = at.y_mm + r->range_mm * sin(world) - key.y_mm;
    double range = hypot(px, py);
    if (!(range <= HL_RANGE_MAX_MM))
        return false;
    hl_bam_t bearing = (hl_bam_t)(hl_bam_from_rad(atan2(py, px)) - key.theta);
    hl_bam_t normal = hl_reading_normal(r, at.theta);
    int32_t tilt = hl_bam_diff(normal, (hl_bam_t)(key.theta + bearing + HL_BAM_HALF_TURN));
    if (tilt > (int32_t)HL_BAM_QUARTER_TURN || tilt < -(int32_t)HL_BAM_QUARTER_TURN)
        return false;
    *out = *r;
    out->range_mm = (int32_t)lround(range);
    out->bearing = bearing;
    out->tilt = (int16_t)tilt;
    return true;
}

void hl_closure_append(hl_closure_t *c, const hl_scan_t *placed, hl_pose_t pose)
{
    if (c->count == 0)
        return;
    uint32_t i = c->count - 1;
    hl_scan_t *s = scan_of(c, i);
    for (uint32_t k = 0; k < placed->count && s->count < HL_SCAN_MAX_READINGS; k++)
        if (placed->readings[k].valid &&
            reading_from(c->placed[i], pose, &placed->readings[k], &s->readings[s->count]))
            s->count++;
}

uint32_t hl_closure_newest_stamp(const hl_closure_t *c)
{
    return c->first + c->count - 1;
}

hl_pose_t hl_closure_newest(const hl_closure_t *c)
{
    return c->count ? c->placed[c->count - 1] : (hl_pose_t){ 0, 0, 0 };
}

uint32_t hl_closure_candidates(const hl_closure_t *c, uint32_t query, uint32_t *stamps,
                               uint32_t max)
{
    return hl_closure_candidates_within(c, query, HL_CLOSURE_RADIUS_MM, stamps, max);
}

uint32_t hl_closure_candidates_within(const hl_closure_t *c, uint32_t query, double radius_mm,
                                      uint32_t *stamps, uint32_t max)
{
    uint32_t n = 0, k = query - c->first;
    if (k >= c->count || k < HL_CLOSURE_GAP)
        return 0;
    hl_pg_pose_t q = c->poses[k];
    for (uint32_t i = 0; i + HL_CLOSURE_GAP <= k && n < max; i++)
        if (hypot(c->poses[i].x - q.x, c->poses[i].y - q.y) <= radius_mm)
            stamps[n++] = c->first + i;
    return n;
}

const hl_map_t *hl_closure_submap(hl_closure_t *c, uint32_t stamp, uint32_t query)
{
    uint32_t i = stamp - c->first, k = query - c->first;
    if (i >= c->count || k >= c->count)
        return NULL;
    hl_map_restore(c->sub, NULL, 0, 0, c->sub_rng);
    uint32_t q;
    for (int32_t d = -HL_CLOSURE_SIDE; d <= HL_CLOSURE_SIDE; d++)
        if (submap_stop(i, d, k, &q))
            hl_map_add_scan(c->sub, scan_of(c, q), c->placed[q], NULL);
    return c->sub;
}

const hl_scan_t *hl_closure_scan(hl_closure_t *c, uint32_t stamp)
{
    uint32_t i = stamp - c->first;
    return i < c->count ? scan_of(c, i) : NULL;
}

const hl_scan_t *hl_closure_query(hl_closure_t *c, uint32_t stamp, uint32_t max_readings)
{
    const hl_scan_t *scan = hl_closure_scan(c, stamp);
    if (!scan || max_readings == 0 || scan->count <= max_readings)
        return scan;
    /* Evenly through the scan, so that every joined scan keeps its share. */
    c->query->count = 0;
    for (uint32_t k = 0; k < scan->count; k++)
        if ((uint64_t)(k + 1) * max_readings / scan->count >
            (uint64_t)k * max_readings / scan->count)
            c->query->readings[c->query->count++] = scan->readings[k];
    return c->query;
}

hl_pose_t hl_closure_pose(const hl_closure_t *c, uint32_t stamp)
{
    uint32_t i = stamp - c->first;
    return i < c->count ? c->placed[i] : (hl_pose_t){ 0, 0, 0 };
}

bool hl_closure_counts(const hl_loc_result_t *loc, hl_pose_t found, hl_pose_t estimate,
                       uint32_t min_votes, hl_mm_t wild_mm)
{
    int64_t dx = (int64_t)found.x_mm - estimate.x_mm, dy = (int64_t)found.y_mm - estimate.y_mm;
    return hl_loc_confidence(loc) >= HL_CLOSURE_MIN_CONFIDENCE && loc->votes >= min_votes &&
           dx * dx + dy * dy <= (int64_t)wild_mm * wild_mm;
}

bool hl_closure_match(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found)
{
    return hl_closure_match_within(c, stamp, query, found, HL_CLOSURE_GATE_MM,
                                   HL_CLOSURE_GATE_DEG * (PI / 180));
}

/* The matches stop @p k has taken. */
static uint32_t matches_taken(const hl_closure_t *c, uint32_t k)
{
    uint32_t n = 0;
    for (uint32_t e = 0; e < c->n_edges; e++)
        n += c->edges[e].loop && c->edges[e].to == k;
    return n;
}

bool hl_closure_gate(const hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found,
                     double gate_mm, double gate_rad, hl_pg_pose_t *said)
{
    uint32_t i = stamp - c->first, k = query - c->first;
    if (i >= c->count || k >= c->count || i + HL_CLOSURE_GAP > k)
        return false;
    hl_pg_pose_t now = hl_pg_between(c->poses[i], c->poses[k]);
    /* found is where the submap, drawn at the stops' places in the map, has the query.
     * Those are the fitted poses but for their rounding to whole millimetres, unless the
     * last fit was not drawn; measuring from the fitted pose otherwise keeps the rounding
     * out of every earlier result (the goldens, the lab tours). */
    hl_pg_pose_t at = c->undrawn ? hl_pg_from_pose(c->placed[i]) : c->poses[i];
    *said = hl_pg_between(at, hl_pg_from_pose(found));
    return hypot(now.x - said->x, now.y - said->y) <= gate_mm &&
           fabs(remainder(now.theta - said->theta, 2 * PI)) <= gate_rad;
}

bool hl_closure_match_within(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found,
                             double gate_mm, double gate_rad)
{
    hl_pg_pose_t said;
    uint32_t k = query - c->first;
    if (!hl_closure_gate(c, stamp, query, found, gate_mm, gate_rad, &said) ||
        c->n_edges >= c->max_edges || matches_taken(c, k) >= HL_CLOSURE_MAX_TAKEN)
        return false;
    c->edges[c->n_edges++] = (hl_pg_edge_t){ stamp - c->first, k, said, true };
    c->closed_path = fmax(c->closed_path, c->path[k]);
    return true;
}
