/* tiles.c - the blur and the peak search over the tiles near votes (see tiles.h). */
#include "tiles.h"

#include <stdlib.h>
#include <string.h>

bool hl_tiles_init(hl_tiles_t *t, uint64_t max_cells, int64_t max_side, int32_t max_nt)
{
    memset(t, 0, sizeof *t);
    /* ceil(nx / W) ceil(ny / H) <= nx ny / (W H) + nx / W + ny / H + 1, nx ny <= max_cells */
    uint64_t cap = max_cells / (HL_TILE_W * HL_TILE_H) + (uint64_t)max_side / HL_TILE_W +
                   (uint64_t)max_side / HL_TILE_H + 4;
    if (cap > UINT32_MAX / 2 || max_nt < 1)
        return false;
    t->capacity = (uint32_t)cap;
    t->max_nt = max_nt;
    t->most = calloc(cap, sizeof *t->most);
    t->voted = malloc(cap * sizeof *t->voted);
    t->voted_most = malloc(cap * sizeof *t->voted_most);
    t->out = malloc(cap * sizeof *t->out);
    t->bound = malloc(cap * sizeof *t->bound);
    t->at = malloc(cap * sizeof *t->at);
    t->max = malloc(cap * sizeof *t->max);
    t->done = malloc(cap * sizeof *t->done);
    t->order = malloc(cap * sizeof *t->order);
    t->scratch = malloc(HL_BLUR_BOX_SCRATCH(HL_TILE_W, HL_TILE_H, max_nt) * sizeof *t->scratch);
    return t->most && t->voted && t->voted_most && t->out && t->bound && t->at && t->max &&
           t->done && t->order && t->scratch;
}

void hl_tiles_free(hl_tiles_t *t)
{
    free(t->most);
    free(t->voted);
    free(t->voted_most);
    free(t->out);
    free(t->bound);
    free(t->at);
    free(t->max);
    free(t->done);
    free(t->order);
    free(t->scratch);
    memset(t, 0, sizeof *t);
}

size_t hl_tiles_mem_bytes(const hl_tiles_t *t)
{
    size_t per_tile = sizeof *t->most + sizeof *t->voted + sizeof *t->voted_most +
                      sizeof *t->out + sizeof *t->bound + sizeof *t->at + sizeof *t->max +
                      sizeof *t->done + sizeof *t->order;
    return (size_t)t->capacity * per_tile +
           HL_BLUR_BOX_SCRATCH(HL_TILE_W, HL_TILE_H, t->max_nt) * sizeof *t->scratch;
}

bool hl_tiles_fit(const hl_tiles_t *t, int32_t nx, int32_t ny, int32_t nt)
{
    if (!t->most || nx < 1 || ny < 1 || nt < 1 || nt > t->max_nt)
        return false;
    uint64_t ntx = ((uint64_t)nx + HL_TILE_W - 1) / HL_TILE_W;
    uint64_t nty = ((uint64_t)ny + HL_TILE_H - 1) / HL_TILE_H;
    return ntx * nty <= t->capacity;
}

void hl_tiles_begin(hl_tiles_t *t, int32_t nx, int32_t ny, int32_t nt)
{
    t->nx = nx;
    t->ny = ny;
    t->nt = nt;
    t->ntx = (nx + HL_TILE_W - 1) / HL_TILE_W;
    t->nty = (ny + HL_TILE_H - 1) / HL_TILE_H;
    t->nout = 0;
}

/* The cells of tile k: x0 .. x0 + w - 1, y0 .. y0 + h - 1. */
typedef struct box {
    int32_t x0, y0, w, h;
} box_t;

static box_t box_of(const hl_tiles_t *t, uint32_t k)
{
    box_t b;
    b.x0 = (int32_t)(k % (uint32_t)t->ntx) * HL_TILE_W;
    b.y0 = (int32_t)(k / (uint32_t)t->ntx) * HL_TILE_H;
    b.w = t->nx - b.x0 < HL_TILE_W ? t->nx - b.x0 : HL_TILE_W;
    b.h = t->ny - b.y0 < HL_TILE_H ? t->ny - b.y0 : HL_TILE_H;
    return b;
}

void hl_tiles_take_votes(hl_tiles_t *t)
{
    uint32_t n = 0, all = (uint32_t)t->ntx * (uint32_t)t->nty;
    for (uint32_t i = 0; i < all; i++)
        if (t->most[i]) {
            t->voted[n] = i;
            t->voted_most[n++] = t->most[i];
            t->most[i] = 0;
        }
    t->nvoted = n;
}

/* The tiles within the kernels' reach of a voted one, each with its bound: 256 times
 * the most votes of the voted tiles within reach. `most` serves as scratch and is left
 * zero. */
static void list_out(hl_tiles_t *t)
{
    int32_t dx = (t->kx->radius + HL_TILE_W - 1) / HL_TILE_W;
    int32_t dy = (t->ky->radius + HL_TILE_H - 1) / HL_TILE_H;
    for (uint32_t i = 0; i < t->nvoted; i++) {
        int32_t tx = (int32_t)(t->voted[i] % (uint32_t)t->ntx);
        int32_t ty = (int32_t)(t->voted[i] / (uint32_t)t->ntx);
        int32_t x0 = tx - dx < 0 ? 0 : tx - dx, x1 = tx + dx >= t->ntx ? t->ntx - 1 : tx + dx;
        int32_t y0 = ty - dy < 0 ? 0 : ty - dy, y1 = ty + dy >= t->nty ? t->nty - 1 : ty + dy;
        uint16_t m = t->voted_most[i];
        for (int32_t y = y0; y <= y1; y++)
            for (int32_t x = x0; x <= x1; x++) {
                uint16_t *o = t->most + (size_t)y * t->ntx + x;
                *o = m > *o ? m : *o;
            }
    }
    uint32_t n = 0, all = (uint32_t)t->ntx * (uint32_t)t->nty;
    size_t at = 0;
    for (uint32_t i = 0; i < all; i++)
        if (t->most[i]) {
            box_t b = box_of(t, i);
            t->out[n] = i;
            t->bound[n] = 256u * t->most[i];
            t->at[n] = at;
            t->done[n] = 0;
            t->order[n] = n;
            at += (size_t)b.w * b.h * t->nt;
            n++;
            t->most[i] = 0;
        }
    t->nout = n;
}

/* Blurs out[k] into its block, once. */
static void blur_tile(hl_tiles_t *t, uint32_t k)
{
    if (t->done[k])
        return;
    box_t b = box_of(t, t->out[k]);
    t->max[k] = hl_blur3_box(t->votes, t->nx, t->ny, t->nt, t->kx, t->ky, t->kt, b.x0, b.y0,
                             b.w, b.h, t->scratch, t->store + t->at[k]);
    t->done[k] = 1;
}

/* Sorts order[] by bound, highest first (heap sort: in place, no allocation). */
static bool before(const hl_tiles_t *t, uint32_t a, uint32_t b)
{
    return t->bound[a] < t->bound[b];     /* the heap's order: lowest bound on top */
}

static void sift(hl_tiles_t *t, uint32_t i, uint32_t n)
{
    uint32_t *o = t->order;
    for (;;) {
        uint32_t l = 2 * i + 1, m = i;
        if (l < n && before(t, o[l], o[m]))
            m = l;
        if (l + 1 < n && before(t, o[l + 1], o[m]))
            m = l + 1;
        if (m == i)
            return;
        uint32_t x = o[i];
        o[i] = o[m];
        o[m] = x;
        i = m;
    }
}

static void sort_by_bound(hl_tiles_t *t)
{
    uint32_t n = t->nout, *o = t->order;
    for (uint32_t i = n / 2; i-- > 0;)
        sift(t, i, n);
    for (uint32_t end = n; end > 1; end--) {
        uint32_t x = o[0];
        o[0] = o[end - 1];
        o[end - 1] = x;
        sift(t, 0, end - 1);
    }
}

/* The raster index ([it][iy][ix]) of the first cell of block k holding v (which it does). */
static size_t first_of(const hl_tiles_t *t, uint32_t k, uint32_t v)
{
    box_t b = box_of(t, t->out[k]);
    const uint32_t *block = t->store + t->at[k];
    size_t i = 0;
    while (block[i] != v)
        i++;
    size_t it = i / ((size_t)b.w * b.h), iy = b.y0 + i / b.w % b.h, ix = b.x0 + i % b.w;
    return (it * t->ny + iy) * t->nx + ix;
}

/* The largest of v[x0 .. x1 - 1]. */
static uint32_t run_max(const uint32_t *v, int32_t x0, int32_t x1)
{
    uint32_t m = 0;
    for (int32_t i = x0; i < x1; i++)
        m = v[i] > m ? v[i] : m;
    return m;
}

/* The largest cell of block k at least the separation from (cx, cy): each row without
 * the run of cells too close (hl_peak_reach, as hl_peak_find's second peak skips them). */
static uint32_t block_second(const hl_tiles_t *t, uint32_t k, int64_t cell2, int64_t sep2,
                             int32_t cx, int32_t cy)
{
    box_t b = box_of(t, t->out[k]);
    const uint32_t *block = t->store + t->at[k];
    uint32_t m = 0;
    for (int32_t i = 0; i < b.h; i++) {
        /* the row's cells too close, [lo, hi) in the block's columns */
        int32_t lo = b.w, hi = b.w;
        int32_t r = hl_peak_reach(cell2, sep2, b.y0 + i - cy);
        if (r >= 0) {
            lo = cx - r - b.x0 < 0 ? 0 : cx - r - b.x0;
            hi = cx + r + 1 - b.x0 > b.w ? b.w : cx + r + 1 - b.x0;
            if (lo > hi)
                lo = hi = b.w;  /* the run is beside the tile */
        }
        for (int32_t it = 0; it < t->nt; it++) {
            const uint32_t *row = block + ((size_t)it * b.h + i) * b.w;
            uint32_t a = run_max(row, 0, lo), c = run_max(row, hi, b.w);
            a = a > c ? a : c;
            m = a > m ? a : m;
        }
    }
    return m;
}

int hl_tiles_search(hl_tiles_t *t, const uint16_t *votes, const hl_kernel_t *kx,
                    const hl_kernel_t *ky, const hl_kernel_t *kt, uint32_t *store,
                    int32_t cell_mm, int32_t sep_mm, hl_peak_t *pk)
{
    t->votes = votes;
    t->kx = kx;
    t->ky = ky;
    t->kt = kt;
    t->store = store;
    list_out(t);
    sort_by_bound(t);

    /* The peak: every tile that could hold a cell as high as the best found is blurred
     * (as high: a tie earlier in [it][iy][ix] order wins). */
    uint32_t best = 0;
    size_t first = SIZE_MAX;
    for (uint32_t j = 0; j < t->nout; j++) {
        uint32_t k = t->order[j];
        if (t->bound[k] < best)
            break;
        blur_tile(t, k);
        if (t->max[k] > best) {
            best = t->max[k];
            first = first_of(t, k, best);
        } else if (t->max[k] == best && best > 0) {
            size_t f = first_of(t, k, best);
            first = f < first ? f : first;
        }
    }
    pk->ix = pk->iy = pk->it = 0;
    pk->score = best;
    pk->second = 0;
    if (best == 0)
        return 0;
    size_t plane = (size_t)t->nx * t->ny;
    pk->it = (int32_t)(first / plane);
    pk->iy = (int32_t)(first % plane / (size_t)t->nx);
    pk->ix = (int32_t)(first % (size_t)t->nx);

    /* The second: every tile that could raise it, from the highest bound down. A tile
     * clear of the square around the circle of cells too close gives its maximum; one it
     * cuts, its cells outside the circle. */
    int64_t cell2 = (int64_t)cell_mm * cell_mm, sep2 = hl_peak_sep2(sep_mm);
    int32_t reach = hl_peak_reach(cell2, sep2, 0);  /* the circle's widest, and tallest */
    uint32_t second = 0;
    for (uint32_t j = 0; j < t->nout; j++) {
        uint32_t k = t->order[j];
        if (t->bound[k] <= second)
            break;
        blur_tile(t, k);
        if (t->max[k] <= second)
            continue;
        box_t b = box_of(t, t->out[k]);
        bool clear = b.x0 > pk->ix + reach || b.x0 + b.w <= pk->ix - reach ||
                     b.y0 > pk->iy + reach || b.y0 + b.h <= pk->iy - reach;
        uint32_t m = clear ? t->max[k] : block_second(t, k, cell2, sep2, pk->ix, pk->iy);
        second = m > second ? m : second;
    }
    pk->second = second;
    return 1;
}

uint32_t hl_tiles_cell(hl_tiles_t *t, int32_t ix, int32_t iy, int32_t it)
{
    uint32_t tile = (uint32_t)(iy >> HL_TILE_H_SHIFT) * (uint32_t)t->ntx +
                    (uint32_t)(ix >> HL_TILE_W_SHIFT);
    uint32_t lo = 0, hi = t->nout;    /* out[] is in index order */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (t->out[mid] < tile)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo == t->nout || t->out[lo] != tile)
        return 0;
    blur_tile(t, lo);
    box_t b = box_of(t, tile);
    return t->store[t->at[lo] + ((size_t)it * b.h + (iy - b.y0)) * b.w + (ix - b.x0)];
}

void hl_tiles_lay_out(hl_tiles_t *t, uint32_t *raster)
{
    for (uint32_t k = 0; k < t->nout; k++) {
        blur_tile(t, k);
        box_t b = box_of(t, t->out[k]);
        const uint32_t *src = t->store + t->at[k];
        for (int32_t it = 0; it < t->nt; it++)
            for (int32_t iy = b.y0; iy < b.y0 + b.h; iy++, src += b.w)
                memcpy(raster + ((size_t)it * t->ny + iy) * t->nx + b.x0, src,
                       (size_t)b.w * sizeof *src);
    }
}

void hl_tiles_clear_votes(hl_tiles_t *t, uint16_t *votes)
{
    /* runs of voted tiles side by side in a tile row (voted[] is in index order) are
     * cleared together, a stretch of each row of theirs at a time */
    for (uint32_t k = 0; k < t->nvoted;) {
        uint32_t e = k + 1;
        while (e < t->nvoted && t->voted[e] == t->voted[e - 1] + 1 &&
               t->voted[e] % (uint32_t)t->ntx != 0)
            e++;
        box_t b = box_of(t, t->voted[k]), last = box_of(t, t->voted[e - 1]);
        size_t w = (size_t)(last.x0 + last.w - b.x0);
        for (int32_t it = 0; it < t->nt; it++)
            for (int32_t iy = b.y0; iy < b.y0 + b.h; iy++)
                memset(votes + ((size_t)it * t->ny + iy) * t->nx + b.x0, 0, w * sizeof *votes);
        k = e;
    }
    t->nvoted = 0;
}
