/* votelone.c - the vote loop for a map of lone vectors (see votelone.h). */
#include "votelone.h"
#include "houghloc-internal/fixed.h"

#include <stdlib.h>
#include <string.h>

#include "simd.h"
#include "tiles.h"

bool hl_votelone_init(hl_votelone_t *v, uint32_t capacity, uint32_t tiles)
{
    memset(v, 0, sizeof *v);
    v->capacity = capacity;
    v->tiles = tiles;
    for (int l = 0; l < 3; l++)
        v->lane[l] = calloc(tiles ? tiles : 1, sizeof *v->lane[l]);
    size_t n = capacity ? capacity : 1;
    int32_t **split[] = { &v->gqx, &v->grx, &v->gqy, &v->gry, &v->qx, &v->rx, &v->qy, &v->ry };
    bool ok = true;
    for (size_t i = 0; i < sizeof split / sizeof split[0]; i++)
        ok = (*split[i] = malloc(n * sizeof **split[i])) != NULL && ok;
    v->lo = malloc(n * sizeof *v->lo);
    v->hi = malloc(n * sizeof *v->hi);
    v->cell = malloc(n * sizeof *v->cell);
    v->tile = malloc(n * sizeof *v->tile);
    v->w = malloc(n * sizeof *v->w);
    hl_votelone_clear(v);
    return ok && v->lane[0] && v->lane[1] && v->lane[2] && v->lo && v->hi && v->cell && v->tile && v->w;
}

void hl_votelone_free(hl_votelone_t *v)
{
    free(v->gqx);
    free(v->grx);
    free(v->gqy);
    free(v->gry);
    free(v->qx);
    free(v->rx);
    free(v->qy);
    free(v->ry);
    free(v->lo);
    free(v->hi);
    free(v->cell);
    free(v->tile);
    free(v->w);
    for (int l = 0; l < 3; l++)
        free(v->lane[l]);
    memset(v, 0, sizeof *v);
}

size_t hl_votelone_mem_bytes(const hl_votelone_t *v)
{
    return (size_t)v->capacity * (8 * sizeof *v->qx + sizeof *v->lo +
                                  sizeof *v->hi + sizeof *v->cell + sizeof *v->tile +
                                  sizeof *v->w) +
           3 * (size_t)v->tiles * sizeof *v->lane[0];
}

/* floor(a / b) for b > 0 */
static int32_t floor_div(int32_t a, int32_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

void hl_votelone_prepare(hl_votelone_t *v, const int32_t *gx, const int32_t *gy, uint32_t n,
                         int32_t cell_q8)
{
    for (uint32_t k = 0; k < n; k++) {
        v->gqx[k] = floor_div(gx[k], cell_q8);
        v->grx[k] = gx[k] - v->gqx[k] * cell_q8;
        v->gqy[k] = floor_div(gy[k], cell_q8);
        v->gry[k] = gy[k] - v->gqy[k] * cell_q8;
    }
}

/* Slice it's cell (offset base), tile and weight of each listed candidate: cell 0, tile 0
 * and weight 0 where it does not vote. The cell of point p under offset t is
 * floor((p - t) / cell), in the raster when 0 <= p - t < n cell: with p = qp cell + rp
 * and t = qt cell + rt (0 <= rp, rt < cell), qp - qt - (rp < rt), in 0 .. n - 1.
 * Returns the sum of the weights. */
HL_VECTOR_KERNEL
static uint32_t cells_of(const int32_t *restrict qx, const int32_t *restrict rx,
                         const int32_t *restrict qy, const int32_t *restrict ry,
                         const int32_t *restrict lo, const int32_t *restrict hi, uint32_t n,
                         const hl_votelone_raster_t *r, int32_t it, uint32_t base,
                         uint32_t *restrict cell, uint32_t *restrict tile,
                         uint32_t *restrict w, uint32_t spare)
{
    const int32_t d = r->cell_q8;
    const int32_t tqx = floor_div(r->tx[it], d), trx = r->tx[it] - tqx * d;
    const int32_t tqy = floor_div(r->ty[it], d), try_ = r->ty[it] - tqy * d;
    const uint32_t nx = (uint32_t)r->nx, ny = (uint32_t)r->ny, ntx = r->ntx;
    uint32_t votes = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t ix = (uint32_t)(qx[i] - tqx - (rx[i] < trx));
        uint32_t iy = (uint32_t)(qy[i] - tqy - (ry[i] < try_));
        uint32_t ok = (uint32_t)(ix < nx) & (uint32_t)(iy < ny) & (uint32_t)(lo[i] <= it) &
                      (uint32_t)(it <= hi[i]);
        cell[i] = ok ? base + iy * nx + ix : i & spare;
        tile[i] = ok ? (iy >> HL_TILE_H_SHIFT) * ntx + (ix >> HL_TILE_W_SHIFT) : 0;
        w[i] = ok;
        votes += ok;
    }
    return votes;
}

/* Adds vote i and notes its cell in `lane`. */
#define VOTE_NOTE(i, lane)                                                   \
    do {                                                                     \
        uint16_t *c_ = votes + cell[i];                                      \
        uint32_t sum_ = *c_ + w[i];                                          \
        uint16_t s_ = (uint16_t)(sum_ < HL_VOTE_MAX ? sum_ : HL_VOTE_MAX);   \
        *c_ = s_;                                                            \
        uint16_t *m_ = (lane) + tile[i];                                     \
        *m_ = s_ > *m_ ? s_ : *m_;                                           \
    } while (0)

uint32_t hl_votelone_cast(hl_votelone_t *v, const hl_votelone_raster_t *r)
{
    const size_t plane = (size_t)r->nx * (size_t)r->ny;
    uint16_t *votes = r->votes, *most = r->most;
    const uint32_t *cell = v->cell, *tile = v->tile, *w = v->w;
    const uint32_t n = v->n;
    uint32_t total = 0;
    /* A vote cast nowhere adds 0 to cell 0, 1, 2 or 3 by its lane, all in tile 0. */
    uint32_t spare = plane * (size_t)r->nt >= 4 ? 3 : 0;
    for (int32_t it = v->lo_min; it <= v->hi_max; it++) {
        uint32_t cast = cells_of(v->qx, v->rx, v->qy, v->ry, v->lo, v->hi, n, r, it,
                                 (uint32_t)((size_t)it * plane), v->cell, v->tile, v->w, spare);
        if (cast == 0)
            continue;
        total += cast;
        if (most) {
            uint16_t *l1 = v->lane[0], *l2 = v->lane[1], *l3 = v->lane[2];
            uint32_t i = 0;
            for (; i + 4 <= n; i += 4) {
                VOTE_NOTE(i, most);
                VOTE_NOTE(i + 1, l1);
                VOTE_NOTE(i + 2, l2);
                VOTE_NOTE(i + 3, l3);
            }
            for (; i < n; i++)
                VOTE_NOTE(i, most);
        } else {
            for (uint32_t i = 0; i < n; i++) {
                uint16_t *c = votes + cell[i];
                uint32_t sum = *c + w[i];
                *c = (uint16_t)(sum < HL_VOTE_MAX ? sum : HL_VOTE_MAX);
            }
        }
    }
    return total;
}

void hl_votelone_fold(hl_votelone_t *v, uint16_t *most, uint32_t n)
{
    uint16_t *l1 = v->lane[0], *l2 = v->lane[1], *l3 = v->lane[2];
    for (uint32_t t = 0; t < n; t++) {
        uint16_t a = l1[t] > l2[t] ? l1[t] : l2[t], b = l3[t] > most[t] ? l3[t] : most[t];
        most[t] = a > b ? a : b;
        l1[t] = l2[t] = l3[t] = 0;
    }
}

uint32_t hl_votelone_vote(hl_votelone_t *v, const hl_vgroups_t *g, const uint32_t *cand,
                          uint32_t n, const gate_t *gate, uint16_t tn0,
                          const hl_votelone_raster_t *r, uint32_t *pairs)
{
    hl_votelone_clear(v);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k = cand[i];
        int32_t lo, hi;
        if (gated_slices(gate, (int16_t)(uint16_t)(g->normal[g->first[k]] - tn0), &lo, &hi)) {
            hl_votelone_push(v, k, lo, hi);
            *pairs += (uint32_t)(hi - lo + 1);
        }
    }
    return hl_votelone_cast(v, r);
}
