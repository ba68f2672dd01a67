/* closure_fit.c - every recorded stop fitted to its steps and matches, and the map drawn
 * again at the fitted poses, at once or a share a scan (closure.h). */
#include "houghloc-internal/closure.h"

#include <math.h>

#include "closure_internal.h"

#define PI 3.14159265358979323846
#define REDRAW_LEVER_MM 5000.0  /* a turn of a stop counts as its move of a wall this far */

/* Whether the fit moved stop @p i farther than @p mm from where its vectors lie, or
 * turned it enough to move a wall 5 m away that far. */
static bool stop_moved(const hl_closure_t *c, uint32_t i, double mm)
{
    hl_pg_pose_t at = hl_pg_from_pose(c->placed[i]);
    double turn = fabs(remainder(c->poses[i].theta - at.theta, 2 * PI));
    return hypot(c->poses[i].x - at.x, c->poses[i].y - at.y) > mm ||
           turn * REDRAW_LEVER_MM > mm;
}

/* Whether the fit moved some stop beyond redraw_mm. */
static bool moved_beyond(const hl_closure_t *c)
{
    for (uint32_t i = 0; i < c->count; i++)
        if (stop_moved(c, i, c->redraw_mm))
            return true;
    return false;
}

/* Which stops the redraw draws again: with redraw_stop_mm, when the fit moved a
 * sixteenth of them or fewer beyond it, those and the newest (its scan has grown since
 * it was drawn); else every one. Most fits move a few recent stops; a closed loop moves
 * most. Drawing again only the moved ones at every fit, the culls of one redraw after
 * another favour the stops drawn most often: on five real buildings with an eighth as
 * the share intel's ATE from the origin rose 0.17 -> 0.22 m, drawing only the moved ones
 * always freiburg-101's 0.044 -> 0.051 (docs/design/loop-closure.md). */
#define SELECTIVE_SHARE 16

static bool choose_stops(hl_closure_t *c)
{
    uint32_t moved = 0;
    for (uint32_t i = 0; i < c->count; i++) {
        c->to_draw[i] = i + 1 == c->count ||
                        (c->redraw_stop_mm > 0 && stop_moved(c, i, c->redraw_stop_mm));
        moved += c->to_draw[i];
    }
    bool some = c->redraw_stop_mm > 0 && moved * SELECTIVE_SHARE <= c->count;
    for (uint32_t i = 0; !some && i < c->count; i++)
        c->to_draw[i] = true;
    return some;
}

/* Starts drawing @p map again into @p into (the map itself, or a shadow): the stops to
 * draw chosen (before their placed poses change), and @p into holding the vectors of the
 * stops no longer recorded and of those not drawn again, with their stamps; the culling
 * generator as it was before the oldest stop was drawn, or, drawing only some, where
 * the map's is. */
static void start_drawing(hl_closure_t *c, const hl_map_t *map, hl_map_t *into)
{
    bool some = choose_stops(c);
    const hl_vector_t *v = hl_map_vectors(map);
    const uint32_t *stamps = hl_map_stamps(map);
    uint32_t n = 0, count = hl_map_count(map);
    for (uint32_t i = 0; i < count && n < c->map_capacity; i++) {
        uint32_t k = stamps[i] - c->first;    /* wraps below first */
        if (k >= c->count || !c->to_draw[k]) {
            c->kept_stamps[n] = stamps[i];
            c->kept[n++] = v[i];
        }
    }
    /* Cannot fail: n fits the map, and its own vectors are in range. */
    hl_map_restore(into, c->kept, n, hl_count_next(hl_map_version(map)),
                   some ? hl_map_rng(map) : c->rng_before[0]);
    hl_map_restore_stamps(into, c->kept_stamps, n);
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
    start_drawing(c, map, map);
    for (uint32_t i = 0; i < c->count; i++) {
        if (!c->to_draw[i])
            continue;
        c->placed[i] = hl_pg_to_pose(c->poses[i]);
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
    redraw(c, map);
    return dropped;
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
    start_drawing(c, map, shadow);
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
        if (!c->to_draw[i]) {
            c->next_drawn++;
            continue;
        }
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
        if (c->to_draw[i])
            c->placed[i] = hl_pg_to_pose(c->poses[i]);
    hl_map_swap(map, shadow);
    c->redrawing = false;
    return true;
}
