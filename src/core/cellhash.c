/* cellhash.c - map vectors hashed by cell (see cellhash.h). */
#include "cellhash.h"

#include <stdlib.h>
#include <string.h>

bool hl_cellhash_init(hl_cellhash_t *h, int32_t cell_mm, uint32_t capacity)
{
    memset(h, 0, sizeof *h);
    h->cell_mm = cell_mm;
    h->capacity = capacity;
    h->buckets = 1;
    while (h->buckets < 2 * capacity)
        h->buckets <<= 1;
    h->start = malloc((h->buckets + 1) * sizeof *h->start);
    h->x = malloc(capacity * sizeof *h->x);
    h->y = malloc(capacity * sizeof *h->y);
    h->normal = malloc(capacity * sizeof *h->normal);
    h->index = malloc(capacity * sizeof *h->index);
    h->bucket = malloc(capacity * sizeof *h->bucket);
    return h->start && h->x && h->y && h->normal && h->index && h->bucket;
}

void hl_cellhash_free(hl_cellhash_t *h)
{
    free(h->start);
    free(h->x);
    free(h->y);
    free(h->normal);
    free(h->index);
    free(h->bucket);
    memset(h, 0, sizeof *h);
}

size_t hl_cellhash_mem_bytes(const hl_cellhash_t *h)
{
    return (h->buckets + 1) * sizeof *h->start +
           h->capacity * (sizeof *h->x + sizeof *h->y + sizeof *h->normal +
                          sizeof *h->index + sizeof *h->bucket);
}

/* A counting sort by bucket. */
void hl_cellhash_build(hl_cellhash_t *h, const hl_vector_t *map, uint32_t n)
{
    memset(h->start, 0, (h->buckets + 1) * sizeof *h->start);
    for (uint32_t i = 0; i < n; i++) {
        h->bucket[i] = hl_cellhash_bucket_of(h, map[i].x_mm, map[i].y_mm);
        h->start[h->bucket[i] + 1]++;
    }
    /* Prefix sums make start[b] the first entry of bucket b; shifted down by one it is
     * the end of bucket b. Filling each bucket from its end, in rising map index, puts
     * the highest index first and leaves start[b] back at the bucket's first entry. */
    for (uint32_t b = 1; b <= h->buckets; b++)
        h->start[b] += h->start[b - 1];
    for (uint32_t b = 0; b < h->buckets; b++)
        h->start[b] = h->start[b + 1];
    for (uint32_t i = 0; i < n; i++) {
        uint32_t e = --h->start[h->bucket[i]];
        h->x[e] = map[i].x_mm;
        h->y[e] = map[i].y_mm;
        h->normal[e] = map[i].normal;
        h->index[e] = i;
    }
}
