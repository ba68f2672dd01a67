/*
 * edt.c - the costmap's exact Euclidean distance transform (costmap.c says what it
 * measures): a column pass to the obstacles grown by one cell, then per row the lower
 * envelope of parabolas of Meijster, Roerdink and Hesselink (2000). Integers throughout.
 */
#include "edt.h"

#include "houghloc/plan.h"

#include "gridwalk.h"

/* The column pass: dist = rows to the nearest cell, in this column, that has an obstacle
 * in its own or a neighbouring column, capped at band. (Taking one off it, the row pass
 * measures to the obstacles grown by one cell.) */
void hl_edt_columns(const uint8_t *cells, uint8_t *dist, int32_t w, int32_t h, uint8_t cap)
{
    for (int32_t j = 0; j < h; j++) {
        const uint8_t *c = cells + (size_t)j * (size_t)w;
        uint8_t *d = dist + (size_t)j * (size_t)w;
        const uint8_t *up = j ? d - w : NULL;
        for (int32_t i = 0; i < w; i++) {
            bool src = c[i] == HL_PLAN_CELL_OBSTACLE ||
                       (i > 0 && c[i - 1] == HL_PLAN_CELL_OBSTACLE) ||
                       (i + 1 < w && c[i + 1] == HL_PLAN_CELL_OBSTACLE);
            d[i] = src ? 0 : up && up[i] < cap ? (uint8_t)(up[i] + 1) : cap;
        }
    }
    for (int32_t j = h - 2; j >= 0; j--) {
        uint8_t *d = dist + (size_t)j * (size_t)w;
        const uint8_t *down = d + w;
        for (int32_t i = 0; i < w; i++)
            if (down[i] + 1 < d[i])
                d[i] = (uint8_t)(down[i] + 1);
    }
}

/* The row pass for row j: for each cell, the squared distance to the grown obstacles,
 * min over i of (x - i)^2 + G(i)^2, by the lower envelope of those parabolas; turned
 * into the cell byte through the table. Columns at the cap are left out: their
 * parabolas never come below lut_n, so a cell no parabola reaches is free. */
void hl_edt_row(const uint8_t *d, uint8_t *out, int32_t w, int32_t band, const uint8_t *lut,
                uint32_t lut_n, int32_t *s, int32_t *t)
{
#define G2(i) ((int64_t)(d[i] ? d[i] - 1 : 0) * (d[i] ? d[i] - 1 : 0))
#define F(x, i) ((int64_t)((x) - (i)) * ((x) - (i)) + G2(i))
    int32_t q = -1;
    for (int32_t u = 0; u < w; u++) {
        if (d[u] >= band)
            continue;
        while (q >= 0 && F(t[q], s[q]) > F(t[q], u))
            q--;
        if (q < 0) {
            q = 0;
            s[0] = u;
            t[0] = 0;
            continue;
        }
        /* The first x where parabola u is below parabola s[q]. */
        int64_t i = s[q];
        int64_t sep = hl_walk_floor_div((int64_t)u * u - i * i + G2(u) - G2(i), 2 * (u - i)) + 1;
        if (sep < w) {
            q++;
            s[q] = u;
            t[q] = (int32_t)sep;
        }
    }
    for (int32_t u = w - 1; u >= 0; u--) {
        if (out[u] == HL_PLAN_CELL_OBSTACLE)
            ;
        else if (q < 0)
            out[u] = 0;
        else {
            int64_t d2 = F(u, s[q]);
            out[u] = d2 < lut_n ? lut[d2] : 0;
        }
        if (q >= 0 && u == t[q])
            q--;
    }
#undef F
#undef G2
}
