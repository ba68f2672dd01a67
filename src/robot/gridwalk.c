/* gridwalk.c - the cells a segment crosses, and whether a straight leg is clear
 * (gridwalk.h; hl_plan_segment_clear in plan.h). */
#include "gridwalk.h"

#include <stdlib.h>

int64_t hl_walk_floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return q * b > a ? q - 1 : q;
}

void hl_walk_init(walk_t *w, const hl_plan_grid_t *g, int64_t ax, int64_t ay, int64_t bx,
                  int64_t by)
{
    int64_t s = 2 * (int64_t)g->cell_mm;
    int64_t X0 = 2 * (ax - g->x0_mm) + g->cell_mm, Y0 = 2 * (ay - g->y0_mm) + g->cell_mm;
    int64_t X1 = 2 * (bx - g->x0_mm) + g->cell_mm, Y1 = 2 * (by - g->y0_mm) + g->cell_mm;
    int64_t dx = X1 - X0, dy = Y1 - Y0, adx = llabs(dx), ady = llabs(dy);
    w->col = (int32_t)hl_walk_floor_div(X0, s);
    w->row = (int32_t)hl_walk_floor_div(Y0, s);
    w->end_col = (int32_t)hl_walk_floor_div(X1, s);
    w->end_row = (int32_t)hl_walk_floor_div(Y1, s);
    w->step_col = dx > 0 ? 1 : -1;
    w->step_row = dy > 0 ? 1 : -1;
    /* A coordinate on a border moving down crosses it at once: the point touches both. */
    int64_t to_c = dx > 0 ? (w->col + 1) * s - X0 : X0 - w->col * s;
    int64_t to_r = dy > 0 ? (w->row + 1) * s - Y0 : Y0 - w->row * s;
    w->next_c = dx ? to_c * ady : INT64_MAX;
    w->next_r = dy ? to_r * adx : INT64_MAX;
    w->inc_c = s * ady;
    w->inc_r = s * adx;
    w->left = abs(w->end_col - w->col) + abs(w->end_row - w->row);
    w->corner = false;
}

bool hl_walk_next(walk_t *w)
{
    if ((w->col == w->end_col && w->row == w->end_row) || w->left <= 0)
        return false;
    bool c = w->next_c <= w->next_r, r = w->next_r <= w->next_c;
    /* A tie at the very end (the end point on a corner) must not step past the end. */
    if (c && r) {
        if (w->col == w->end_col)
            c = false;
        else if (w->row == w->end_row)
            r = false;
    }
    w->corner = c && r;
    if (c) {
        w->col += w->step_col;
        w->next_c += w->inc_c;
        w->left--;
    }
    if (r) {
        w->row += w->step_row;
        w->next_r += w->inc_r;
        w->left--;
    }
    return true;
}

bool hl_walk_in_grid(const hl_plan_grid_t *g, int32_t col, int32_t row)
{
    return col >= 0 && row >= 0 && col < g->cols && row < g->rows;
}

static bool cell_ok(const hl_plan_grid_t *g, int32_t col, int32_t row, uint8_t max_cost)
{
    size_t i = (size_t)row * (size_t)g->cols + (size_t)col;
    uint8_t v = g->cells[i];
    return v <= max_cost || (g->start_region[i] && v != HL_PLAN_CELL_OBSTACLE);
}

bool hl_plan_segment_clear(const hl_plan_grid_t *g, hl_mm_t ax, hl_mm_t ay, hl_mm_t bx,
                           hl_mm_t by, uint8_t max_cost)
{
    if (!g || g->cols <= 0)
        return false;
    walk_t w;
    hl_walk_init(&w, g, ax, ay, bx, by);
    if (!hl_walk_in_grid(g, w.col, w.row) || !hl_walk_in_grid(g, w.end_col, w.end_row))
        return false;
    if (!cell_ok(g, w.col, w.row, max_cost))
        return false;
    while (hl_walk_next(&w)) {
        if (!cell_ok(g, w.col, w.row, max_cost))
            return false;
        if (w.corner) {
            /* Squeezing between two obstacle cells through their common corner touches
             * both. (Only the start's lethal region can be next to an obstacle.) */
            const uint8_t *v = g->cells;
            size_t side_a = (size_t)(w.row - w.step_row) * (size_t)g->cols + (size_t)w.col;
            size_t side_b = (size_t)w.row * (size_t)g->cols + (size_t)(w.col - w.step_col);
            if (v[side_a] == HL_PLAN_CELL_OBSTACLE || v[side_b] == HL_PLAN_CELL_OBSTACLE)
                return false;
        }
    }
    return true;
}

