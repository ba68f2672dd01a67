/* config_print.c - the configuration written back as an INI file: every key
 * (--print-config=all) or the operator's (--print-config, packaging/houghlocd.conf), each
 * under its section with its comment, in a form that reads back to the same values. */
#include "config.h"

#include <stdlib.h>
#include <string.h>

#include "config_keys.h"
#include "log.h"

#define VALUE_LEN HL_CONFIG_VALUE_LEN

const hl_param_info_t *hl_config_core_key(const char *name)
{
    const hl_param_info_t *k;
    for (size_t i = 0; (k = hl_params_info(i)); i++)
        if (strcmp(k->key, name) == 0)
            return k->level <= HL_PARAM_EXPERT ? k : NULL;
    return NULL;
}

/* The value of the daemon's key @p k in @p c as the file writes it (config_keys.h). */
static void format_own(const hl_config_t *c, const hl_config_key_t *k, char *buf, size_t cap)
{
    const char *field = (const char *)c + k->offset;
    buf[0] = '\0';
    switch (k->type) {
    case HL_KEY_STR:
    case HL_KEY_LINK:
    case HL_KEY_ROBOT_PROFILE: snprintf(buf, cap, "%s", field); break;
    case HL_KEY_I32: snprintf(buf, cap, "%d", *(const int32_t *)field); break;
    case HL_KEY_U16: snprintf(buf, cap, "%u", *(const uint16_t *)field); break;
    case HL_KEY_BOOL: snprintf(buf, cap, "%s", *(const bool *)field ? "true" : "false"); break;
    case HL_KEY_DEG: {
        hl_bam_t a = *(const hl_bam_t *)field;
        double deg = k->min < 0 ? hl_bam_to_sdeg(a) : hl_bam_to_deg(a);
        /* the fewest decimals that read back as the same BAM */
        for (int decimals = 0; decimals <= 17; decimals++) {
            snprintf(buf, cap, "%.*f", decimals, deg);
            if (hl_bam_from_deg(strtod(buf, NULL)) == a)
                break;
        }
        break;
    }
    case HL_KEY_METRES: snprintf(buf, cap, "%.3f", *(const hl_mm_t *)field / 1000.0); break;
    case HL_KEY_LEVEL:
        snprintf(buf, cap, "%s", hl_log_level_name(*(const int32_t *)field));
        break;
    case HL_KEY_FENCE_POLYGON: snprintf(buf, cap, "%s", c->fence_text); break;
    case HL_KEY_FENCE_RECT:
    case HL_KEY_CORE: break;
    }
}

void hl_config_format_value(const hl_config_t *c, const char *name, char *buf, size_t cap)
{
    const hl_config_key_t *k = hl_config_key_find(name);
    if (k)
        format_own(c, k, buf, cap);
    else if (hl_params_get(&c->params, name, buf, cap) != HL_OK && cap > 0)
        buf[0] = '\0';
}

/* A key to print: its name, its comment, whether it is an operator's. */
typedef struct shown {
    const char *name;
    const char *help;
    bool operator_key;
} shown_t;

/* Writes one key under its section (opening it when it differs from @p section's). */
static void print_one(const hl_config_t *c, FILE *out, const shown_t *k, char section[64])
{
    char value[VALUE_LEN];
    const char *dot = strchr(k->name, '.');
    size_t slen = (size_t)(dot - k->name);
    if (strncmp(section, k->name, slen) != 0 || section[slen] != '\0') {
        fprintf(out, "%s[%.*s]\n", section[0] ? "\n" : "", (int)slen, k->name);
        snprintf(section, 64, "%.*s", (int)slen, k->name);
    }
    hl_config_format_value(c, k->name, value, sizeof value);
    fprintf(out, "; %s\n%s = %s\n", k->help, dot + 1, value);
}

/* Writes the keys @p show picks, each under its section with its comment: the daemon's,
 * and the core's where the daemon's table holds their place. */
static void print_keys(const hl_config_t *c, FILE *out,
                       bool (*show)(const hl_config_t *, const shown_t *, const void *),
                       const void *arg)
{
    char section[64] = "";
    for (size_t i = 0; i < hl_config_nkeys; i++) {
        const hl_config_key_t *k = &hl_config_keys[i];
        if (k->type == HL_KEY_CORE) {
            const hl_param_info_t *info;
            for (size_t j = 0; (info = hl_params_info(j)); j++) {
                shown_t s = { info->key, info->help, info->level == HL_PARAM_OPERATOR };
                if (info->level <= HL_PARAM_EXPERT && show(c, &s, arg))
                    print_one(c, out, &s, section);
            }
            continue;
        }
        shown_t s = { k->name, k->help, hl_config_key_for_operator(k) };
        /* the fence prints as its polygon, which reads back the same; a retired key not */
        if (k->type != HL_KEY_FENCE_RECT && k->help && show(c, &s, arg))
            print_one(c, out, &s, section);
    }
}

static bool show_all(const hl_config_t *c, const shown_t *k, const void *arg)
{
    (void)c, (void)k, (void)arg;
    return true;
}

void hl_config_print(const hl_config_t *c, FILE *out)
{
    fputs("; houghlocd configuration (INI): every key with its value; ';' starts a comment.\n"
          "; Keys left out keep the compiled-in defaults, or the value slam.profile or\n"
          "; robot.profile gives them; `houghlocd --print-config=all` prints every key,\n"
          "; `--print-config` the operator's, and README.md explains each section.\n\n", out);
    print_keys(c, out, show_all, NULL);
}

/* The operator's keys; any other key whose value differs from what the defaults and the
 * presets of @p c give it (@p arg: that configuration), so that nothing set is hidden and
 * the printout reads back the same; a preset key when it differs from the default. */
static bool show_operator(const hl_config_t *c, const shown_t *k, const void *arg)
{
    if (k->operator_key)
        return true;
    const hl_config_t *const *base = arg;   /* [0]: the defaults, [1]: with c's presets */
    bool preset = strcmp(k->name, "slam.profile") == 0 || strcmp(k->name, "robot.profile") == 0;
    char mine[VALUE_LEN], theirs[VALUE_LEN];
    hl_config_format_value(c, k->name, mine, sizeof mine);
    hl_config_format_value(base[preset ? 0 : 1], k->name, theirs, sizeof theirs);
    return strcmp(mine, theirs) != 0;
}

void hl_config_print_operator(const hl_config_t *c, FILE *out)
{
    hl_config_t *base = malloc(2 * sizeof *base);
    if (!base) {    /* cannot tell what changed: print everything, which reads back too */
        hl_config_print(c, out);
        return;
    }
    hl_config_defaults(&base[0]);
    hl_config_defaults(&base[1]);
    char profile[64];
    hl_params_get(&c->params, "slam.profile", profile, sizeof profile);
    hl_params_set(&base[1].params, "slam.profile", profile);
    snprintf(base[1].robot_profile, sizeof base[1].robot_profile, "%s", c->robot_profile);
    hl_config_apply_robot_profile(&base[1]);
    const hl_config_t *bases[2] = { &base[0], &base[1] };
    fputs("; houghlocd configuration (INI; ';' starts a comment): the keys an operator sets.\n"
          "; Every other key (the localizer's, the map's, the guard's, loop closure's) keeps\n"
          "; its compiled-in value, or the one slam.profile or robot.profile gives it; any\n"
          "; may still be set here in its [section] or with --set, and\n"
          "; `houghlocd --print-config=all` lists them all with their comments.\n\n", out);
    print_keys(c, out, show_operator, bases);
    free(base);
}
