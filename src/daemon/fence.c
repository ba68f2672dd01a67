/*
 * fence.c - the geofence (see houghloc/fence.h): polygon validation and point-in-polygon
 * on integer millimetres.
 *
 * Range: vertices lie within +-HL_COORD_MAX_MM (2^22), so a difference of two vertex
 * coordinates is below 2^23 and a cross product of two edge vectors below 2^47. A query
 * point may be any int32: a difference is then below 2^31 + 2^22 < 2^32 and a cross
 * product below 2^32 * 2^23 * 2 = 2^56. Twice the polygon's area, summed over at most 64
 * triangles fanned from vertex 0, stays below 64 * 2^47 = 2^53. All of it fits int64.
 */
#include "fence.h"

#include <stddef.h>

typedef struct pt {
    int64_t x, y;
} pt_t;

static pt_t vertex(const hl_mm_t *x, const hl_mm_t *y, uint32_t i)
{
    return (pt_t){ x[i], y[i] };
}

/* (b - a) x (c - a): > 0 when c is left of the line a->b, 0 when on it. */
static int64_t cross(pt_t a, pt_t b, pt_t c)
{
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

static int sign(int64_t v)
{
    return (v > 0) - (v < 0);
}

static int64_t min64(int64_t a, int64_t b)
{
    return a < b ? a : b;
}

static int64_t max64(int64_t a, int64_t b)
{
    return a > b ? a : b;
}

/* c collinear with a, b: is it within the segment's bounding box? */
static bool within_box(pt_t a, pt_t b, pt_t c)
{
    return c.x >= min64(a.x, b.x) && c.x <= max64(a.x, b.x) &&
           c.y >= min64(a.y, b.y) && c.y <= max64(a.y, b.y);
}

/* Closed segments p1-p2 and q1-q2 share at least one point (touching counts). */
static bool segments_meet(pt_t p1, pt_t p2, pt_t q1, pt_t q2)
{
    int d1 = sign(cross(q1, q2, p1)), d2 = sign(cross(q1, q2, p2));
    int d3 = sign(cross(p1, p2, q1)), d4 = sign(cross(p1, p2, q2));
    if (d1 * d2 < 0 && d3 * d4 < 0)
        return true;
    return (d1 == 0 && within_box(q1, q2, p1)) || (d2 == 0 && within_box(q1, q2, p2)) ||
           (d3 == 0 && within_box(p1, p2, q1)) || (d4 == 0 && within_box(p1, p2, q2));
}

static bool coord_ok(hl_mm_t v)
{
    return v >= -HL_COORD_MAX_MM && v <= HL_COORD_MAX_MM;
}

/*
 * A simple polygon has no repeated consecutive vertex, no edge that doubles back over
 * the one before it, and no two non-adjacent edges that touch. With those, adjacent
 * edges meet only at their shared vertex, so the checks below cover every pair.
 */
static const char *crossing_error(const hl_mm_t *x, const hl_mm_t *y, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        pt_t a = vertex(x, y, i), b = vertex(x, y, (i + 1) % n), c = vertex(x, y, (i + 2) % n);
        if (a.x == b.x && a.y == b.y)
            return "fence has two consecutive vertices at the same point";
        /* b -> c turns straight back along a -> b: the edges overlap. */
        if (cross(a, b, c) == 0 && (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) < 0)
            return "fence edges overlap (the outline doubles back on itself)";
    }
    for (uint32_t i = 0; i < n; i++) {
        pt_t p1 = vertex(x, y, i), p2 = vertex(x, y, (i + 1) % n);
        for (uint32_t j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1)
                continue; /* edge n-1 ends where edge 0 starts: adjacent */
            pt_t q1 = vertex(x, y, j), q2 = vertex(x, y, (j + 1) % n);
            if (segments_meet(p1, p2, q1, q2))
                return "fence edges cross or touch each other (not a simple polygon)";
        }
    }
    return NULL;
}

const char *hl_fence_error(const hl_mm_t *x_mm, const hl_mm_t *y_mm, uint32_t n)
{
    if (!x_mm || !y_mm)
        return "fence has no vertices";
    if (n < 3)
        return "fence needs at least 3 vertices";
    if (n > HL_FENCE_MAX_VERTICES)
        return "fence has more than 64 vertices";
    for (uint32_t i = 0; i < n; i++)
        if (!coord_ok(x_mm[i]) || !coord_ok(y_mm[i]))
            return "fence vertex outside +-4194304 mm";
    int64_t twice_area = 0;
    pt_t o = vertex(x_mm, y_mm, 0);
    for (uint32_t i = 1; i + 1 < n; i++)
        twice_area += cross(o, vertex(x_mm, y_mm, i), vertex(x_mm, y_mm, i + 1));
    if (twice_area == 0)
        return "fence has zero area";
    return crossing_error(x_mm, y_mm, n);
}

hl_status_t hl_fence_polygon(hl_fence_t *f, const hl_mm_t *x_mm, const hl_mm_t *y_mm,
                             uint32_t n)
{
    if (!f || !x_mm || !y_mm)
        return HL_ERR_ARG;
    if (hl_fence_error(x_mm, y_mm, n))
        return HL_ERR_RANGE;
    f->n = n;
    for (uint32_t i = 0; i < n; i++) {
        f->x_mm[i] = x_mm[i];
        f->y_mm[i] = y_mm[i];
    }
    return HL_OK;
}

hl_status_t hl_fence_rect(hl_fence_t *f, hl_mm_t min_x, hl_mm_t min_y, hl_mm_t max_x,
                          hl_mm_t max_y)
{
    if (!f)
        return HL_ERR_ARG;
    if (!(min_x < max_x && min_y < max_y) || !coord_ok(min_x) || !coord_ok(max_x) ||
        !coord_ok(min_y) || !coord_ok(max_y))
        return HL_ERR_RANGE;
    const hl_mm_t x[4] = { min_x, max_x, max_x, min_x };
    const hl_mm_t y[4] = { min_y, min_y, max_y, max_y };
    return hl_fence_polygon(f, x, y, 4);
}

bool hl_fence_contains(const hl_fence_t *f, hl_mm_t x_mm, hl_mm_t y_mm)
{
    if (!f || f->n < 3 || f->n > HL_FENCE_MAX_VERTICES)
        return false;
    const pt_t p = { x_mm, y_mm };
    bool inside = false;
    for (uint32_t i = 0; i < f->n; i++) {
        pt_t a = vertex(f->x_mm, f->y_mm, i);
        pt_t b = vertex(f->x_mm, f->y_mm, (i + 1) % f->n);
        int64_t c = cross(a, b, p);
        if (c == 0 && within_box(a, b, p))
            return true; /* on the border */
        /* Crossing number along the ray from p towards +x. An edge counts when it
         * straddles p's row (half-open, so a vertex on the row counts once) and crosses
         * the row right of p: p is left of an upward edge, or right of a downward one. */
        if ((a.y > p.y) != (b.y > p.y) && (c > 0) == (b.y > a.y))
            inside = !inside;
    }
    return inside;
}
