/* synthroom.c - synthetic rooms (see synthroom.h). */
#include "synthroom.h"

#include <math.h>
#include <stdlib.h>

static const double PI = 3.14159265358979323846;

static double uniform(sr_room_t *room)
{
    return hl_rng_next(&room->rng) / 4294967296.0;
}

double sr_gauss_rng(hl_rng_t *rng)
{
    double u1 = (hl_rng_next(rng) + 1.0) / 4294967297.0;    /* (0, 1]: log(u1) is finite */
    double u2 = hl_rng_next(rng) / 4294967296.0;
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PI * u2);
}

double sr_gauss(sr_room_t *room)
{
    return sr_gauss_rng(&room->rng);
}

static void add_segment(sr_room_t *room, double x1, double y1, double x2, double y2)
{
    if (room->nseg >= SR_MAX_SEGMENTS)
        return;
    room->seg[room->nseg++] = (sr_segment_t){ x1, y1, x2, y2 };
}

static void add_box(sr_room_t *room, double cx, double cy, double w, double h, double a)
{
    double c = cos(a), s = sin(a);
    double px[4], py[4];
    double dx[4] = { -w / 2, w / 2, w / 2, -w / 2 }, dy[4] = { -h / 2, -h / 2, h / 2, h / 2 };
    for (int i = 0; i < 4; i++) {
        px[i] = cx + dx[i] * c - dy[i] * s;
        py[i] = cy + dx[i] * s + dy[i] * c;
    }
    for (int i = 0; i < 4; i++)
        add_segment(room, px[i], py[i], px[(i + 1) % 4], py[(i + 1) % 4]);
}

void sr_room_make(sr_room_t *room, double x0_mm, double y0_mm, double width_mm,
                  double height_mm, int nboxes, uint64_t seed)
{
    room->nseg = 0;
    room->x0_mm = x0_mm;
    room->y0_mm = y0_mm;
    room->width_mm = width_mm;
    room->height_mm = height_mm;
    hl_rng_seed(&room->rng, seed);
    double x1 = x0_mm + width_mm, y1 = y0_mm + height_mm;
    add_segment(room, x0_mm, y0_mm, x1, y0_mm);
    add_segment(room, x1, y0_mm, x1, y1);
    add_segment(room, x1, y1, x0_mm, y1);
    add_segment(room, x0_mm, y1, x0_mm, y0_mm);
    for (int i = 0; i < nboxes; i++) {
        double w = 200 + 800 * uniform(room), h = 200 + 800 * uniform(room);
        double cx = x0_mm + 600 + (width_mm - 1200) * uniform(room);
        double cy = y0_mm + 600 + (height_mm - 1200) * uniform(room);
        double a = (i % 2) ? uniform(room) * PI : 0.0;
        add_box(room, cx, cy, w, h, a);
    }
}

double sr_cast(const sr_room_t *room, double x, double y, double angle)
{
    double dx = cos(angle), dy = sin(angle), best = -1;
    for (int i = 0; i < room->nseg; i++) {
        const sr_segment_t *s = &room->seg[i];
        double ex = s->x2 - s->x1, ey = s->y2 - s->y1;
        double den = dx * ey - dy * ex;
        if (fabs(den) < 1e-12)
            continue;
        double wx = s->x1 - x, wy = s->y1 - y;
        double t = (wx * ey - wy * ex) / den;   /* along the ray */
        double u = (wx * dy - wy * dx) / den;   /* along the segment */
        if (t > 1e-6 && u >= 0 && u <= 1 && (best < 0 || t < best))
            best = t;
    }
    return best;
}

double sr_clearance(const sr_room_t *room, double x, double y)
{
    double best = 1e30;
    for (int i = 0; i < room->nseg; i++) {
        const sr_segment_t *s = &room->seg[i];
        double ex = s->x2 - s->x1, ey = s->y2 - s->y1;
        double len2 = ex * ex + ey * ey;
        double t = len2 > 0 ? ((x - s->x1) * ex + (y - s->y1) * ey) / len2 : 0;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double d = hypot(x - (s->x1 + t * ex), y - (s->y1 + t * ey));
        best = d < best ? d : best;
    }
    return best;
}

/* Inside the walls and not inside a box: a ray in any direction hits something, and
 * an odd number of crossings of a ray means inside a closed box. */
int sr_inside_box(const sr_room_t *room, double x, double y)
{
    int crossings = 0;
    for (int i = 4; i < room->nseg; i++) {
        const sr_segment_t *s = &room->seg[i];
        if ((s->y1 > y) != (s->y2 > y)) {
            double xc = s->x1 + (y - s->y1) * (s->x2 - s->x1) / (s->y2 - s->y1);
            crossings += xc > x;
        }
    }
    return crossings % 2;
}

hl_pose_t sr_free_pose(sr_room_t *room, double clear_mm)
{
    for (int tries = 0; tries < 100000; tries++) {
        double x = room->x0_mm + room->width_mm * uniform(room);
        double y = room->y0_mm + room->height_mm * uniform(room);
        if (sr_clearance(room, x, y) >= clear_mm && !sr_inside_box(room, x, y)) {
            hl_pose_t p = { (hl_mm_t)lround(x), (hl_mm_t)lround(y),
                            (hl_bam_t)(hl_rng_next(&room->rng) & 0xFFFF) };
            return p;
        }
    }
    hl_pose_t centre = { (hl_mm_t)(room->x0_mm + room->width_mm / 2),
                         (hl_mm_t)(room->y0_mm + room->height_mm / 2), 0 };
    return centre;
}

hl_pose_t sr_walk(sr_room_t *room, hl_pose_t from, double step_mm, double clear_mm)
{
    double a0 = hl_bam_to_rad(from.theta);
    for (int tries = 0; tries < 200; tries++) {
        /* widen the turn as tries fail, so a walk never gets stuck in a corner */
        double a = a0 + (uniform(room) - 0.5) * (0.6 + tries * 0.05);
        double x = from.x_mm + step_mm * cos(a), y = from.y_mm + step_mm * sin(a);
        if (sr_clearance(room, x, y) < clear_mm || sr_inside_box(room, x, y))
            continue;
        /* the straight path must be clear too */
        double mx = (from.x_mm + x) / 2, my = (from.y_mm + y) / 2;
        if (sr_clearance(room, mx, my) < clear_mm / 2)
            continue;
        hl_pose_t p = { (hl_mm_t)lround(x), (hl_mm_t)lround(y), hl_bam_from_rad(a) };
        return p;
    }
    hl_pose_t turned = from;
    turned.theta = (hl_bam_t)(turned.theta + 32768u);
    return turned;
}

void sr_sound(sr_room_t *room, hl_pose_t pose, int n, double max_range_mm,
              double noise_mm, hl_scan_t *out)
{
    hl_scan_clear(out);
    for (int i = 0; i < n && i < HL_SCAN_MAX_READINGS; i++) {
        hl_bam_t bearing = (hl_bam_t)((65536u * (uint32_t)i) / (uint32_t)n);
        double a = hl_bam_to_rad((hl_bam_t)(pose.theta + bearing));
        double r = sr_cast(room, pose.x_mm, pose.y_mm, a);
        if (r >= 0 && noise_mm > 0)
            r += noise_mm * sr_gauss(room);
        int valid = r > 0 && r <= max_range_mm;
        hl_scan_add(out, bearing, valid ? (int32_t)lround(r) : 0, (int8_t)(i % 128), valid);
    }
}

uint32_t sr_make_map(sr_room_t *room, uint32_t count, int n, double max_range_mm,
                     double noise_mm, hl_vector_t *out)
{
    /* Sound from enough positions for 1.5x the vectors wanted, then sample without
     * replacement (the paper keeps a random fraction of all readings). */
    uint32_t pool_cap = count + count / 2 + (uint32_t)n;
    hl_vector_t *pool = malloc(pool_cap * sizeof *pool);
    hl_scan_t *scan = malloc(sizeof *scan);
    if (!pool || !scan) {
        free(pool);
        free(scan);
        return 0;
    }
    uint32_t have = 0;
    for (int tries = 0; have + (uint32_t)n <= pool_cap && tries < 100000; tries++) {
        hl_pose_t p = sr_free_pose(room, 400);
        sr_sound(room, p, n, max_range_mm, noise_mm, scan);
        for (uint32_t i = 0; i < scan->count; i++)
            if (hl_vector_from_reading(p, &scan->readings[i], &pool[have]))
                have++;
    }
    uint32_t m = have < count ? have : count;
    for (uint32_t i = 0; i < m; i++) {
        uint32_t j = i + hl_rng_below(&room->rng, have - i);
        hl_vector_t t = pool[i];
        pool[i] = pool[j];
        pool[j] = t;
        out[i] = pool[i];
    }
    free(pool);
    free(scan);
    return m;
}
