/* mapsq.c - map slots chained by place (see mapsq.h). */
#include "mapsq.h"

#include <stdlib.h>
#include <string.h>

#include "placehash.h"

#define NONE UINT32_MAX
#define SECTOR_SHIFT 13     /* an eighth of a turn of normals */
#define X_SHIFT 27          /* a place's number: x square, y square (24 bits each), side */
#define Y_SHIFT 3

bool hl_mapsq_init(hl_mapsq_t *q, uint32_t capacity, int32_t square_mm)
{
    memset(q, 0, sizeof *q);
    if (!hl_floordiv_init(&q->square, square_mm))
        return false;
    q->square_mm = square_mm;
    uint32_t buckets = hl_place_buckets(capacity);
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
           (uint64_t)(a->normal >> SECTOR_SHIFT);
}

static uint32_t bucket_of(const hl_mapsq_t *q, uint64_t place)
{
    return hl_place_bucket(place, q->mask);
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
