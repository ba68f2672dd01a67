/* profiles.c - the sensor profiles (the core's presets) as fragments, and the advice for
 * a map file larger than the configured map (profiles.h). */
#include "profiles.h"

#include <stdlib.h>
#include <string.h>

const hl_param_preset_t *hl_sensor_profile_find(const char *name)
{
    const hl_param_preset_t *p;
    for (size_t i = 0; name && (p = hl_params_preset(i)); i++)
        if (strcmp(name, p->name) == 0)
            return p;
    return NULL;
}

const char *hl_sensor_profile_names(void)
{
    const hl_param_info_t *k;
    for (size_t i = 0; (k = hl_params_info(i)); i++)
        if (k->type == HL_PARAM_PRESET)
            return k->range;
    return "";
}

void hl_sensor_profile_print(const hl_param_preset_t *p, FILE *out)
{
    fprintf(out,
            "; houghloc sensor profile '%s' (houghlocd --print-profile %s):\n"
            "; %s.\n"
            "; Its keys, as `slam.profile = %s` sets them over the defaults, before every\n"
            "; other key; read as a configuration file, this sets the same.\n",
            p->name, p->name, p->summary, p->name);
    if (p->count == 0) {
        fputs("; It sets no key.\n", out);
        return;
    }
    const char *section = "";
    size_t section_len = 0;
    for (size_t i = 0; i < p->count; i++) {
        const char *key = p->settings[i].key, *dot = strchr(key, '.');
        size_t len = (size_t)(dot - key);
        if (len != section_len || strncmp(key, section, len) != 0) {
            fprintf(out, "\n[%.*s]\n", (int)len, key);
            section = key;
            section_len = len;
        }
        fprintf(out, "; %s\n%s = %s\n", p->settings[i].why, dot + 1, p->settings[i].value);
    }
}

uint32_t hl_sensor_profile_capacity(const hl_param_preset_t *p)
{
    for (size_t i = 0; p && i < p->count; i++)
        if (strcmp(p->settings[i].key, "slam.map_capacity") == 0)
            return (uint32_t)strtoul(p->settings[i].value, NULL, 10);
    return 0;
}

void hl_capacity_advice(const char *path, uint32_t count, uint32_t capacity, char *out,
                        size_t cap)
{
    /* the profile with the smallest map that holds the file, if any */
    const hl_param_preset_t *fits = NULL, *p;
    for (size_t i = 0; (p = hl_params_preset(i)); i++) {
        uint32_t c = hl_sensor_profile_capacity(p);
        if (c >= count && (!fits || c < hl_sensor_profile_capacity(fits)))
            fits = p;
    }
    char profile[64] = "";
    if (fits)
        snprintf(profile, sizeof profile, ", or slam.profile = %s", fits->name);
    snprintf(out, cap,
             "%.300s: holds %u vectors, more than slam.map_capacity = %u: raise it "
             "(--set slam.map_capacity=%u%s) or start afresh with --fresh-map (which moves "
             "this file aside)",
             path, count, capacity, count, profile);
}
