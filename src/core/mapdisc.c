/* mapdisc.c - map slots chained by square, for the search of a disc (see mapdisc.h). */
#include "mapdisc.h"

#include <stdlib.h>
#include <string.h>

#include "placehash.h"

#define NONE UINT32_MAX
#define WALKS 16    /* squares a search may reach: a disc of 3 radii, 4 x 4 of them */

bool hl_mapdisc_init(hl_mapdisc_t *d, uint32_t capacity, int32_t square_mm)
{
    memset(d, 0, sizeof *d);
    if (!hl_floordiv_init(&d->square, square_mm))
        return false;
    uint32_t buckets = hl_place_buckets(capacity);
    d->mask = buckets - 1;
    d->head = malloc((size_t)buckets * sizeof *d->head);
    d->link = malloc((size_t)capacity * sizeof *d->link);
    d->prev = malloc((size_t)capacity * sizeof *d->prev);
    if (!d->head || !d->link || !d->prev)
        return false;
    memset(d->head, 0xff, (size_t)buckets * sizeof *d->head);
    return true;
}

void hl_mapdisc_free(hl_mapdisc_t *d)
{
    free(d->head);
    free(d->link);
    free(d->prev);
    memset(d, 0, sizeof *d);
}

size_t hl_mapdisc_mem_bytes(const hl_mapdisc_t *d, uint32_t capacity)
{
    return d->head ? ((size_t)d->mask + 1) * sizeof *d->head +
                         capacity * (sizeof *d->link + sizeof *d->prev)
                   : 0;
}

/* The chain of square (sx, sy). Squares of one chain need not be alike: a search tests
 * every link's distance, which no vector of another square can pass unless its square
 * is searched too, and searches each chain once. */
static uint32_t bucket_of(const hl_mapdisc_t *d, uint32_t sx, uint32_t sy)
{
    return hl_place_bucket((uint64_t)sx << 24 | sy, d->mask);
}

static uint32_t bucket_at(const hl_mapdisc_t *d, hl_mm_t x_mm, hl_mm_t y_mm)
{
    return bucket_of(d, hl_floordiv_from_base(&d->square, x_mm),
                     hl_floordiv_from_base(&d->square, y_mm));
}

void hl_mapdisc_rebuild(hl_mapdisc_t *d, const hl_vector_t *v, uint32_t n)
{
    memset(d->head, 0xff, ((size_t)d->mask + 1) * sizeof *d->head);
    for (uint32_t s = 0; s < n; s++)
        hl_mapdisc_link(d, v, s);
}

void hl_mapdisc_link(hl_mapdisc_t *d, const hl_vector_t *v, uint32_t slot)
{
    hl_mapdisc_link_t *l = &d->link[slot];
    l->x_mm = v[slot].x_mm;
    l->y_mm = v[slot].y_mm;
    l->normal = v[slot].normal;
    uint32_t *head = &d->head[bucket_at(d, l->x_mm, l->y_mm)];
    l->next = *head;
    if (*head != NONE)
        d->prev[*head] = slot;
    d->prev[slot] = NONE;
    *head = slot;
}

void hl_mapdisc_unlink(hl_mapdisc_t *d, uint32_t slot)
{
    const hl_mapdisc_link_t *l = &d->link[slot];
    uint32_t before = d->prev[slot];
    if (before == NONE)
        d->head[bucket_at(d, l->x_mm, l->y_mm)] = l->next;
    else
        d->link[before].next = l->next;
    if (l->next != NONE)
        d->prev[l->next] = before;
}

/* Keeps @p s among the lowest @p max slots found, ascending in out[0 .. *n). */
static void keep_lowest(uint32_t s, uint32_t *out, uint32_t *n, uint32_t max)
{
    if (*n == max && (max == 0 || out[max - 1] < s))
        return;
    uint32_t j = *n < max ? (*n)++ : max - 1;
    for (; j > 0 && out[j - 1] > s; j--)
        out[j] = out[j - 1];
    out[j] = s;
}

#define CANDS 64    /* links that passed, gathered before they are sorted in */

/* Keeps the @p m candidates among the lowest slots found; empties them. */
static void keep_candidates(uint32_t *cand, uint32_t *m, uint32_t *out, uint32_t *n,
                            uint32_t max)
{
    for (uint32_t i = 0; i < *m; i++)
        keep_lowest(cand[i], out, n, max);
    *m = 0;
}

/* The squares from the one of x - r to the one of x + r, clamped to the coordinates. */
static void square_span(const hl_mapdisc_t *d, int32_t x, int32_t r, uint32_t *lo,
                        uint32_t *hi)
{
    int32_t a = x - r < -HL_COORD_MAX_MM ? -HL_COORD_MAX_MM : x - r;
    int32_t b = x + r > HL_COORD_MAX_MM ? HL_COORD_MAX_MM : x + r;
    *lo = hl_floordiv_from_base(&d->square, a);
    *hi = hl_floordiv_from_base(&d->square, b);
}

/* The distinct chains of the squares the disc of @p r about @p x reaches. */
static uint32_t chains_of(const hl_mapdisc_t *d, const hl_vector_t *x, int32_t r,
                          uint32_t *bucket)
{
    uint32_t x0, x1, y0, y1, k = 0;
    square_span(d, x->x_mm, r, &x0, &x1);
    square_span(d, x->y_mm, r, &y0, &y1);
    for (uint32_t sx = x0; sx <= x1; sx++)
        for (uint32_t sy = y0; sy <= y1 && k < WALKS; sy++) {
            uint32_t b = bucket_of(d, sx, sy), i = 0;
            while (i < k && bucket[i] != b)
                i++;
            if (i == k)
                bucket[k++] = b;
        }
    return k;
}

uint32_t hl_mapdisc_near(const hl_mapdisc_t *d, const hl_vector_t *x, int32_t radius,
                         int32_t gate, uint32_t *out, uint32_t max)
{
    uint32_t bucket[WALKS], cand[CANDS], n = 0, m = 0;
    uint32_t k = chains_of(d, x, radius, bucket);
    const int64_t r2 = (int64_t)radius * radius;
    for (uint32_t i = 0; i < k; i++)
        for (uint32_t s = d->head[bucket[i]]; s != NONE; s = d->link[s].next) {
            /* Every link a candidate, kept by the count of its test rather than a branch:
             * which links pass is a coin toss to the processor's predictor. */
            const hl_mapdisc_link_t *l = &d->link[s];
            int64_t ex = (int64_t)l->x_mm - x->x_mm, ey = (int64_t)l->y_mm - x->y_mm;
            int32_t dn = hl_bam_diff(l->normal, x->normal);
            cand[m] = s;
            m += (uint32_t)(ex * ex + ey * ey <= r2) & (uint32_t)((dn < 0 ? -dn : dn) <= gate);
            if (m == CANDS)
                keep_candidates(cand, &m, out, &n, max);
        }
    keep_candidates(cand, &m, out, &n, max);
    return n;
}
