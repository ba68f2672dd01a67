/* mapsq.c - map slots chained by place (see mapsq.h). */
#include "mapsq.h"

#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX
#define SECTOR_SHIFT 13     /* an eighth of a turn of normals */
#define X_SHIFT 27          /* a place's number: x square, y square (24 bits each), side */
#define Y_SHIFT 3

bool hl_mapsq_init(hl_mapsq_t *q, uint32_t capacity, int32_t square_mm, bool sides)
{
    memset(q, 0, sizeof *q);
    q->sides = sides;
    if (!hl_floordiv_init(&q->square, square_mm))
        return false;
    q->square_mm = square_mm;
    uint32_t buckets = 1;
    while (buckets < 2 * capacity)
        buckets <<= 1;
    q->mask = buckets - 1;
    q->head = malloc((size_t)buckets * sizeof *q->head);
    q->next = malloc((size_t)capacity * sizeof *q->next);
    q->key = calloc(capacity, sizeof *q->key);
    if (!q->head || !q->next || !q->key)
        return false;
    memset(q->head, 0xff, (size_t)buckets * sizeof *q->head);
    return true;
}

void hl_mapsq_free(hl_mapsq_t *q)
{
    free(q->head);
    free(q->next);
    free(q->key);
    memset(q, 0, sizeof *q);
}

size_t hl_mapsq_mem_bytes(const hl_mapsq_t *q, uint32_t capacity)
{
    return q->head ? ((size_t)q->mask + 1) * sizeof *q->head +
                         capacity * (sizeof *q->next + sizeof *q->key)
                   : 0;
}

/* The place of @p a as one number: its square's two coordinates and its side. Chains
 * compare these rather than divide again at every link. */
static uint64_t place_of(const hl_mapsq_t *q, const hl_vector_t *a)
{
    /* squares counted from below every coordinate: 24 bits each */
    return (uint64_t)hl_floordiv_from_base(&q->square, a->x_mm) << X_SHIFT |
           (uint64_t)hl_floordiv_from_base(&q->square, a->y_mm) << Y_SHIFT |
           (uint64_t)(q->sides ? a->normal >> SECTOR_SHIFT : 0);
}

static uint32_t bucket_of(const hl_mapsq_t *q, uint64_t place)
{
    return (uint32_t)((place * 0x9E3779B97F4A7C15u) >> 32) & q->mask;
}

void hl_mapsq_rebuild(hl_mapsq_t *q, const hl_vector_t *v, uint32_t n)
{
    memset(q->head, 0xff, ((size_t)q->mask + 1) * sizeof *q->head);
    /* linking in descending order puts every chain in ascending order at its head */
    for (uint32_t s = n; s-- > 0;) {
        q->key[s] = place_of(q, &v[s]);
        uint32_t b = bucket_of(q, q->key[s]);
        q->next[s] = q->head[b];
        q->head[b] = s;
    }
}

void hl_mapsq_link(hl_mapsq_t *q, const hl_vector_t *v, uint32_t slot)
{
    q->key[slot] = place_of(q, &v[slot]);
    uint32_t *at = &q->head[bucket_of(q, q->key[slot])];
    while (*at != NONE && *at < slot)
        at = &q->next[*at];
    q->next[slot] = *at;
    *at = slot;
}

void hl_mapsq_unlink(hl_mapsq_t *q, uint32_t slot)
{
    uint32_t *at = &q->head[bucket_of(q, q->key[slot])];
    while (*at != NONE && *at != slot)
        at = &q->next[*at];
    if (*at == slot)
        *at = q->next[slot];
}

uint32_t hl_mapsq_count(const hl_mapsq_t *q, const hl_vector_t *x)
{
    uint64_t place = place_of(q, x);
    uint32_t n = 0;
    for (uint32_t s = q->head[bucket_of(q, place)]; s != NONE; s = q->next[s])
        n += q->key[s] == place;
    return n;
}

uint32_t hl_mapsq_nth(const hl_mapsq_t *q, const hl_vector_t *x, uint32_t r)
{
    uint64_t place = place_of(q, x);
    for (uint32_t s = q->head[bucket_of(q, place)]; s != NONE; s = q->next[s])
        if (q->key[s] == place && r-- == 0)
            return s;
    return NONE;    /* r >= the count: not reached by map.c */
}

/* The squares from the one of x - r to the one of x + r, clamped to the coordinates. */
static void square_span(const hl_mapsq_t *q, int32_t x, int32_t r, uint32_t *lo, uint32_t *hi)
{
    int32_t a = x - r < -HL_COORD_MAX_MM ? -HL_COORD_MAX_MM : x - r;
    int32_t b = x + r > HL_COORD_MAX_MM ? HL_COORD_MAX_MM : x + r;
    *lo = hl_floordiv_from_base(&q->square, a);
    *hi = hl_floordiv_from_base(&q->square, b);
}

/* Appends to out[0 .. *n) the slots of place @p place within r2 of @p x, normals within
 * @p gate. */
static void near_in_place(const hl_mapsq_t *q, const hl_vector_t *v, const hl_vector_t *x,
                          uint64_t place, int64_t r2, int32_t gate, uint32_t *out,
                          uint32_t *n, uint32_t max)
{
    for (uint32_t s = q->head[bucket_of(q, place)]; s != NONE && *n < max; s = q->next[s]) {
        if (q->key[s] != place)
            continue;
        int64_t ex = (int64_t)v[s].x_mm - x->x_mm, ey = (int64_t)v[s].y_mm - x->y_mm;
        int32_t dn = hl_bam_diff(v[s].normal, x->normal);
        if (ex * ex + ey * ey <= r2 && (dn < 0 ? -dn : dn) <= gate)
            out[(*n)++] = s;
    }
}

uint32_t hl_mapsq_near(const hl_mapsq_t *q, const hl_vector_t *v, const hl_vector_t *x,
                       int32_t radius, int32_t gate, uint32_t *out, uint32_t max)
{
    uint32_t x0, x1, y0, y1, n = 0;
    square_span(q, x->x_mm, radius, &x0, &x1);
    square_span(q, x->y_mm, radius, &y0, &y1);
    const int64_t r2 = (int64_t)radius * radius;
    for (uint32_t sx = x0; sx <= x1; sx++)
        for (uint32_t sy = y0; sy <= y1; sy++)
            near_in_place(q, v, x, (uint64_t)sx << X_SHIFT | (uint64_t)sy << Y_SHIFT, r2,
                          gate, out, &n, max);
    /* ascending slots: "the r-th vector of the place" depends only on the vectors array */
    for (uint32_t i = 1; i < n; i++) {
        uint32_t t = out[i], j = i;
        for (; j > 0 && out[j - 1] > t; j--)
            out[j] = out[j - 1];
        out[j] = t;
    }
    return n;
}
