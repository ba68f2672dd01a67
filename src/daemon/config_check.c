/* config_check.c - the rules over several configuration keys, in the keys' names
 * (config_check.h). Each rule is the library's, in the order the library checks them:
 * the line of hl_slam_params_error, hl_loc_params_error, ... it mirrors is named above it. */
#include "config_check.h"

#include <stdio.h>
#include <string.h>

#include "config_keys.h"
#include "houghloc/echo.h"
#include "houghloc/fixed.h"
#include "houghloc/localize.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)

/* "section.key (value)", the value as the file writes it (degrees, metres). */
#define KV_LEN 100
typedef char kv_t[KV_LEN];

static const char *kv(const hl_config_t *c, const char *name, kv_t buf)
{
    const hl_config_key_t *k = hl_config_key_find(name);
    char value[HL_CONFIG_VALUE_LEN] = "?";
    if (k)
        hl_config_format_value(c, k, value, sizeof value);
    snprintf(buf, KV_LEN, "%s (%.40s)", name, value);
    return buf;
}

static double span_deg(hl_bam_t step, unsigned half_steps)
{
    return (double)step * (2.0 * half_steps + 1.0) * 360.0 / HL_BAM_PER_TURN;
}

/* hl_slam_params_error: the map's culls. */
static bool check_culls(const hl_config_t *c, char *why)
{
    const hl_slam_params_t *p = &c->slam;
    kv_t a, b;
    if (p->crowd_square_mm != 0 && p->crowd_square_mm < 10)
        return WHY("config: %s must be 0 or in 10..1000", kv(c, "slam.crowd_square_mm", a)),
               false;
    if (p->crowd_square_mm != 0 && !p->cull_crowded)
        return WHY("config: %s is the crowding cull's: it needs %s set to true",
                   kv(c, "slam.crowd_square_mm", a), kv(c, "slam.cull_crowded", b)), false;
    if (p->cull_crowded && p->cull_choices < 2)
        return WHY("config: %s needs %s of at least 2", kv(c, "slam.cull_crowded", a),
                   kv(c, "slam.cull_choices", b)), false;
    if (p->cull_crowded && p->map_per_place == 0)
        return WHY("config: %s needs %s above 0 (a bound per place)",
                   kv(c, "slam.cull_crowded", a), kv(c, "slam.map_per_place", b)), false;
    return true;
}

/* hl_loc_params_error, on slam.loc; then hl_slam_params_error's search window. */
static bool check_localize(const hl_config_t *c, char *why)
{
    const hl_loc_params_t *l = &c->slam.loc;
    kv_t a, b, d, e;
    if ((uint32_t)l->theta_step * (2u * l->theta_half_steps + 1u) > HL_BAM_HALF_TURN)
        return WHY("config: %s x (2 x %s + 1) must span at most 180 degrees (it spans %.4g)",
                   kv(c, "localize.theta_step_deg", a), kv(c, "localize.theta_half_steps", b),
                   span_deg(l->theta_step, l->theta_half_steps)), false;
    if (l->blur_sigma_mm > 10 * l->cell_mm)
        return WHY("config: %s must be at most 10 x %s", kv(c, "localize.blur_sigma_mm", a),
                   kv(c, "localize.cell_mm", b)), false;
    if (l->group_mm != 0 && l->group_mm < 8)
        return WHY("config: %s must be 0 or in 8..1000", kv(c, "localize.group_mm", a)), false;
    const hl_slam_params_t *p = &c->slam;
    uint32_t cells = p->window_mm > 0 ? hl_loc_cells_for_window(l, p->window_mm, p->search_theta)
                                      : 0;
    if (cells > l->max_cells && p->search_theta)
        return WHY("config: %s needs %u raster cells of %s over 2 x %s + 1 headings "
                   "(slam.search_theta), more than %s", kv(c, "slam.window_mm", a), cells,
                   kv(c, "localize.cell_mm", b), kv(c, "localize.theta_half_steps", d),
                   kv(c, "localize.max_cells", e)), false;
    if (cells > l->max_cells)
        return WHY("config: %s needs %u raster cells of %s, more than %s",
                   kv(c, "slam.window_mm", a), cells, kv(c, "localize.cell_mm", b),
                   kv(c, "localize.max_cells", d)), false;
    /* the global search's last stage sizes its own raster for its window, every heading */
    uint32_t fine = hl_loc_cells_for_window(l, p->reloc.fine_window_mm, true);
    if (fine > HL_LOC_MAX_CELLS)
        return WHY("config: %s needs %u raster cells of %s over 2 x %s + 1 headings, more "
                   "than the %u a search may have", kv(c, "reloc.fine_window_mm", a), fine,
                   kv(c, "localize.cell_mm", b), kv(c, "localize.theta_half_steps", d),
                   HL_LOC_MAX_CELLS), false;
    return true;
}

/* hl_echo_params_error and hl_normals_params_error, which apply only when the slam uses
 * echo bearings or fitted normals. */
static bool check_readings(const hl_config_t *c, char *why)
{
    const hl_slam_params_t *p = &c->slam;
    kv_t a, b, d;
    unsigned candidates = p->echo.step ? 2u * p->echo.half_beam / p->echo.step + 1u : 0;
    if (p->echo_bearings && (p->echo.step == 0 || candidates > HL_ECHO_MAX_CANDIDATES))
        return WHY("config: %s and %s give %u candidate bearings (2 x half beam / step + 1), "
                   "more than %d, with %s", kv(c, "echo.half_beam_deg", a),
                   kv(c, "echo.step_deg", b), candidates, HL_ECHO_MAX_CANDIDATES,
                   kv(c, "slam.echo_bearings", d)), false;
    if (p->echo_bearings && p->echo.noise_mm < 1)
        return WHY("config: %s must be at least 1 with %s", kv(c, "echo.noise_mm", a),
                   kv(c, "slam.echo_bearings", b)), false;
    const hl_normals_params_t *n = &c->slam.normals;
    if (p->fit_normals && n->min_points > 2 * n->half_window + 1)
        return WHY("config: %s must be at most 2 x %s + 1 (the points of a window), with %s",
                   kv(c, "normals.min_points", a), kv(c, "normals.half_window", b),
                   kv(c, "slam.fit_normals", d)), false;
    return true;
}

/* hl_slam_params_error: loop closure's square walls, and long drives. */
static bool check_closure(const hl_config_t *c, char *why)
{
    const hl_slam_params_t *p = &c->slam;
    kv_t a, b, d;
    if (p->square_walls && !p->close_loops)
        return WHY("config: %s needs %s set to true", kv(c, "slam.square_walls", a),
                   kv(c, "slam.close_loops", b)), false;
    if (p->long_drive_mm > 0 &&
        (uint32_t)p->long_drive_turn * p->long_drive_turns > HL_BAM_QUARTER_TURN)
        return WHY("config: %s x %s must turn at most 90 degrees in all (it turns %.4g), with "
                   "%s", kv(c, "slam.long_drive_turn_deg", a), kv(c, "slam.long_drive_turns", b),
                   (double)p->long_drive_turn * p->long_drive_turns * 360.0 / HL_BAM_PER_TURN,
                   kv(c, "slam.long_drive_mm", d)), false;
    return true;
}

/* hl_reloc_params_error. */
static bool check_reloc(const hl_config_t *c, char *why)
{
    const hl_reloc_params_t *r = &c->slam.reloc;
    kv_t a, b;
    if (2u * r->coarse_half_steps * r->coarse_theta_step < 64u)
        return WHY("config: %s x 2 x %s must span at least 0.35 degrees",
                   kv(c, "reloc.coarse_theta_step_deg", a),
                   kv(c, "reloc.coarse_half_steps", b)), false;
    if ((uint32_t)r->coarse_theta_step * (2u * r->coarse_half_steps + 1u) > HL_BAM_HALF_TURN)
        return WHY("config: %s x (2 x %s + 1) must span at most 180 degrees (it spans %.4g)",
                   kv(c, "reloc.coarse_theta_step_deg", a), kv(c, "reloc.coarse_half_steps", b),
                   span_deg(r->coarse_theta_step, r->coarse_half_steps)), false;
    if (r->coarse_blur_mm > 10 * r->coarse_cell_mm)
        return WHY("config: %s must be at most 10 x %s", kv(c, "reloc.coarse_blur_mm", a),
                   kv(c, "reloc.coarse_cell_mm", b)), false;
    if (r->coarse_group_mm != 0 && r->coarse_group_mm < 8)
        return WHY("config: %s must be 0 or in 8..1000", kv(c, "reloc.coarse_group_mm", a)),
               false;
    if (r->short_mm != 0 && r->short_mm <= 300)
        return WHY("config: %s must be 0 or in 301..10000", kv(c, "reloc.short_mm", a)), false;
    return true;
}

/* hl_calib_error (under hl_sounder_params_error) and hl_drive_params_error. */
static bool check_robot(const hl_config_t *c, char *why)
{
    kv_t a, b;
    if (c->sounder.calib.min_raw >= c->sounder.calib.sentinel_raw)
        return WHY("config: %s must be below %s", kv(c, "calibration.min_raw", a),
                   kv(c, "calibration.sentinel_raw", b)), false;
    const hl_drive_params_t *d = &c->drive;
    if (d->max_leg_mm < d->arrive_mm)
        return WHY("config: %s must be at least %s", kv(c, "drive.max_leg_mm", a),
                   kv(c, "drive.arrive_mm", b)), false;
    if (d->slow_mm != 0 && d->slow_mm <= d->stop_mm)
        return WHY("config: %s must be 0 (never slow) or above %s", kv(c, "drive.slow_mm", a),
                   kv(c, "drive.stop_mm", b)), false;
    return true;
}

bool hl_config_check(const hl_config_t *c, char *why)
{
    if (!check_culls(c, why) || !check_localize(c, why) || !check_readings(c, why) ||
        !check_closure(c, why) || !check_reloc(c, why) || !check_robot(c, why))
        return false;
    /* A rule of the libraries not stated above: their own words, which name a parameter
     * but not its section. */
    const char *e = hl_slam_params_error(&c->slam);
    if (!e)
        e = hl_sounder_params_error(&c->sounder);
    if (!e)
        e = hl_drive_params_error(&c->drive);
    if (!e)
        e = hl_rlink_params_error(&c->rlink);
    if (e)
        return WHY("config: %s", e), false;
    char channel[HL_BUS_CHANNEL_MAX];
    if (!hl_bus_channel(c->prefix, HL_CHANNEL_DESTINATION, channel))
        return WHY("config: lcm.prefix '%s' must be at most %d of A-Z a-z 0-9 _ - . /",
                   c->prefix, HL_BUS_PREFIX_MAX), false;
    return true;
}
