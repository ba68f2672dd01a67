/* mapsq.c - map slots chained by place (see mapsq.h). */
#include "mapsq.h"

#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX
#define SECTOR_SHIFT 13     /* an eighth of a turn of normals */

bool hl_mapsq_init(hl_mapsq_t *q, uint32_t capacity, int32_t square_mm)
{
    memset(q, 0, sizeof *q);
    q->square_mm = square_mm;
    uint32_t buckets = 1;
    while (buckets < 2 * capacity)
        buckets <<= 1;
    q->mask = buckets - 1;
    q->head = malloc((size_t)buckets * sizeof *q->head);
    q->next = malloc((size_t)capacity * sizeof *q->next);
    if (!q->head || !q->next)
        return false;
    memset(q->head, 0xff, (size_t)buckets * sizeof *q->head);
    return true;
}

void hl_mapsq_free(hl_mapsq_t *q)
{
    free(q->head);
    free(q->next);
    memset(q, 0, sizeof *q);
}

size_t hl_mapsq_mem_bytes(const hl_mapsq_t *q, uint32_t capacity)
{
    return q->head ? ((size_t)q->mask + 1) * sizeof *q->head + capacity * sizeof *q->next : 0;
}

static int32_t square_of(int32_t v, int32_t side)
{
    return v >= 0 ? v / side : -((-v + side - 1) / side);
}

static bool same_place(const hl_mapsq_t *q, const hl_vector_t *a, const hl_vector_t *b)
{
    return square_of(a->x_mm, q->square_mm) == square_of(b->x_mm, q->square_mm) &&
           square_of(a->y_mm, q->square_mm) == square_of(b->y_mm, q->square_mm) &&
           a->normal >> SECTOR_SHIFT == b->normal >> SECTOR_SHIFT;
}

static uint32_t bucket_of(const hl_mapsq_t *q, const hl_vector_t *a)
{
    uint32_t k = (uint32_t)square_of(a->x_mm, q->square_mm) * 73856093u ^
                 (uint32_t)square_of(a->y_mm, q->square_mm) * 19349663u ^
                 (uint32_t)(a->normal >> SECTOR_SHIFT) * 83492791u;
    return k & q->mask;
}

void hl_mapsq_rebuild(hl_mapsq_t *q, const hl_vector_t *v, uint32_t n)
{
    memset(q->head, 0xff, ((size_t)q->mask + 1) * sizeof *q->head);
    /* linking in descending order puts every chain in ascending order at its head */
    for (uint32_t s = n; s-- > 0;) {
        uint32_t b = bucket_of(q, &v[s]);
        q->next[s] = q->head[b];
        q->head[b] = s;
    }
}

void hl_mapsq_link(hl_mapsq_t *q, const hl_vector_t *v, uint32_t slot)
{
    uint32_t *at = &q->head[bucket_of(q, &v[slot])];
    while (*at != NONE && *at < slot)
        at = &q->next[*at];
    q->next[slot] = *at;
    *at = slot;
}

void hl_mapsq_unlink(hl_mapsq_t *q, const hl_vector_t *v, uint32_t slot)
{
    uint32_t *at = &q->head[bucket_of(q, &v[slot])];
    while (*at != NONE && *at != slot)
        at = &q->next[*at];
    if (*at == slot)
        *at = q->next[slot];
}

uint32_t hl_mapsq_count(const hl_mapsq_t *q, const hl_vector_t *v, const hl_vector_t *x)
{
    uint32_t n = 0;
    for (uint32_t s = q->head[bucket_of(q, x)]; s != NONE; s = q->next[s])
        n += same_place(q, &v[s], x);
    return n;
}

uint32_t hl_mapsq_nth(const hl_mapsq_t *q, const hl_vector_t *v, const hl_vector_t *x,
                      uint32_t r)
{
    for (uint32_t s = q->head[bucket_of(q, x)]; s != NONE; s = q->next[s])
        if (same_place(q, &v[s], x) && r-- == 0)
            return s;
    return NONE;    /* r >= the count: not reached by map.c */
}
