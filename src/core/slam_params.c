/* slam_params.c - the slam's parameters as the stages need them: their validation, and
 * the map's cull and density bound as they set it up (slam_params.h). The defaults,
 * ranges and names are params_table.c's. */
#include "houghloc-internal/slam_params.h"

#include "houghloc-internal/closure.h"   /* HL_CLOSURE_MAX_STOPS */

const char *hl_slam_params_error(const hl_slam_params_t *p)
{
    if (!p)
        return "no slam parameters";
    if (p->map_capacity < 1 || p->map_capacity > HL_MAP_MAX_CAPACITY)
        return "map_capacity must be in 1..1048576";
    if (!(p->heading_gain >= 0.0 && p->heading_gain <= 1.0))
        return "heading_gain must be in 0..1";
    if (!(p->wall_gain >= 0.0 && p->wall_gain <= 1.0))
        return "wall_gain must be in 0..1";
    hl_map_params_t mp;
    hl_slam_map_params(p, &mp);
    const char *e = hl_map_params_error(&mp);
    if (e)
        return e;
    if (p->crowd_square_mm != 0 && !p->cull_crowded)
        return "crowd_square_mm is the crowding cull's: it needs cull_crowded";
    hl_loc_params_t lp = p->loc;    /* as hl_slam_create makes the localizer */
    lp.max_map_vectors = p->map_capacity;
    e = hl_loc_params_error(&lp);
    if (e)
        return e;
    if (p->window_mm < 0 || p->window_mm > 1000000)
        return "window_mm must be in 0..1000000";
    if (p->window_mm > 0 && hl_loc_cells_for_window(&p->loc, p->window_mm, true) > p->loc.max_cells)
        return "the search window needs more raster cells than max_cells";
    if (p->echo_bearings && hl_echo_params_error(&p->echo))
        return hl_echo_params_error(&p->echo);
    if (p->fit_normals && hl_normals_params_error(&p->normals))
        return hl_normals_params_error(&p->normals);
    if (p->refine && hl_refine_params_error(&p->refine_params))
        return hl_refine_params_error(&p->refine_params);
    if (p->closure_stops < 2 || p->closure_stops > HL_CLOSURE_MAX_STOPS)
        return "closure_stops must be in 2..4096";
    if (!(p->closure_match_weight > 0 && p->closure_match_weight <= 1))
        return "closure_match_weight must be in (0, 1]";
    if (p->closure_match_readings > HL_SCAN_MAX_READINGS)
        return "closure_match_readings must be in 0..1024";
    if (p->closure_redraw_mm < 0 || p->closure_redraw_mm > 1000)
        return "closure_redraw_mm must be in 0..1000";
    if (p->closure_redraw_stop_mm < 0 || p->closure_redraw_stop_mm > 1000)
        return "closure_redraw_stop_mm must be in 0..1000";
    if (p->keyframe_mm < 0 || p->keyframe_mm > 100000)
        return "keyframe_mm must be in 0..100000";
    if (p->square_walls && !p->close_loops)
        return "square_walls needs close_loops";
    if (p->multiscan_mm < 0 || p->multiscan_mm > 100000)
        return "multiscan_mm must be in 0..100000";
    if (p->multiscan_turn > HL_BAM_HALF_TURN)
        return "multiscan_turn must be at most a half turn";
    if (p->multiscan_mm > 0 && p->close_loops)
        return "multiscan_mm needs close_loops off: loop closure's stops are scans drawn "
               "as they come";
    if (p->long_drive_mm < 0 || p->long_drive_mm > 1000000)
        return "long_drive_mm must be in 0..1000000";
    if (p->lost_after < 0 || p->lost_after > 1000000)
        return "lost_after must be in 0..1000000";
    if (p->search_every < 0 || p->search_every > 1000000)
        return "search_every must be in 0..1000000";
    return hl_reloc_params_error(&p->reloc);
}

void hl_slam_map_params(const hl_slam_params_t *p, hl_map_params_t *out)
{
    *out = (hl_map_params_t){
        .capacity = p->map_capacity, .seed = p->seed,
        .per_place = p->map_per_place, .square_mm = p->map_square_mm,
        .round_places = p->map_round_places,
        .cull_choices = p->cull_choices, .confirm_mm = HL_MAP_CONFIRM_MM,
        .cull_crowded = p->cull_crowded, .crowd_square_mm = p->crowd_square_mm,
    };
}
