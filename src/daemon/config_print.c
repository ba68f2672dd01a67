/* config_print.c - the configuration written back as an INI file: every key
 * (--print-config=all) or the operator's (--print-config, packaging/houghlocd.conf), each
 * under its section with its comment, in a form that reads back to the same values. */
#include "config.h"

#include <stdlib.h>
#include <string.h>

#include "config_keys.h"
#include "log.h"

#define VALUE_LEN HL_CONFIG_VALUE_LEN

/* The fewest decimals (up to 17 significant digits) that read back as @p v, in plain
 * notation: 0.05, 30, 1.1 rather than 0.050000000000000003 or 3e+01. */
static void format_double(char *buf, size_t cap, double v)
{
    for (int decimals = 0; decimals <= 17; decimals++) {
        snprintf(buf, cap, "%.*f", decimals, v);
        if (strtod(buf, NULL) == v)
            return;
    }
    /* a value too small for 17 decimals (1e-30 would print as 0): 17 significant digits
     * always read back the same double */
    snprintf(buf, cap, "%.17g", v);
}

/* The value of @p k in @p c as the file writes it (config_keys.h). */
void hl_config_format_value(const hl_config_t *c, const hl_config_key_t *k, char *buf,
                            size_t cap)
{
    const char *field = (const char *)c + k->offset;
    buf[0] = '\0';
    switch (k->type) {
    case HL_KEY_STR:
    case HL_KEY_LINK:
    case HL_KEY_ROBOT_PROFILE: snprintf(buf, cap, "%s", field); break;
    case HL_KEY_I32: snprintf(buf, cap, "%d", *(const int32_t *)field); break;
    case HL_KEY_U16: snprintf(buf, cap, "%u", *(const uint16_t *)field); break;
    case HL_KEY_U32: snprintf(buf, cap, "%u", *(const uint32_t *)field); break;
    case HL_KEY_U64:
        snprintf(buf, cap, "%llu", (unsigned long long)*(const uint64_t *)field);
        break;
    case HL_KEY_DOUBLE: format_double(buf, cap, *(const double *)field); break;
    case HL_KEY_BOOL: snprintf(buf, cap, "%s", *(const bool *)field ? "true" : "false"); break;
    case HL_KEY_DEG: {
        hl_bam_t a = *(const hl_bam_t *)field;
        double deg = k->min < 0 ? hl_bam_to_sdeg(a) : a == 32768 ? 180.0 : hl_bam_to_deg(a);
        /* the fewest decimals that read back as the same BAM */
        for (int decimals = 0; decimals <= 17; decimals++) {
            snprintf(buf, cap, "%.*f", decimals, deg);
            if (hl_bam_from_deg(strtod(buf, NULL)) == a)
                break;
        }
        break;
    }
    case HL_KEY_METRES: snprintf(buf, cap, "%.3f", *(const hl_mm_t *)field / 1000.0); break;
    case HL_KEY_Q8: snprintf(buf, cap, "%g", *(const uint16_t *)field / 256.0); break;
    case HL_KEY_LEVEL:
        snprintf(buf, cap, "%s", hl_log_level_name(*(const int32_t *)field));
        break;
    case HL_KEY_MODE: snprintf(buf, cap, "%s", c->mode); break;
    case HL_KEY_SENSOR_PROFILE: snprintf(buf, cap, "%s", c->profile); break;
    case HL_KEY_FENCE_POLYGON: snprintf(buf, cap, "%s", c->fence_text); break;
    case HL_KEY_FENCE_RECT: break;
    }
}

/* Writes the keys @p show picks, each under its section with its comment. */
static void print_keys(const hl_config_t *c, FILE *out,
                       bool (*show)(const hl_config_t *, const hl_config_key_t *, const void *),
                       const void *arg)
{
    char section[64] = "", value[VALUE_LEN];
    for (size_t i = 0; i < hl_config_nkeys; i++) {
        const hl_config_key_t *k = &hl_config_keys[i];
        if (k->type == HL_KEY_FENCE_RECT || !show(c, k, arg))
            continue;   /* the fence prints as its polygon, which reads back the same */
        const char *dot = strchr(k->name, '.');
        size_t slen = (size_t)(dot - k->name);
        if (strncmp(section, k->name, slen) != 0 || section[slen] != '\0') {
            fprintf(out, "%s[%.*s]\n", section[0] ? "\n" : "", (int)slen, k->name);
            snprintf(section, sizeof section, "%.*s", (int)slen, k->name);
        }
        hl_config_format_value(c, k, value, sizeof value);
        fprintf(out, "; %s\n%s = %s\n", k->help, dot + 1, value);
    }
}

static bool show_all(const hl_config_t *c, const hl_config_key_t *k, const void *arg)
{
    (void)c, (void)k, (void)arg;
    return true;
}

void hl_config_print(const hl_config_t *c, FILE *out)
{
    fputs("; houghlocd configuration (INI): every key with its value; ';' starts a comment.\n"
          "; Keys left out keep the compiled-in defaults, or the value slam.mode, slam.profile\n"
          "; or robot.profile gives them; `houghlocd --print-config=all` prints every key,\n"
          "; `--print-config` the operator's, and README.md explains each section.\n\n", out);
    print_keys(c, out, show_all, NULL);
}

/* The operator's keys; any other key whose value differs from what the defaults and the
 * presets of @p c give it (@p arg: that configuration), so that nothing set is hidden and
 * the printout reads back the same; a preset key when it differs from the default. */
static bool show_operator(const hl_config_t *c, const hl_config_key_t *k, const void *arg)
{
    if (hl_config_key_for_operator(k))
        return true;
    const hl_config_t *const *base = arg;   /* [0]: the defaults, [1]: with c's presets */
    char mine[VALUE_LEN], theirs[VALUE_LEN];
    hl_config_format_value(c, k, mine, sizeof mine);
    hl_config_format_value(base[hl_config_key_is_preset(k) ? 0 : 1], k, theirs, sizeof theirs);
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
    snprintf(base[1].mode, sizeof base[1].mode, "%s", c->mode);
    snprintf(base[1].profile, sizeof base[1].profile, "%s", c->profile);
    snprintf(base[1].robot_profile, sizeof base[1].robot_profile, "%s", c->robot_profile);
    char why[HL_CONFIG_WHY_LEN];
    hl_config_apply_presets(&base[1], why);
    const hl_config_t *bases[2] = { &base[0], &base[1] };
    fputs("; houghlocd configuration (INI; ';' starts a comment): the keys an operator sets.\n"
          "; Every other key (the localizer's, the map's, the sounding's, the link's) keeps\n"
          "; its compiled-in value, or the one slam.mode, slam.profile or robot.profile\n"
          "; gives it; any may still be set here in its [section] or with --set, and\n"
          "; `houghlocd --print-config=all` lists them all with their comments.\n\n", out);
    print_keys(c, out, show_operator, bases);
    free(base);
}
