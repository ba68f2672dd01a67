/* vgroup.c - the map's vectors grouped and indexed for the vote loop (see vgroup.h). */
#include "vgroup.h"

#include <stdlib.h>
#include <string.h>

#define BOX_SIDE_MM ((1 << 21) + (1 << 16))
#define TILE_ROW_MM 256     /* a reading's box spans a dozen or two of these */
#define PLAIN_INDEX_MM 32   /* squares of the index when vectors are not merged */

/* Entries of row_start: a tile row per sector, and one past the last. */
static size_t row_keys(const hl_vgroups_t *g)
{
    return HL_VGROUP_SECTORS * (size_t)(g->axis_cells / (uint32_t)g->row_cells + 1) + 1;
}

bool hl_vgroups_init(hl_vgroups_t *g, uint32_t capacity, int32_t group_mm)
{
    memset(g, 0, sizeof *g);
    g->merge = group_mm > 0;
    g->cell_mm = g->merge ? group_mm : PLAIN_INDEX_MM;
    g->row_cells = g->cell_mm < TILE_ROW_MM ? TILE_ROW_MM / g->cell_mm : 1;
    g->capacity = capacity;
    g->axis_cells = BOX_SIDE_MM / (uint32_t)g->cell_mm + 2;
    g->gx = malloc(capacity * sizeof *g->gx);
    g->gy = malloc(capacity * sizeof *g->gy);
    g->gcx = malloc(capacity * sizeof *g->gcx);
    g->first = malloc((capacity + 1) * sizeof *g->first);
    g->normal = malloc(capacity * sizeof *g->normal);
    g->row_start = malloc(row_keys(g) * sizeof *g->row_start);
    g->count = malloc((g->axis_cells + 1) * sizeof *g->count);
    g->slot_a = malloc(capacity * sizeof *g->slot_a);
    g->slot_b = malloc(capacity * sizeof *g->slot_b);
    g->index = malloc(capacity * sizeof *g->index);
    g->cx = malloc(capacity * sizeof *g->cx);
    g->cy = malloc(capacity * sizeof *g->cy);
    g->sector = malloc(capacity * sizeof *g->sector);
    g->row = malloc(capacity * sizeof *g->row);
    return g->gx && g->gy && g->gcx && g->first && g->normal && g->row_start && g->count &&
           g->slot_a && g->slot_b && g->index && g->cx && g->cy && g->sector && g->row;
}

void hl_vgroups_free(hl_vgroups_t *g)
{
    free(g->gx);
    free(g->gy);
    free(g->gcx);
    free(g->first);
    free(g->normal);
    free(g->row_start);
    free(g->count);
    free(g->slot_a);
    free(g->slot_b);
    free(g->index);
    free(g->cx);
    free(g->cy);
    free(g->sector);
    free(g->row);
    memset(g, 0, sizeof *g);
}

size_t hl_vgroups_mem_bytes(const hl_vgroups_t *g)
{
    size_t per_vector = sizeof *g->gx + sizeof *g->gy + sizeof *g->gcx + sizeof *g->first +
                        sizeof *g->normal + sizeof *g->slot_a + sizeof *g->slot_b +
                        sizeof *g->index + sizeof *g->cx + sizeof *g->cy + sizeof *g->sector +
                        sizeof *g->row;
    return g->capacity * per_vector + sizeof *g->first +
           row_keys(g) * sizeof *g->row_start +
           (g->axis_cells + 1) * sizeof *g->count;
}

/* One stable counting-sort pass of the n slots in `from` by key[slot] in 0 .. keys - 1. */
static void sort_pass(hl_vgroups_t *g, const uint32_t *from, uint32_t *to, uint32_t n,
                      const int32_t *key, uint32_t keys)
{
    memset(g->count, 0, (keys + 1) * sizeof *g->count);
    for (uint32_t i = 0; i < n; i++)
        g->count[key[from[i]] + 1]++;
    for (uint32_t k = 1; k <= keys; k++)
        g->count[k] += g->count[k - 1];
    for (uint32_t i = 0; i < n; i++)
        to[g->count[key[from[i]]]++] = from[i];
}

/* Appends one group made of the sorted slots [b, e) to the result. */
static void add_group(hl_vgroups_t *g, const hl_vector_t *map, const uint32_t *index,
                      uint32_t b, uint32_t e, int32_t ox, int32_t oy)
{
    uint32_t k = g->ngroups++;
    int64_t sx = 0, sy = 0;
    g->first[k] = b;
    for (uint32_t i = b; i < e; i++) {
        const hl_vector_t *v = &map[index[g->slot_a[i]]];
        sx += (int64_t)v->x_mm - ox;
        sy += (int64_t)v->y_mm - oy;
        g->normal[i] = v->normal;
    }
    /* the centroid in 1/256 mm, rounded half away from zero */
    int64_t m = (int64_t)(e - b);
    sx *= 256;
    sy *= 256;
    g->gx[k] = (int32_t)((sx + (sx >= 0 ? m / 2 : -(m / 2))) / m);
    g->gy[k] = (int32_t)((sy + (sy >= 0 ? m / 2 : -(m / 2))) / m);
    g->gcx[k] = g->cx[g->slot_a[b]];
}

uint32_t hl_vgroups_build(hl_vgroups_t *g, const hl_vector_t *map, uint32_t n,
                          int64_t x_lo, int64_t x_hi, int64_t y_lo, int64_t y_hi,
                          int32_t origin_x, int32_t origin_y)
{
    /* The vectors in the box (slot s is map[index[s]]), and the corner of the smallest
     * square-aligned box holding them. */
    uint32_t *index = g->index;
    uint32_t m = 0;
    int64_t mx0 = INT64_MAX, my0 = INT64_MAX;
    for (uint32_t i = 0; i < n; i++) {
        const hl_vector_t *v = &map[i];
        if (v->x_mm < x_lo || v->x_mm > x_hi || v->y_mm < y_lo || v->y_mm > y_hi)
            continue;
        mx0 = v->x_mm < mx0 ? v->x_mm : mx0;
        my0 = v->y_mm < my0 ? v->y_mm : my0;
        index[m++] = i;
    }
    g->ngroups = 0;
    g->nrows = 0;
    if (m == 0)
        return 0;
    int32_t c = g->cell_mm;
    /* floor to a multiple of the square, so that squares do not depend on the box */
    mx0 = (mx0 >= 0 ? mx0 : mx0 - (c - 1)) / c * c;
    my0 = (my0 >= 0 ? my0 : my0 - (c - 1)) / c * c;
    g->cell_x0 = mx0 - origin_x;
    g->cell_y0 = my0 - origin_y;
    /* Divisions by the square (below 2^22 mm) and by the squares of a row (below 2^18)
     * by exact reciprocals: this runs over the whole map on every search. */
    uint64_t per_square = (1ull << 32) / (uint32_t)c + 1;
    uint64_t per_row = (1ull << 32) / (uint32_t)g->row_cells + 1;
    int32_t wx = 0, wy = 0;
    for (uint32_t s = 0; s < m; s++) {
        const hl_vector_t *v = &map[index[s]];
        g->cx[s] = (int32_t)(((uint64_t)(v->x_mm - mx0) * per_square) >> 32);
        g->cy[s] = (int32_t)(((uint64_t)(v->y_mm - my0) * per_square) >> 32);
        g->row[s] = (int32_t)(((uint64_t)g->cy[s] * per_row) >> 32);
        wx = g->cx[s] > wx ? g->cx[s] : wx;
        wy = g->cy[s] > wy ? g->cy[s] : wy;
        g->sector[s] = v->normal >> HL_VGROUP_SECTOR_SHIFT;
        g->slot_a[s] = s;
    }
    g->nrows = wy / g->row_cells + 1;

    /* by y square, then x square, then tile row, then sector: the last pass decides */
    sort_pass(g, g->slot_a, g->slot_b, m, g->cy, (uint32_t)wy + 1);
    sort_pass(g, g->slot_b, g->slot_a, m, g->cx, (uint32_t)wx + 1);
    sort_pass(g, g->slot_a, g->slot_b, m, g->row, (uint32_t)g->nrows);
    sort_pass(g, g->slot_b, g->slot_a, m, g->sector, HL_VGROUP_SECTORS);

    /* Walk the sorted slots (now in slot_a): a group is a run of one square and sector
     * (or one vector). */
    int32_t key = -1, last_key = HL_VGROUP_SECTORS * g->nrows;
    uint32_t b = 0;
    for (uint32_t i = 1; i <= m; i++) {
        uint32_t sb = g->slot_a[b], si = i < m ? g->slot_a[i] : 0;
        if (i < m && g->merge && g->cx[si] == g->cx[sb] && g->cy[si] == g->cy[sb] &&
            g->sector[si] == g->sector[sb])
            continue;
        int32_t k = g->sector[sb] * g->nrows + g->row[sb];
        while (key < k)
            g->row_start[++key] = g->ngroups;
        add_group(g, map, index, b, i, origin_x, origin_y);
        b = i;
    }
    while (key < last_key)
        g->row_start[++key] = g->ngroups;
    g->first[g->ngroups] = m;
    return g->ngroups;
}

/* floor(a / b) for b > 0 */
uint32_t hl_vgroups_row_end(const hl_vgroups_t *g, uint32_t sector, int32_t row)
{
    return g->row_start[(size_t)sector * (size_t)g->nrows + (size_t)row + 1];
}

static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

static int32_t clamp(int64_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : v > hi ? hi : (int32_t)v;
}

int32_t hl_vgroups_square_x(const hl_vgroups_t *g, int64_t q8)
{
    return clamp(floor_div(floor_div(q8, 256) - g->cell_x0, g->cell_mm), -1,
                 (int32_t)g->axis_cells);
}

int32_t hl_vgroups_row_y(const hl_vgroups_t *g, int64_t q8)
{
    int64_t square = floor_div(floor_div(q8, 256) - g->cell_y0, g->cell_mm);
    return clamp(floor_div(square, g->row_cells), -1, g->nrows);
}

uint32_t hl_vgroups_seek(const hl_vgroups_t *g, uint32_t sector, int32_t row,
                         int32_t square)
{
    size_t key = (size_t)sector * (size_t)g->nrows + (size_t)row;
    uint32_t lo = g->row_start[key], hi = g->row_start[key + 1];
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (g->gcx[mid] < square)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

uint32_t hl_vgroups_gather(const hl_vgroups_t *g, const int32_t *tx, const int32_t *ty,
                           int32_t nt, uint32_t width_q8, uint32_t height_q8,
                           uint32_t theta_step, uint16_t tn0, int32_t gate, uint32_t *out)
{
    int32_t xmin = tx[0], xmax = xmin, ymin = ty[0], ymax = ymin;
    for (int32_t it = 1; it < nt; it++) {
        xmin = tx[it] < xmin ? tx[it] : xmin;
        xmax = tx[it] > xmax ? tx[it] : xmax;
        ymin = ty[it] < ymin ? ty[it] : ymin;
        ymax = ty[it] > ymax ? ty[it] : ymax;
    }
    /* Positions are relative to the raster origin in 1/256 mm; a vote lands in the
     * raster when centroid - origin - test is in [0, width) for some heading. */
    int64_t bx0 = xmin, bx1 = (int64_t)xmax + width_q8;
    int64_t by0 = ymin, by1 = (int64_t)ymax + height_q8;
    if (g->ngroups == 0)
        return 0;
    int32_t r0 = hl_vgroups_row_y(g, by0), r1 = hl_vgroups_row_y(g, by1 - 1);
    int32_t sq0 = hl_vgroups_square_x(g, bx0), sq1 = hl_vgroups_square_x(g, bx1 - 1);
    r0 = r0 < 0 ? 0 : r0;
    r1 = r1 >= g->nrows ? g->nrows - 1 : r1;
    /* the normal sectors that some member passing the gate under some heading is in */
    uint32_t span = (uint32_t)(nt - 1) * theta_step + 2u * (uint32_t)gate;
    uint32_t sec0 = 0, nsec = HL_VGROUP_SECTORS;
    if (span < 65536u - (1u << HL_VGROUP_SECTOR_SHIFT)) {
        sec0 = (uint16_t)(tn0 - gate) >> HL_VGROUP_SECTOR_SHIFT;
        uint32_t sec1 = (uint16_t)(tn0 - gate + span) >> HL_VGROUP_SECTOR_SHIFT;
        nsec = (sec1 - sec0) % HL_VGROUP_SECTORS + 1;
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < nsec; i++) {
        uint32_t sec = (sec0 + i) % HL_VGROUP_SECTORS;
        for (int32_t r = r0; r <= r1; r++) {
            uint32_t end = hl_vgroups_row_end(g, sec, r);
            for (uint32_t k = hl_vgroups_seek(g, sec, r, sq0); k < end && g->gcx[k] <= sq1; k++) {
                if (g->gx[k] >= bx0 && g->gx[k] < bx1 && g->gy[k] >= by0 && g->gy[k] < by1)
                    out[n++] = k;
            }
        }
    }
    return n;
}

