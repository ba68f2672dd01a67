/*
 * params.c - hl_params_t (params.h): values set and read by name through the table
 * (params_table.c), the profiles applied, and the rules over several keys.
 */
#include "houghloc/params.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/params.h"
#include "houghloc/fixed.h"

_Static_assert(sizeof(hl_params_body_t) <= HL_PARAMS_SIZE, "hl_params_t holds its values");

static hl_params_body_t *body(hl_params_t *p)
{
    return (hl_params_body_t *)(void *)p->private_.bytes;
}

static const hl_params_body_t *cbody(const hl_params_t *p)
{
    return (const hl_params_body_t *)(const void *)p->private_.bytes;
}

/* ---- values as text ------------------------------------------------------------------ */

/* Degrees to BAM; 180 is 32768, which a gate may use to mean "any direction". */
static hl_bam_t bam_of(double deg)
{
    return fabs(deg) == 180.0 ? (hl_bam_t)32768u : hl_bam_from_deg(deg);
}

#define WHY(buf, ...) snprintf(buf, HL_PARAMS_WHY_LEN, __VA_ARGS__)

/* A number for @p e: parsed, whole if it must be, in range. @return HL_OK, or
 * HL_ERR_PARSE / HL_ERR_RANGE with why. */
static hl_status_t number_for(const hl_param_entry_t *e, const char *text, double *d, char *why)
{
    const char *key = e->info.key;
    if (!hl_params_parse_number(text, d))
        return WHY(why, "key '%s': '%.40s' is not a number", key, text), HL_ERR_PARSE;
    if (e->info.type == HL_PARAM_INT && *d != floor(*d))
        return WHY(why, "key '%s': %.40s is not a whole number", key, text), HL_ERR_PARSE;
    if (e->info.level != HL_PARAM_FIXED && !(e->zero_ok && *d == 0) &&
        (*d < e->min || *d > e->max))
        return WHY(why, "key '%s': %.40s is outside %s", key, text, e->info.range),
               HL_ERR_RANGE;
    return HL_OK;
}

/* Parses @p text for @p e and writes it to @p field (as e->store says). @return
 * HL_OK, or HL_ERR_PARSE / HL_ERR_RANGE with why. */
static hl_status_t store(const hl_param_entry_t *e, void *field, const char *text, char *why)
{
    if (e->store == HL_PARAM_STORE_BOOL) {
        bool b;
        if (!hl_params_parse_bool(text, &b))
            return WHY(why, "key '%s': '%.40s' is not true or false", e->info.key, text),
                   HL_ERR_PARSE;
        *(bool *)field = b;
        return HL_OK;
    }
    double d;
    hl_status_t st = number_for(e, text, &d, why);
    if (st != HL_OK)
        return st;
    switch (e->store) {
    case HL_PARAM_STORE_I32: *(int32_t *)field = (int32_t)d; break;
    case HL_PARAM_STORE_U16: *(uint16_t *)field = (uint16_t)d; break;
    case HL_PARAM_STORE_U32: *(uint32_t *)field = (uint32_t)d; break;
    case HL_PARAM_STORE_U64: *(uint64_t *)field = (uint64_t)d; break;
    case HL_PARAM_STORE_DOUBLE: *(double *)field = d; break;
    case HL_PARAM_STORE_BAM: *(hl_bam_t *)field = bam_of(d); break;
    default: break;
    }
    return HL_OK;
}

/* The fewest decimals (up to 17 significant digits) that read back as @p v, in plain
 * notation: 0.05, 30, 1.1 rather than 0.050000000000000003 or 3e+01. */
static void format_double(char *buf, size_t cap, double v)
{
    for (int decimals = 0; decimals <= 17; decimals++) {
        snprintf(buf, cap, "%.*f", decimals, v);
        if (strtod(buf, NULL) == v)
            return;
    }
    snprintf(buf, cap, "%.17g", v);     /* too small for 17 decimals */
}

static void format(const hl_param_entry_t *e, const void *field, char *buf, size_t cap)
{
    switch (e->store) {
    case HL_PARAM_STORE_I32: snprintf(buf, cap, "%d", *(const int32_t *)field); break;
    case HL_PARAM_STORE_U16: snprintf(buf, cap, "%u", *(const uint16_t *)field); break;
    case HL_PARAM_STORE_U32: snprintf(buf, cap, "%u", *(const uint32_t *)field); break;
    case HL_PARAM_STORE_U64:
        snprintf(buf, cap, "%llu", (unsigned long long)*(const uint64_t *)field);
        break;
    case HL_PARAM_STORE_DOUBLE: format_double(buf, cap, *(const double *)field); break;
    case HL_PARAM_STORE_BOOL: snprintf(buf, cap, "%s", *(const bool *)field ? "true" : "false");
        break;
    case HL_PARAM_STORE_BAM: {
        hl_bam_t a = *(const hl_bam_t *)field;
        double deg = a == 32768 ? 180.0 : hl_bam_to_deg(a);
        for (int decimals = 0; decimals <= 17; decimals++) {   /* the fewest that read back */
            snprintf(buf, cap, "%.*f", decimals, deg);
            if (bam_of(strtod(buf, NULL)) == a)
                break;
        }
        break;
    }
    default: snprintf(buf, cap, "%s", e->info.value); break;
    }
}

/* ---- the table ------------------------------------------------------------------------ */

const hl_param_entry_t *hl_param_find(const char *key)
{
    for (size_t i = 0; key && i < hl_param_table_len; i++)
        if (strcmp(hl_param_table[i].info.key, key) == 0)
            return &hl_param_table[i];
    return NULL;
}

static bool is_field(const hl_param_entry_t *e)
{
    return e->store != HL_PARAM_STORE_NONE;
}

void hl_params_fill_defaults(void *dst, size_t base, size_t size)
{
    char why[HL_PARAMS_WHY_LEN];
    for (size_t i = 0; i < hl_param_table_len; i++) {
        const hl_param_entry_t *e = &hl_param_table[i];
        if (is_field(e) && e->offset >= base && e->offset < base + size)
            (void)store(e, (char *)dst + (e->offset - base), e->info.value, why);
    }
}

void hl_slam_params_default(hl_slam_params_t *p)
{
    memset(p, 0, sizeof *p);
    hl_loc_params_default(&p->loc);
    hl_echo_params_default(&p->echo);
    hl_normals_params_default(&p->normals);
    hl_refine_params_default(&p->refine_params);
    hl_reloc_params_default(&p->reloc);
    hl_params_fill_defaults(p, 0, sizeof *p);
}

/* ---- the API -------------------------------------------------------------------------- */

void hl_params_default(hl_params_t *p)
{
    memset(p, 0, sizeof *p);
    hl_slam_params_default(&body(p)->slam);
    body(p)->profile = 0;
}

static size_t preset_index(const char *name)
{
    for (size_t i = 0; i < hl_param_presets_len; i++)
        if (strcmp(hl_param_presets[i].name, name) == 0)
            return i;
    return hl_param_presets_len;
}

/* The fixed key @p e given @p text: its own value, or refused. */
static hl_status_t check_fixed(const hl_param_entry_t *e, const char *text, char *why)
{
    bool same;
    if (e->info.type == HL_PARAM_WORD) {
        same = strcmp(text, e->info.value) == 0;
    } else if (e->info.type == HL_PARAM_BOOL) {
        bool a, b;
        if (!hl_params_parse_bool(text, &a))
            return WHY(why, "key '%s': '%.40s' is not true or false", e->info.key, text),
                   HL_ERR_PARSE;
        same = hl_params_parse_bool(e->info.value, &b) && a == b;
    } else {
        double a, b = 0;
        hl_status_t st = number_for(e, text, &a, why);
        if (st != HL_OK)
            return st;
        hl_params_parse_number(e->info.value, &b);
        same = e->info.type == HL_PARAM_DEG ? bam_of(a) == bam_of(b) : a == b;
    }
    if (same)
        return HL_OK;
    WHY(why, "key '%s': no longer a setting, fixed at %s%s%s", e->info.key, e->info.value,
        e->info.help ? " (" : "", e->info.help ? e->info.help : "");
    if (e->info.help)
        strncat(why, ")", HL_PARAMS_WHY_LEN - strlen(why) - 1);
    return HL_ERR_RANGE;
}

/* Sets @p e in @p b from @p text. */
static hl_status_t set_entry(hl_params_body_t *b, const hl_param_entry_t *e, const char *text)
{
    if (e->info.level == HL_PARAM_FIXED)
        return check_fixed(e, text, b->why);
    if (e->info.type == HL_PARAM_PRESET) {
        size_t i = preset_index(text);
        if (i == hl_param_presets_len)
            return WHY(b->why, "key '%s': '%.40s' is not one of %s", e->info.key, text,
                       e->info.range), HL_ERR_PARSE;
        hl_slam_params_t fresh;
        hl_slam_params_default(&fresh);
        hl_slam_params_t keep = b->slam;
        b->slam = fresh;
        const hl_param_preset_t *pr = &hl_param_presets[i];
        for (size_t k = 0; k < pr->count; k++) {
            const hl_param_entry_t *s = hl_param_find(pr->settings[k].key);
            hl_status_t st = s ? set_entry(b, s, pr->settings[k].value) : HL_ERR_ARG;
            if (st != HL_OK) {      /* the table's own mistake: say so, change nothing */
                b->slam = keep;
                return WHY(b->why, "key '%s': profile %s cannot set %s", e->info.key,
                           pr->name, pr->settings[k].key), st;
            }
        }
        b->profile = (uint32_t)i;
        return HL_OK;
    }
    return store(e, (char *)&b->slam + e->offset, text, b->why);
}

hl_status_t hl_params_set(hl_params_t *p, const char *key, const char *value)
{
    if (!p)
        return HL_ERR_ARG;
    hl_params_body_t *b = body(p);
    b->why[0] = '\0';
    if (!key || !value)
        return WHY(b->why, "no key or no value"), HL_ERR_ARG;
    const hl_param_entry_t *e = hl_param_find(key);
    if (!e)
        return WHY(b->why, "unknown key '%.60s'", key), HL_ERR_ARG;
    hl_status_t st = set_entry(b, e, value);
    if (st == HL_OK)
        b->why[0] = '\0';
    return st;
}

hl_status_t hl_params_get(const hl_params_t *p, const char *key, char *buf, size_t cap)
{
    const hl_param_entry_t *e = hl_param_find(key);
    if (cap > 0 && buf)
        buf[0] = '\0';
    if (!p || !e || !buf || cap == 0)
        return HL_ERR_ARG;
    if (e->info.type == HL_PARAM_PRESET)
        snprintf(buf, cap, "%s", hl_param_presets[cbody(p)->profile].name);
    else
        format(e, (const char *)&cbody(p)->slam + e->offset, buf, cap);
    return HL_OK;
}

const char *hl_params_error(const hl_params_t *p)
{
    return p && cbody(p)->why[0] ? cbody(p)->why : NULL;
}

const hl_param_info_t *hl_params_info(size_t i)
{
    return i < hl_param_table_len ? &hl_param_table[i].info : NULL;
}

const hl_param_preset_t *hl_params_preset(size_t i)
{
    return i < hl_param_presets_len ? &hl_param_presets[i] : NULL;
}

/* ---- the rules over several keys ---------------------------------------------------- */

/* "key (value)" for a message. */
typedef char kv_t[96];

static const char *kv(const hl_params_t *p, const char *key, kv_t buf)
{
    char value[40];
    hl_params_get(p, key, value, sizeof value);
    snprintf(buf, sizeof(kv_t), "%s (%s)", key, value);
    return buf;
}

hl_status_t hl_params_check(hl_params_t *p)
{
    if (!p)
        return HL_ERR_ARG;
    hl_params_body_t *b = body(p);
    const hl_slam_params_t *s = &b->slam;
    kv_t x, y, z;
    b->why[0] = '\0';
    if (s->loc.blur_sigma_mm > 10 * s->loc.cell_mm)
        WHY(b->why, "%s must be at most 10 x %s", kv(p, "localize.blur_sigma_mm", x),
            kv(p, "localize.cell_mm", y));
    else if (s->window_mm > 0 &&
             hl_loc_cells_for_window(&s->loc, s->window_mm, true) > s->loc.max_cells)
        WHY(b->why, "%s needs %u raster cells of %s over %d headings, more than %s",
            kv(p, "slam.window_mm", x), hl_loc_cells_for_window(&s->loc, s->window_mm, true),
            kv(p, "localize.cell_mm", y), 2 * HL_LOC_THETA_HALF_STEPS + 1,
            kv(p, "localize.max_cells", z));
    else if (s->crowd_square_mm != 0 && !s->cull_crowded)
        WHY(b->why, "%s is the crowding cull's: it needs %s set to true",
            kv(p, "slam.crowd_square_mm", x), kv(p, "slam.cull_crowded", y));
    else if (s->cull_crowded && s->cull_choices < 2)
        WHY(b->why, "%s needs %s of at least 2", kv(p, "slam.cull_crowded", x),
            kv(p, "slam.cull_choices", y));
    else if (s->cull_crowded && s->map_per_place == 0)
        WHY(b->why, "%s needs %s above 0 (a bound per place)", kv(p, "slam.cull_crowded", x),
            kv(p, "slam.map_per_place", y));
    else if (s->square_walls && !s->close_loops)
        WHY(b->why, "%s needs %s set to true", kv(p, "slam.square_walls", x),
            kv(p, "slam.close_loops", y));
    else if (hl_slam_params_error(s))   /* a value set directly (hl_params_slam) */
        WHY(b->why, "slam parameters: %s", hl_slam_params_error(s));
    return b->why[0] ? HL_ERR_RANGE : HL_OK;
}
