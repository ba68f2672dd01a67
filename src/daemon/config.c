/* config.c - defaults, INI file (libinih), presets, overrides (the file read and checked:
 * config_file.c; the rules over several keys: config_check.c; printing: config_print.c). */
#include "config.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "config_check.h"
#include "config_file.h"
#include "config_keys.h"
#include "houghloc/sounder.h"
#include "link.h"
#include "log.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)
/* A reason without the file or key, and a bounded path, so that messages fit. */
#define REASON_LEN 200
#define REASON(...) snprintf(why, REASON_LEN, __VA_ARGS__)
#define KEY_MSG_LEN 320   /* "key 'x.y': " + a reason */

void hl_config_apply_robot_profile(hl_config_t *c)
{
    hl_robot_profile_t rp;
    if (hl_robot_profile_find(c->robot_profile, &rp) == HL_OK)
        c->sounder.calib = rp.calib;
}

void hl_config_defaults(hl_config_t *c)
{
    memset(c, 0, sizeof *c);
    c->queue = 1000;
    c->save_every = 50;
    c->map_period_ms = HL_CONFIG_MAP_PERIOD_MS;
    c->map_input_ratio = 4;
    c->status_period_ms = 1000;
    c->idle_after_ms = HL_CONFIG_IDLE_AFTER_MS;
    c->compute_window = 100;
    c->log_level = HL_LOG_INFO;
    c->max_ahead_s = 300;
    snprintf(c->robot_profile, sizeof c->robot_profile, "bonnie");
    c->robot_sound_on_connect = true;
    c->robot_lost_soundings = HL_CONFIG_LOST_SOUNDINGS;
    c->robot_reconnect_max_ms = HL_CONFIG_RECONNECT_MAX_MS;
    c->robot_radius_mm = 250;       /* a Pioneer 3's, and houghloc-sim's */
    hl_sounder_params_default(&c->sounder);
    hl_drive_params_default(&c->drive);
    hl_rlink_params_default(&c->rlink);
    hl_fence_rect(&c->fence, -10000, -10000, 10000, 10000);
    snprintf(c->fence_text, sizeof c->fence_text, "-10,-10 10,-10 10,10 -10,10");
    hl_params_default(&c->params);
    hl_config_apply_robot_profile(c);
}

uint32_t hl_config_map_capacity(const hl_config_t *c)
{
    char v[32];
    hl_params_get(&c->params, "slam.map_capacity", v, sizeof v);
    return (uint32_t)strtoul(v, NULL, 10);
}

/* ---- values ------------------------------------------------------------------------ */

/* "X,Y X,Y ..." in metres -> vertices in mm. @return the count, or -1. */
static int parse_points(const char *s, hl_mm_t *x, hl_mm_t *y, int max)
{
    int n = 0;
    while (*s) {
        while (*s == ' ' || *s == '\t')
            s++;
        if (!*s)
            break;
        char *end;
        double vx = strtod(s, &end);
        if (end == s || *end != ',' || n >= max)
            return -1;
        s = end + 1;
        double vy = strtod(s, &end);
        if (end == s || (*end && *end != ' ' && *end != '\t' && *end != ','))
            return -1;
        if (!isfinite(vx) || !isfinite(vy) || fabs(vx) > 4194 || fabs(vy) > 4194)
            return -1;
        x[n] = (hl_mm_t)lround(vx * 1000.0);
        y[n] = (hl_mm_t)lround(vy * 1000.0);
        n++;
        s = *end == ',' ? end + 1 : end;    /* rect: "a,b,c,d" */
    }
    return n;
}

static bool set_fence(hl_config_t *c, const hl_config_key_t *k, const char *v, char *why)
{
    hl_mm_t x[HL_FENCE_MAX_VERTICES + 1], y[HL_FENCE_MAX_VERTICES + 1];
    int n = parse_points(v, x, y, HL_FENCE_MAX_VERTICES + 1);
    hl_fence_t f;
    if (k->type == HL_KEY_FENCE_RECT) {
        if (n != 2)
            return REASON("expected MIN_X,MIN_Y,MAX_X,MAX_Y in metres"), false;
        if (hl_fence_rect(&f, x[0], y[0], x[1], y[1]) != HL_OK)
            return REASON("the minimum must be below the maximum on both axes"), false;
    } else {
        if (n < 0)
            return REASON("expected X,Y pairs in metres separated by spaces"), false;
        if (hl_fence_polygon(&f, x, y, (uint32_t)n) != HL_OK) {
            const char *e = hl_fence_error(x, y, (uint32_t)n);
            return REASON("%s", e ? e : "not a simple polygon of 3 to 64 vertices"), false;
        }
    }
    c->fence = f;
    size_t len = 0;
    for (uint32_t i = 0; i < f.n && len < sizeof c->fence_text; i++)
        len += (size_t)snprintf(c->fence_text + len, sizeof c->fence_text - len, "%s%g,%g",
                                i ? " " : "", f.x_mm[i] / 1000.0, f.y_mm[i] / 1000.0);
    return true;
}

static bool check_link(const char *v, char *why)
{
    hl_link_spec_t spec;
    char reason[HL_LINK_WHY_LEN];
    if (hl_link_spec_parse(v, &spec, reason))
        return true;
    return REASON("%.190s", reason), false;
}

static bool check_profile(const char *v, char *why)
{
    hl_robot_profile_t profile;
    if (hl_robot_profile_find(v, &profile) == HL_OK)
        return true;
    return REASON("'%.60s' is not a robot profile (" HL_ROBOT_PROFILE_NAMES ")", v), false;
}

/* The longest line libinih reads whole (its 200-byte buffer holds 198 characters, the
 * newline and the terminating NUL): --print-config writes each key as one "key = value"
 * line, which must fit. */
#define PRINTED_LINE_MAX 198

/* A value that --print-config writes as "key = value" must read back the same: inih
 * takes a ';' or '#' at the start of a value or after a space for a comment. Such a value
 * can still reach us (a continuation line, "key=;", an override), so it is refused. */
static bool starts_comment(const char *v)
{
    for (const char *s = v; *s; s++)
        if ((*s == ';' || *s == '#') && (s == v || isspace((unsigned char)s[-1])))
            return true;
    return false;
}

/* Sets one key from its text. @return false with the reason (no file or line). */
static bool set_value(hl_config_t *c, const hl_config_key_t *k, const char *v, char *why)
{
    char *field = (char *)c + k->offset;
    double d = 0;
    bool b;
    switch (k->type) {
    case HL_KEY_LINK:
    case HL_KEY_ROBOT_PROFILE:
    case HL_KEY_STR:
        if (strlen(v) >= k->size)
            return REASON("longer than %zu characters", k->size - 1), false;
        if (strlen(strchr(k->name, '.') + 1) + 3 + strlen(v) > PRINTED_LINE_MAX)
            return REASON("longer than %zu characters (the printed 'key = value' line must "
                          "stay within %d)", PRINTED_LINE_MAX - 3 - strlen(strchr(k->name, '.') + 1),
                          PRINTED_LINE_MAX), false;
        if (starts_comment(v))
            return REASON("'%.60s': a ';' or '#' at its start or after a space would read back "
                          "as a comment", v), false;
        if (k->type == HL_KEY_LINK && *v && !check_link(v, why))
            return false;
        if (k->type == HL_KEY_ROBOT_PROFILE && !check_profile(v, why))
            return false;
        memcpy(field, v, strlen(v) + 1);
        return true;
    case HL_KEY_BOOL:
        if (!hl_params_parse_bool(v, &b))
            return REASON("'%s' is not true or false", v), false;
        *(bool *)field = b;
        return true;
    case HL_KEY_LEVEL: {
        int level = hl_log_parse_level(v);
        if (level < 0)
            return REASON("'%s' is not one of error, warning, notice, info, debug", v), false;
        *(int32_t *)field = level;
        return true;
    }
    case HL_KEY_FENCE_RECT:
    case HL_KEY_FENCE_POLYGON:
        return set_fence(c, k, v, why);
    default:
        break;
    }
    if (!hl_params_parse_number(v, &d))
        return REASON("'%s' is not a number", v), false;
    if (d < k->min || d > k->max)
        return REASON("%s is outside %.16g..%.16g", v, k->min, k->max), false;
    bool integral = k->type == HL_KEY_I32 || k->type == HL_KEY_U16;
    if (integral && d != floor(d))
        return REASON("%s is not a whole number", v), false;
    switch (k->type) {
    case HL_KEY_I32: *(int32_t *)field = (int32_t)d; break;
    case HL_KEY_U16: *(uint16_t *)field = (uint16_t)d; break;
    case HL_KEY_METRES: *(hl_mm_t *)field = (hl_mm_t)lround(d * 1000.0); break;
    case HL_KEY_DEG:
        /* 180 degrees is 32768 BAM, which a gate may use to mean "any direction" */
        *(hl_bam_t *)field = fabs(d) == 180.0 && k->min >= 0 ? 32768 : hl_bam_from_deg(d);
        break;
    default: break;
    }
    return true;
}

/* ---- one key, the daemon's or the core's ------------------------------------------ */

/* Keys renamed when the tracker's table took them over from [daemon]. */
static const char *const renamed[][2] = {
    { "daemon.lost_after", "slam.lost_after" },
    { "daemon.search_every", "slam.search_every" },
    { "daemon.lost_peak_ratio", "slam.lost_peak_ratio" },
};

/* A warning of this load, "WHERE: key 'KEY' WHAT" (main.c logs them). */
static void note(hl_config_t *c, const char *where, const char *key, const char *what,
                 const char *value)
{
    if (c->n_notes < HL_CONFIG_MAX_NOTES)
        snprintf(c->notes[c->n_notes++], HL_CONFIG_NOTE_LEN, "%.150s: key '%.60s' %s%.60s%s",
                 where, key, what, value, *value ? "): ignored" : "");
}

/* A retired daemon key @p k given @p v: its fixed value (a warning), or refused. */
static bool set_retired(hl_config_t *c, const hl_config_key_t *k, const char *v,
                        const char *where, char *why)
{
    hl_config_t *t = malloc(2 * sizeof *t);     /* [0] the defaults, [1] with v */
    if (!t)
        return REASON("out of memory"), false;
    hl_config_defaults(&t[0]);
    t[1] = t[0];
    char fixed[HL_CONFIG_VALUE_LEN], given[HL_CONFIG_VALUE_LEN];
    hl_config_format_value(&t[0], k->name, fixed, sizeof fixed);
    bool ok = set_value(&t[1], k, v, why);
    if (ok) {
        hl_config_format_value(&t[1], k->name, given, sizeof given);
        if (strcmp(given, fixed) == 0)
            note(c, where, k->name, "is no longer a setting (fixed at ", fixed);
        else
            ok = false, REASON("no longer a setting, fixed at %.60s", fixed);
    }
    free(t);
    return ok;
}

/* Sets the core's key @p name (its table decides: params.h). */
static bool set_core(hl_config_t *c, const hl_param_info_t *info, const char *v,
                     const char *where, char *why)
{
    if (info->level == HL_PARAM_STUDY)
        return REASON("a setting of the laboratory's studies (hl_params_set), not of "
                      "houghlocd"), false;
    if (hl_params_set(&c->params, info->key, v) != HL_OK) {
        const char *e = hl_params_error(&c->params);
        const char *tail = strstr(e, "': ");     /* the core says "key 'x.y': reason" */
        return REASON("%s", tail ? tail + 3 : e), false;
    }
    if (info->level == HL_PARAM_FIXED)
        note(c, where, info->key, "is no longer a setting (fixed at ", info->value);
    return true;
}

/* Sets @p name ("section.key") from @p v in the pass that takes it (@p presets_only: the
 * presets, slam.profile and robot.profile; else every other key). @return false with the
 * reason, or with *unknown set for a key neither the daemon nor the core has. */
static bool set_key(hl_config_t *c, const char *name, const char *v, bool presets_only,
                    const char *where, bool *unknown, char *why)
{
    *unknown = false;
    for (size_t i = 0; i < sizeof renamed / sizeof renamed[0]; i++)
        if (strcmp(name, renamed[i][0]) == 0) {
            char what[80];
            snprintf(what, sizeof what, "is now %s", renamed[i][1]);
            if (!presets_only)
                note(c, where, name, what, "");
            name = renamed[i][1];
        }
    const hl_config_key_t *k = hl_config_key_find(name);
    const hl_param_info_t *info = NULL;
    for (size_t i = 0; !k && (info = hl_params_info(i)) && strcmp(info->key, name) != 0; i++)
        ;
    if (!k && !info)
        return *unknown = true, false;
    bool preset = k ? k->type == HL_KEY_ROBOT_PROFILE : info->type == HL_PARAM_PRESET;
    if (presets_only != preset)
        return true;
    if (info)
        return set_core(c, info, v, where, why);
    return k->help ? set_value(c, k, v, why) : set_retired(c, k, v, where, why);
}

/* ---- the file and the overrides ------------------------------------------------------ */

typedef struct parse_ctx {
    hl_config_t *c;
    const char *path;
    bool presets_only;  /* first pass: only the presets (slam.mode, slam.profile,
                           robot.profile); second pass: all other keys */
    bool failed;
    char *why;
    const char *next;   /* the text not read yet (config_file.c: it holds no NUL) */
    int line;           /* the line being read: the one a handler call comes from */
    bool at_line_start;
    int long_line;      /* the first line longer than libinih reads, 0 if none */
    int max_line;
    int fail_line;
} parse_ctx_t;

/* libinih's reader over the file's text, as fgets reads a file (at most num - 1 bytes, up
 * to and with the newline), counting lines so that our own errors can name theirs. */
static char *read_line(char *str, int num, void *stream)
{
    parse_ctx_t *p = stream;
    if (*p->next == '\0' || num < 2)
        return NULL;
    size_t n = strcspn(p->next, "\n");
    if (p->next[n] == '\n')
        n++;
    if (n > (size_t)num - 1)
        n = (size_t)num - 1;
    memcpy(str, p->next, n);
    str[n] = '\0';
    p->next += n;
    if (p->at_line_start)
        p->line++;
    p->at_line_start = str[n - 1] == '\n';
    if (!p->at_line_start && *p->next && !p->long_line) {
        p->long_line = p->line;     /* libinih would read the rest as another line */
        p->max_line = num - 2;     /* the buffer also holds the newline and the NUL */
    }
    return str;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx_t *p = user;
    if (p->failed)
        return 0;
    char full[130], where[340], reason[REASON_LEN];
    snprintf(full, sizeof full, "%.63s.%.63s", section, name);
    snprintf(where, sizeof where, "%.300s:%d", p->path, p->line);
    bool unknown;
    if (set_key(p->c, full, value, p->presets_only, where, &unknown, reason))
        return 1;
    if (unknown)
        snprintf(p->why, KEY_MSG_LEN, "unknown key '%s' in section [%s]", name, section);
    else
        snprintf(p->why, KEY_MSG_LEN, "key '%.100s': %s", full, reason);
    p->failed = true;
    p->fail_line = p->line;
    return 0;
}

/* Runs one pass over the file's @p text. @return false with the reason in why. */
static bool parse_text(hl_config_t *c, const char *path, const char *text, bool presets_only,
                       char *why)
{
    char reason[KEY_MSG_LEN];
    parse_ctx_t p = { .c = c, .path = path, .presets_only = presets_only, .why = reason,
                      .next = text, .at_line_start = true };
    int rc = ini_parse_stream(read_line, &p, on_key, &p);
    if (rc == -2)
        return WHY("%s: out of memory while reading", path), false;
    if (p.long_line && (rc == 0 || rc >= p.long_line))
        return WHY("%.300s:%d: longer than %d characters, the longest line the reader takes",
                   path, p.long_line, p.max_line), false;
    if (rc == 0)
        return true;
    /* libinih reports the first bad line, ours or a syntax error before it */
    if (p.failed && (rc < 0 || rc >= p.fail_line))
        WHY("%.300s:%d: %s", path, p.fail_line, reason);
    else
        WHY("%.300s:%d: not a 'key = value' line or a [section]", path, rc);
    return false;
}

static bool apply_override(hl_config_t *c, const char *o, bool presets_only, char *why)
{
    const char *eq = strchr(o, '=');
    const char *dot = strchr(o, '.');
    if (!eq || !dot || dot > eq)
        return WHY("--set %s: expected SECTION.KEY=VALUE", o), false;
    char name[130], where[220], reason[REASON_LEN];
    size_t len = (size_t)(eq - o);
    if (len >= sizeof name)
        return WHY("--set %.200s: unknown key", o), false;
    memcpy(name, o, len);
    name[len] = '\0';
    snprintf(where, sizeof where, "--set %.200s", o);
    bool unknown;
    if (set_key(c, name, eq + 1, presets_only, where, &unknown, reason))
        return true;
    if (unknown)
        return WHY("--set %.200s: unknown key '%s'", o, name), false;
    return WHY("--set %.200s: %s", o, reason), false;
}

/* The file's text (NULL for none), then the overrides, in the two passes. */
static bool load_text(hl_config_t *c, const char *path, const char *text,
                      const char *const *overrides, int n_overrides, char *why)
{
    /* Pass 1: the presets, from the file then the overrides; pass 2: the rest. */
    for (int pass = 0; pass < 2; pass++) {
        bool presets_only = pass == 0;
        if (text && !parse_text(c, path, text, presets_only, why))
            return false;
        for (int i = 0; i < n_overrides; i++)
            if (!apply_override(c, overrides[i], presets_only, why))
                return false;
        if (presets_only)
            hl_config_apply_robot_profile(c);
    }
    return hl_config_check(c, why);
}

bool hl_config_load(hl_config_t *c, const char *path, bool optional,
                    const char *const *overrides, int n_overrides, char *why)
{
    hl_config_defaults(c);
    char *text = NULL;
    if (path) {
        /* read once, checked (config_file.h), and parsed twice from memory */
        hl_config_file_status_t st = hl_config_file_read(path, &text, why);
        if (st == HL_CONFIG_FILE_MISSING && optional)
            path = NULL;    /* no default file: the compiled-in defaults apply */
        else if (st != HL_CONFIG_FILE_OK)
            return false;
    }
    bool ok = load_text(c, path, text, overrides, n_overrides, why);
    free(text);
    return ok;
}
