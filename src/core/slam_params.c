/* slam_params.c - the slam's parameters: defaults, validation, and the map's cull and
 * density bound as they set it up (slam.h). */
#include "houghloc/slam.h"

#include "houghloc-internal/closure.h"   /* HL_CLOSURE_MAX_STOPS */

void hl_slam_params_default(hl_slam_params_t *p)
{
    hl_loc_params_default(&p->loc);
    p->map_capacity = HL_MAP_DEFAULT_CAPACITY;
    p->map_per_place = 0;
    p->map_square_mm = 50;
    p->cull_choices = 1;
    p->confirm_mm = 100;
    p->cull_crowded = false;
    p->crowd_square_mm = 0;
    p->seed = 1;
    p->heading_gain = 1.0;
    p->guarded = true;
    p->interpolate = true;
    p->use_prior = true;
    p->window_mm = 1000;
    p->search_theta = true;
    p->wild_mm = 500;
    p->min_confidence = 0.05;
    p->min_votes = 20;
    p->min_peak_ratio = 0.25;
    p->echo_bearings = true;
    hl_echo_params_default(&p->echo);
    p->fit_normals = false;
    hl_normals_params_default(&p->normals);
    p->refine = true;
    p->refine_heading = true;
    hl_refine_params_default(&p->refine_params);
    p->close_loops = false;
    p->closure_stops = 256;
    p->keyframe_mm = 0;
    p->keyframe_turn = 0;
    p->closure_match_weight = 1;
    p->closure_matches_per_scan = 0;
    p->closure_match_readings = 0;
    p->closure_redraw_readings = 0;
    p->closure_redraw_mm = 0;
    p->square_walls = false;
    p->wall_axis = 0;
    p->long_drive_mm = 0;
    p->long_drive_turn = hl_bam_from_deg(6.0);
    p->long_drive_turns = 2;
    hl_reloc_params_default(&p->reloc);
    /* The lost state is off until the global search meets its wrong-answer target
     * (docs/results/relocalization.md): a wrong answer adopted moves the robot's
     * estimate, and the map, to the wrong place. hl_slam_lose works regardless. */
    p->lost_after = 0;
    p->lost_peak_ratio = 0.5;
    p->search_every = 0;
}

const char *hl_slam_params_error(const hl_slam_params_t *p)
{
    if (!p)
        return "no slam parameters";
    if (p->map_capacity < 1 || p->map_capacity > HL_MAP_MAX_CAPACITY)
        return "map_capacity must be in 1..1048576";
    if (p->map_per_place > HL_MAP_MAX_PER_PLACE)
        return "map_per_place must be in 0..1000";
    if (!(p->heading_gain >= 0.0 && p->heading_gain <= 1.0))
        return "heading_gain must be in 0..1";
    if (p->map_square_mm < HL_MAP_MIN_SQUARE_MM || p->map_square_mm > HL_MAP_MAX_SQUARE_MM)
        return "map_square_mm must be in 10..1000";
    if (p->cull_choices < 1 || p->cull_choices > HL_MAP_MAX_CHOICES)
        return "cull_choices must be in 1..64";
    if (p->confirm_mm < 1 || p->confirm_mm > HL_MAP_MAX_SQUARE_MM)
        return "confirm_mm must be in 1..1000";
    if (p->crowd_square_mm != 0 && (p->crowd_square_mm < HL_MAP_MIN_SQUARE_MM ||
                                     p->crowd_square_mm > HL_MAP_MAX_SQUARE_MM))
        return "crowd_square_mm must be 0 or in 10..1000";
    if (p->crowd_square_mm != 0 && !p->cull_crowded)
        return "crowd_square_mm is the crowding cull's: it needs cull_crowded";
    if (p->cull_crowded && (p->cull_choices < 2 || p->map_per_place == 0))
        return "cull_crowded needs cull_choices of 2 or more and a map_per_place bound";
    hl_loc_params_t lp = p->loc;    /* as hl_slam_create makes the localizer */
    lp.max_map_vectors = p->map_capacity;
    const char *e = hl_loc_params_error(&lp);
    if (e)
        return e;
    if (p->window_mm < 0 || p->window_mm > 1000000)
        return "window_mm must be in 0..1000000";
    if (p->window_mm > 0 &&
        hl_loc_cells_for_window(&p->loc, p->window_mm, p->search_theta) > p->loc.max_cells)
        return "the search window needs more raster cells than max_cells";
    if (p->wild_mm < 1)
        return "wild_mm must be positive";
    if (!(p->min_confidence >= 0.0 && p->min_confidence <= 1.0))
        return "min_confidence must be in 0..1";
    if (!(p->min_peak_ratio >= 0.0 && p->min_peak_ratio <= 1.0))
        return "min_peak_ratio must be in 0..1";
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
    if (p->keyframe_mm < 0 || p->keyframe_mm > 100000)
        return "keyframe_mm must be in 0..100000";
    if (p->keyframe_turn > HL_BAM_HALF_TURN)
        return "keyframe_turn must be at most a half turn";
    if (p->square_walls && !p->close_loops)
        return "square_walls needs close_loops";
    if (p->long_drive_mm < 0 || p->long_drive_mm > 1000000)
        return "long_drive_mm must be in 0..1000000";
    if (p->long_drive_mm > 0 &&
        (p->long_drive_turns < 1 || p->long_drive_turns > HL_SLAM_MAX_DRIVE_TURNS ||
         p->long_drive_turn == 0 ||
         (uint32_t)p->long_drive_turn * p->long_drive_turns > HL_BAM_QUARTER_TURN))
        return "long drives need long_drive_turns in 1..4 and long_drive_turn above 0, "
               "turning at most 90 degrees in all";
    if (p->lost_after < 0 || p->lost_after > 1000000)
        return "lost_after must be in 0..1000000";
    if (!(p->lost_peak_ratio >= 0 && p->lost_peak_ratio <= 1))
        return "lost_peak_ratio must be in 0..1";
    if (p->search_every < 0 || p->search_every > 1000000)
        return "search_every must be in 0..1000000";
    return hl_reloc_params_error(&p->reloc);
}

void hl_slam_map_params(const hl_slam_params_t *p, hl_map_params_t *out)
{
    *out = (hl_map_params_t){
        .capacity = p->map_capacity, .seed = p->seed,
        .per_place = p->map_per_place, .square_mm = p->map_square_mm,
        .cull_choices = p->cull_choices, .confirm_mm = p->confirm_mm,
        .cull_crowded = p->cull_crowded, .crowd_square_mm = p->crowd_square_mm,
    };
}
