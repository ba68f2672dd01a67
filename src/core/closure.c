/* closure.c - loop closure's record of stops, matches and fit (closure.h). */
#include "houghloc-internal/closure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/posegraph.h"

#define PI 3.14159265358979323846
#define MAX_EDGES_A_STOP (1 + HL_CLOSURE_MAX_MATCHES)   /* its step and its matches */
#define REDRAW_LEVER_MM 5000.0  /* a turn of a stop counts as its move of a wall this far */

struct hl_closure {
    uint32_t cap;           /* stops recorded at most */
    uint32_t first;         /* the oldest recorded stop's stamp */
    uint32_t count;         /* stops recorded: stamps first .. first + count - 1 */
    uint32_t next;          /* the next stop's stamp (from 1: 0 is no stop's) */
    hl_scan_t *scans;       /* [cap] by stamp % cap: the scan as mapped */
    /* [cap] by stamp - first: */
    hl_pg_pose_t *poses;    /* fitted */
    hl_pose_t *placed;      /* where the stop's vectors lie in the map (poses, rounded, as
                               of the last fit) */
    hl_rng_t *rng_before;   /* the map's culling generator before the stop was drawn */
    double *wall_axis;      /* the walls' axis in the stop's frame, radians (square walls;
                               its scan's, worked out once when recorded rather than a
                               sine and a cosine a reading of every stop at every fit) */
    double *wall_sigma;     /* ... its sigma, radians; 0: the stop says nothing of walls */
    double *path;           /* the path driven to the stop since the record began, mm */
    double closed_path;     /* ... to the newest stop a match was taken for */
    hl_pg_heading_t *headings;  /* [cap] scratch: the stops' headings for a fit */
    bool square_walls;
    double building_axis;   /* radians */
    hl_pg_edge_t *edges;    /* steps and matches, poses by stamp - first */
    uint32_t n_edges, max_edges;
    hl_posegraph_t *graph;
    hl_vector_t *kept;      /* [map_capacity] scratch: the vectors a fit does not redraw */
    uint32_t map_capacity;
    hl_map_t *sub;          /* the map a match is sought in */
    hl_scan_t *query;       /* the scan a match is sought for, thinned (hl_closure_query) */
    hl_corr_t *corr;        /* the correlative search (hl_closure_seek) ... */
    hl_corr_point_t *sub_points, *query_points; /* ... its submap's and query's points */
    struct pending {        /* ... the matches it found for one query, not yet settled */
        uint32_t stamp;
        hl_pose_t found;
        double gate_mm, gate_rad;
    } pending[HL_CLOSURE_MAX_MATCHES];
    uint32_t n_pending, pending_query;
    /* A redraw spread over the scans that follow a fit (hl_closure_fit_spread): */
    bool redrawing;
    uint32_t next_drawn;    /* ... the stamp of the next stop to draw into the shadow map */
    hl_pg_pose_t fit_before, fit_after; /* ... the newest stop fitted, before and after the
                                           fit: the frame change the slam's pose and the
                                           stops recorded meanwhile go through */
    hl_rng_t sub_rng;       /* ... started afresh each time */
    double redraw_mm;       /* a fit is drawn only when it moves a stop this far (0: always) */
    bool undrawn;           /* the last fit was not drawn: the map (and the slam) are in the
                               frame before it, the fit's poses after it */
};

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
    c->headings = malloc((size_t)stops * sizeof *c->headings);
    c->edges = malloc((size_t)c->max_edges * sizeof *c->edges);
    c->graph = hl_posegraph_create(stops, c->max_edges);
    c->map_capacity = map_capacity;
    c->kept = malloc((size_t)map_capacity * sizeof *c->kept);
    c->sub = hl_map_create(map_capacity, seed);
    c->query = malloc(sizeof *c->query);
    c->corr = hl_corr_create();
    c->sub_points = malloc(HL_CORR_MAX_POINTS * sizeof *c->sub_points);
    c->query_points = malloc(HL_CORR_MAX_POINTS * sizeof *c->query_points);
    hl_rng_seed(&c->sub_rng, seed);
    if (!c->scans || !c->poses || !c->placed || !c->rng_before || !c->wall_axis ||
        !c->wall_sigma || !c->path || !c->headings || !c->edges || !c->graph || !c->kept || !c->sub ||
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
    free(c->headings);
    free(c->edges);
    free(c->kept);
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
                             sizeof *c->wall_sigma + sizeof *c->headings) +
           (size_t)c->max_edges * sizeof *c->edges + (size_t)c->map_capacity * sizeof *c->kept +
           hl_posegraph_mem_bytes(c->cap, c->max_edges) + hl_map_mem_bytes(c->sub) +
           sizeof *c->query;
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

/* The record's scan of the stop @p i stops after the oldest recorded (its stamp is
 * first + i; the scans are kept by stamp, round the record). */
static hl_scan_t *scan_of(hl_closure_t *c, uint32_t i)
{
    return &c->scans[(c->first + i) % c->cap];
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
    double c4 = 0, s4 = 0;
    uint32_t n = 0;
    for (uint32_t k = 0; k < placed->count; k++) {
        const hl_reading_t *r = &placed->readings[k];
        if (!r->valid)
            continue;
        double normal = hl_bam_to_rad(hl_reading_normal(r, 0));   /* the robot's frame */
        c4 += cos(4 * normal);
        s4 += sin(4 * normal);
        n++;
    }
    *sigma = 0;
    double r = n ? hypot(c4, s4) / n : 0;
    if (n < HL_CLOSURE_WALL_MIN_READINGS || r < HL_CLOSURE_WALL_MIN_R)
        return 0;
    double deg = HL_CLOSURE_WALL_SIGMA_R / r;
    *sigma = fmin(HL_CLOSURE_WALL_SIGMA_MAX_DEG, fmax(HL_CLOSURE_WALL_SIGMA_MIN_DEG, deg)) *
             (PI / 180);
    return atan2(s4, c4) / 4;
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
    for (int32_t d = -HL_CLOSURE_SIDE; d <= HL_CLOSURE_SIDE; d++) {
        int64_t q = (int64_t)i + d;
        if (q >= 0 && q + HL_CLOSURE_GAP <= k)
            n = hl_corr_points(&c->scans[(c->first + (uint32_t)q) % c->cap],
                               hl_pg_from_pose(c->placed[q]), out, n, max);
    }
    return n;
}

const hl_map_t *hl_closure_submap(hl_closure_t *c, uint32_t stamp, uint32_t query)
{
    uint32_t i = stamp - c->first, k = query - c->first;
    if (i >= c->count || k >= c->count)
        return NULL;
    hl_map_restore(c->sub, NULL, 0, 0, c->sub_rng);
    for (int32_t d = -HL_CLOSURE_SIDE; d <= HL_CLOSURE_SIDE; d++) {
        int64_t q = (int64_t)i + d;
        if (q >= 0 && q + HL_CLOSURE_GAP <= k)
            hl_map_add_scan(c->sub, scan_of(c, (uint32_t)q),
                            c->placed[q], NULL);
    }
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

bool hl_closure_match_within(hl_closure_t *c, uint32_t stamp, uint32_t query, hl_pose_t found,
                             double gate_mm, double gate_rad)
{
    uint32_t i = stamp - c->first, k = query - c->first;
    if (i >= c->count || k >= c->count || i + HL_CLOSURE_GAP > k ||
        c->n_edges >= c->max_edges)
        return false;
    hl_pg_pose_t now = hl_pg_between(c->poses[i], c->poses[k]);
    /* found is where the submap, drawn at the stops' places in the map, has the query.
     * Those are the fitted poses but for their rounding to whole millimetres, unless the
     * last fit was not drawn; measuring from the fitted pose otherwise keeps the rounding
     * out of every earlier result (the goldens, the lab tours). */
    hl_pg_pose_t at = c->undrawn ? hl_pg_from_pose(c->placed[i]) : c->poses[i];
    hl_pg_pose_t said = hl_pg_between(at, hl_pg_from_pose(found));
    if (hypot(now.x - said.x, now.y - said.y) > gate_mm ||
        fabs(remainder(now.theta - said.theta, 2 * PI)) > gate_rad)
        return false;
    c->edges[c->n_edges++] = (hl_pg_edge_t){ i, k, said, true };
    c->closed_path = fmax(c->closed_path, c->path[k]);
    return true;
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
    uint32_t taken = 0;
    for (uint32_t j = 0; j < n; j++) {
        const struct pending *p = &c->pending[j];
        if (agree(&c->pending[best], p))
            taken += hl_closure_match_within(c, p->stamp, query, p->found, p->gate_mm,
                                             p->gate_rad);
    }
    return taken;
}

/* The map drawn again: the vectors of stops no longer recorded where they are, then every
 * recorded stop's scan at its fitted pose, in order, through the map's own density bound
 * and cull, with the culling generator as it was before the oldest was drawn: the map the
 * slam would hold had the stops always been where the fit puts them. Two other ways, on
 * simulated lab tours: moving each vector with its stop kept what the culls had decided
 * at the drifted poses (a wall drawn twice, the drifted copy the better confirmed; tours
 * 1-8, 364 mm mean RMSE against 226); drawing again with the generator where it was
 * made every fit cull other vectors (tours 1-24, 289 mm against 237). docs/results/relocalization.md. */
static void redraw(hl_closure_t *c, hl_map_t *map)
{
    const hl_vector_t *v = hl_map_vectors(map);
    const uint32_t *stamps = hl_map_stamps(map);
    uint32_t n = 0, count = hl_map_count(map);
    for (uint32_t i = 0; i < count && n < c->map_capacity; i++)
        if (stamps[i] - c->first >= c->count)     /* wraps below first */
            c->kept[n++] = v[i];
    /* Cannot fail: n fits the map, and its own vectors are in range. */
    hl_map_restore(map, c->kept, n, hl_count_next(hl_map_version(map)), c->rng_before[0]);
    for (uint32_t i = 0; i < c->count; i++) {
        hl_map_set_stamp(map, c->first + i);
        hl_map_add_scan(map, scan_of(c, i), c->placed[i], NULL);
    }
}

/* Each stop's heading against the world from the walls it saw: of the four that put the
 * walls square to the building, the one nearest its heading now. @return how many. */
static uint32_t wall_headings(hl_closure_t *c)
{
    uint32_t n = 0;
    for (uint32_t i = 1; c->square_walls && i < c->count; i++) {
        if (c->wall_sigma[i] <= 0)
            continue;
        double theta = c->poses[i].theta;
        double off = remainder(4 * (theta + c->wall_axis[i] - c->building_axis), 2 * PI) / 4;
        c->headings[n++] = (hl_pg_heading_t){ i, theta - off, c->wall_sigma[i] };
    }
    return n;
}

/* Fits every stop to its steps and matches (the poses only). */
static uint32_t fit_poses(hl_closure_t *c)
{
    uint32_t n_headings = wall_headings(c);
    return hl_posegraph_fit(c->graph, c->poses, c->count, c->edges, &c->n_edges, c->headings,
                            n_headings, HL_CLOSURE_SIGMA_MM, HL_CLOSURE_SIGMA_DEG * (PI / 180),
                            HL_CLOSURE_KERNEL, HL_CLOSURE_OUTLIER);
}

uint32_t hl_closure_fit(hl_closure_t *c, hl_map_t *map)
{
    c->fit_before = c->poses[c->count - 1];
    uint32_t dropped = fit_poses(c);
    c->fit_after = c->poses[c->count - 1];
    for (uint32_t i = 0; i < c->count; i++)
        c->placed[i] = hl_pg_to_pose(c->poses[i]);
    redraw(c, map);
    return dropped;
}

/* Whether the fit moved some stop farther than redraw_mm from where its vectors lie, or
 * turned it enough to move a wall 5 m away that far. */
static bool moved_beyond(const hl_closure_t *c)
{
    for (uint32_t i = 0; i < c->count; i++) {
        hl_pg_pose_t at = hl_pg_from_pose(c->placed[i]);
        double turn = fabs(remainder(c->poses[i].theta - at.theta, 2 * PI));
        if (hypot(c->poses[i].x - at.x, c->poses[i].y - at.y) > c->redraw_mm ||
            turn * REDRAW_LEVER_MM > c->redraw_mm)
            return true;
    }
    return false;
}

uint32_t hl_closure_fit_spread(hl_closure_t *c, const hl_map_t *map, hl_map_t *shadow)
{
    if (c->count == 0 || c->redrawing)
        return 0;
    /* The frame change the slam's pose and new stops go through: from the map's frame */
    uint32_t newest = c->count - 1;
    c->fit_before = c->undrawn ? hl_pg_from_pose(c->placed[newest]) : c->poses[newest];
    uint32_t dropped = fit_poses(c);
    c->fit_after = c->poses[newest];
    c->undrawn = c->redraw_mm > 0 && !moved_beyond(c);
    if (c->undrawn)
        return dropped;
    /* The shadow starts as the redraw does: the vectors of stops no longer recorded, and
     * the culling generator before the oldest recorded stop was drawn. */
    const hl_vector_t *v = hl_map_vectors(map);
    const uint32_t *stamps = hl_map_stamps(map);
    uint32_t n = 0, count = hl_map_count(map);
    for (uint32_t i = 0; i < count && n < c->map_capacity; i++)
        if (stamps[i] - c->first >= c->count)
            c->kept[n++] = v[i];
    hl_map_restore(shadow, c->kept, n, hl_count_next(hl_map_version(map)), c->rng_before[0]);
    c->next_drawn = c->first;
    c->redrawing = true;
    return dropped;
}

bool hl_closure_redrawing(const hl_closure_t *c)
{
    return c->redrawing;
}

hl_pose_t hl_closure_carry(const hl_closure_t *c, hl_pose_t pose)
{
    hl_pg_pose_t rel = hl_pg_between(c->fit_before, hl_pg_from_pose(pose));
    return hl_pg_to_pose(hl_pg_compose(c->fit_after, rel));
}

bool hl_closure_redraw_step(hl_closure_t *c, hl_map_t *map, hl_map_t *shadow, uint32_t readings)
{
    if (!c->redrawing)
        return false;
    if (c->next_drawn < c->first)   /* forgotten before they were drawn: theirs stay out */
        c->next_drawn = c->first;
    uint32_t drawn = 0, newest = c->first + c->count - 1;
    /* The newest stop last, in the call that puts the shadow in place: scans still join
     * it until then. */
    while (c->next_drawn < newest && drawn < readings) {
        uint32_t i = c->next_drawn - c->first;
        hl_map_set_stamp(shadow, c->next_drawn);
        hl_map_add_scan(shadow, scan_of(c, i), hl_pg_to_pose(c->poses[i]), NULL);
        drawn += scan_of(c, i)->count;
        c->next_drawn++;
    }
    if (c->next_drawn < newest || drawn >= readings)
        return false;
    hl_map_set_stamp(shadow, newest);
    hl_map_add_scan(shadow, scan_of(c, c->count - 1), hl_pg_to_pose(c->poses[c->count - 1]), NULL);
    for (uint32_t i = 0; i < c->count; i++)
        c->placed[i] = hl_pg_to_pose(c->poses[i]);
    hl_map_swap(map, shadow);
    c->redrawing = false;
    return true;
}
