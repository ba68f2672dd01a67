/* loc_params.c - the localizer's parameters: defaults, validation, and the raster sizes
 * they imply (localize.h). */
#include <stddef.h>
#include <string.h>

#include "houghloc-internal/localize.h"
#include "houghloc-internal/params.h"
#include "loc_params.h"

void hl_loc_params_default(hl_loc_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->theta_step = hl_bam_from_deg(HL_LOC_THETA_STEP_DEG);
    p->theta_half_steps = HL_LOC_THETA_HALF_STEPS;
    p->normal_gate = hl_bam_from_deg(HL_LOC_NORMAL_GATE_DEG);
    p->blur_sigma_theta = hl_bam_from_deg(HL_LOC_BLUR_SIGMA_THETA_DEG);
    p->peak_separation_mm = HL_LOC_PEAK_SEPARATION_MM;
    p->vote_once = false;   /* the global search's coarse stage asks for it (reloc.h) */
    p->max_map_vectors = HL_LOC_MAX_MAP_VECTORS;
    /* cell, blur, prior, raster, stride, groups: localize.* (params_table.c) */
    hl_params_fill_defaults(p, offsetof(hl_slam_params_t, loc), sizeof *p);
}

const char *hl_loc_params_error(const hl_loc_params_t *p)
{
    if (!p)
        return "no localizer parameters";
    if (p->cell_mm < 1 || p->cell_mm > HL_LOC_MAX_CELL_MM)
        return "cell_mm must be in 1..1000";
    if (p->theta_step == 0 && p->theta_half_steps > 0)
        return "theta_step must be positive when theta_half_steps > 0";
    if (p->theta_half_steps > HL_LOC_MAX_HALF_STEPS)
        return "theta_half_steps must be at most 256";
    if ((uint32_t)p->theta_step * (2u * p->theta_half_steps + 1u) > 32768u)
        return "the heading slice must span less than half a turn";
    if (p->normal_gate > HL_BAM_HALF_TURN)
        return "normal_gate must be at most 180 degrees";
    if (p->blur_sigma_mm < 0 || p->blur_sigma_mm > 10 * p->cell_mm)
        return "blur_sigma_mm must be in 0..10 cells";
    if (p->peak_separation_mm < 0 || p->peak_separation_mm > HL_RANGE_MAX_MM)
        return "peak_separation_mm must be in 0..32767";
    if (p->prior_sigma_mm < 1 || p->prior_sigma_mm > HL_COORD_MAX_MM)
        return "prior_sigma_mm must be positive";
    if (p->prior_sigma_theta == 0)
        return "prior_sigma_theta must be positive";
    if (p->max_cells < 1 || p->max_cells > HL_LOC_MAX_CELLS)
        return "max_cells must be in 1..2^26";
    if (p->group_mm != 0 && (p->group_mm < 8 || p->group_mm > 1000))
        return "group_mm must be 0 or in 8..1000";
    if (p->reading_stride < 1 || p->reading_stride > 64)
        return "reading_stride must be in 1..64";
    if (p->max_map_vectors < 1 || p->max_map_vectors > HL_MAP_MAX_CAPACITY)
        return "max_map_vectors must be in 1..2^20";
    return NULL;
}

int32_t hl_loc_slices(const hl_loc_params_t *p, bool search_theta)
{
    return search_theta ? 2 * p->theta_half_steps + 1 : 1;
}

int32_t hl_loc_window_cells(const hl_loc_params_t *p, hl_mm_t window_mm)
{
    return (int32_t)((2 * (int64_t)window_mm + p->cell_mm - 1) / p->cell_mm);
}

uint32_t hl_loc_cells_for_window(const hl_loc_params_t *p, hl_mm_t window_mm,
                                 bool search_theta)
{
    int64_t n = hl_loc_window_cells(p, window_mm);
    int64_t cells = n * n * hl_loc_slices(p, search_theta);
    return cells > UINT32_MAX ? UINT32_MAX : (uint32_t)cells;
}
