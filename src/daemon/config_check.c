/* config_check.c - the rules over several configuration keys, in the keys' names
 * (config_check.h): the core's for its keys (hl_params_check), the robot layer's here,
 * each mirroring the line of hl_drive_params_error ... named above it. */
#include "config_check.h"

#include <stdio.h>
#include <string.h>

#include "config_keys.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)

/* "section.key (value)", the value as the file writes it (degrees, metres). */
#define KV_LEN 100
typedef char kv_t[KV_LEN];

static const char *kv(const hl_config_t *c, const char *name, kv_t buf)
{
    char value[HL_CONFIG_VALUE_LEN] = "?";
    hl_config_format_value(c, name, value, sizeof value);
    snprintf(buf, KV_LEN, "%s (%.40s)", name, value);
    return buf;
}

/* hl_drive_params_error. */
static bool check_robot(const hl_config_t *c, char *why)
{
    kv_t a, b;
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
    /* The tracker's keys: the core's rules, in the keys' names (params.h). */
    hl_params_t p = c->params;
    if (hl_params_check(&p) != HL_OK)
        return WHY("config: %s", hl_params_error(&p)), false;
    if (!check_robot(c, why))
        return false;
    /* A rule of the libraries not stated above: their own words, which name a parameter
     * but not its section. */
    const char *e = hl_sounder_params_error(&c->sounder);
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
