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
#include "houghloc-internal/daemon_config.h"
#include "houghloc/sounder.h"
#include "link.h"
#include "log.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)
/* A reason without the file or key, and a bounded path, so that messages fit. */
#define REASON_LEN 200
#define REASON(...) snprintf(why, REASON_LEN, __VA_ARGS__)
#define KEY_MSG_LEN 320   /* "key 'x.y': " + a reason */

/* The paper's method (tools/experiments/modes.cpp's paper mode): every localization
 * extends the map, global search, best cell, readings on their beam axes. */
static void paper_preset(hl_slam_params_t *p)
{
    hl_slam_params_default(p);
    p->loc.cell_mm = 47;
    p->loc.blur_sigma_mm = 50;
    p->loc.max_cells = 1u << 22;
    p->loc.group_mm = 0;         /* every pair votes, as in the paper */
    p->guarded = false;
    p->use_prior = false;
    p->interpolate = false;
    p->window_mm = 0;
    p->echo_bearings = false;
    p->refine = false;
}

/* The daemon's LOST state is on (docs/design/relocalization.md): the global search
 * answers wrong on at most 1 % of the kidnap trials of every row
 * (docs/results/relocalization.md), so that a robot moved while the daemon was down, or
 * carried while it ran, is found rather than driven from where it was. The watch
 * searches every scan tracking is in doubt about (after a restart until a search
 * confirms the pose, a rejected one, one matched far worse than the recent ones) and
 * every 10th scan besides (about 30 ms a search against 1 ms of tracking; the continuous
 * profiles turn it off, profiles.c), and two doubtful scans in a row make it lost.
 * The library's tracker leaves it to its caller (hl_slam_params_default); the paper's
 * method had none. */
static void daemon_preset(hl_slam_params_t *p)
{
    hl_slam_params_default(p);
    p->lost_after = 2;
    p->search_every = 10;
}

static void apply_mode(hl_config_t *c)
{
    if (strcmp(c->mode, "paper") == 0)
        paper_preset(&c->slam);
    else
        daemon_preset(&c->slam);
}

static bool set_value(hl_config_t *c, const hl_config_key_t *k, const char *v, char *why);

/* The presets, in order: slam.mode sets the method's parameters afresh, slam.profile's
 * keys go over them (so that its fragment, --print-profile, read as a file means the
 * same), robot.profile gives the calibration. The other keys come after all three.
 * @return false with "config: ..." in why (a profile key the table cannot set). */
bool hl_config_apply_presets(hl_config_t *c, char *why)
{
    apply_mode(c);
    const hl_sensor_profile_t *sp = hl_sensor_profile_find(c->profile);
    for (size_t i = 0; sp && i < sp->n_keys; i++) {
        const hl_config_key_t *k = hl_config_key_find(sp->keys[i].key);
        char reason[200];
        if (!k || !set_value(c, k, sp->keys[i].value, reason))
            return snprintf(why, HL_CONFIG_WHY_LEN, "config: slam.profile %s: cannot set %s",
                            sp->name, sp->keys[i].key), false;
    }
    hl_robot_profile_t rp;
    if (hl_robot_profile_find(c->robot_profile, &rp) == HL_OK)
        c->sounder.calib = rp.calib;
    return true;
}

bool hl_config_key_is_preset(const hl_config_key_t *k)
{
    return k->type == HL_KEY_MODE || k->type == HL_KEY_SENSOR_PROFILE ||
           k->type == HL_KEY_ROBOT_PROFILE;
}

void hl_config_defaults(hl_config_t *c)
{
    memset(c, 0, sizeof *c);
    c->queue = 1000;
    c->save_every = 50;
    c->map_period_ms = 1000;
    c->map_input_ratio = 4;
    c->status_period_ms = 1000;
    c->idle_after_ms = 5000;
    c->compute_window = 100;
    c->log_level = HL_LOG_INFO;
    c->max_ahead_s = 300;
    snprintf(c->robot_profile, sizeof c->robot_profile, "bonnie");
    c->robot_sound_on_connect = true;
    c->robot_lost_soundings = 3;
    c->robot_reconnect_max_ms = 5000;
    c->robot_radius_mm = 250;       /* a Pioneer 3's, and houghloc-sim's */
    hl_sounder_params_default(&c->sounder);
    hl_drive_params_default(&c->drive);
    hl_rlink_params_default(&c->rlink);
    hl_fence_rect(&c->fence, -10000, -10000, 10000, 10000);
    snprintf(c->fence_text, sizeof c->fence_text, "-10,-10 10,-10 10,10 -10,10");
    snprintf(c->mode, sizeof c->mode, "improved");
    snprintf(c->profile, sizeof c->profile, HL_SENSOR_PROFILE_DEFAULT);
    char why[HL_CONFIG_WHY_LEN];
    hl_config_apply_presets(c, why);  /* the defaults' presets set nothing a table could refuse */
}

/* ---- values ------------------------------------------------------------------------ */

static bool parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    while (*end == ' ' || *end == '\t')
        end++;
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
        return false;
    *out = v;
    return true;
}

static bool parse_bool(const char *s, bool *out)
{
    static const char *const yes[] = { "true", "yes", "on", "1" };
    static const char *const no[] = { "false", "no", "off", "0" };
    for (int i = 0; i < 4; i++) {
        if (strcmp(s, yes[i]) == 0)
            return *out = true, true;
        if (strcmp(s, no[i]) == 0)
            return *out = false, true;
    }
    return false;
}

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
        if (!parse_bool(v, &b))
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
    case HL_KEY_MODE:
        if (strcmp(v, "improved") != 0 && strcmp(v, "paper") != 0)
            return REASON("'%s' is not improved or paper", v), false;
        snprintf(c->mode, sizeof c->mode, "%s", v);
        return true;   /* applied as a preset by hl_config_load */
    case HL_KEY_SENSOR_PROFILE:
        if (!hl_sensor_profile_find(v))
            return REASON("'%.60s' is not a sensor profile (" HL_SENSOR_PROFILE_NAMES ")", v),
                   false;
        snprintf(c->profile, sizeof c->profile, "%s", v);
        return true;   /* applied as a preset by hl_config_load */
    case HL_KEY_FENCE_RECT:
    case HL_KEY_FENCE_POLYGON:
        return set_fence(c, k, v, why);
    default:
        break;
    }
    if (!parse_double(v, &d))
        return REASON("'%s' is not a number", v), false;
    if (d < k->min || d > k->max)
        return REASON("%s is outside %.16g..%.16g", v, k->min, k->max), false;
    bool integral = k->type == HL_KEY_I32 || k->type == HL_KEY_U16 || k->type == HL_KEY_U32 ||
                    k->type == HL_KEY_U64;
    if (integral && d != floor(d))
        return REASON("%s is not a whole number", v), false;
    switch (k->type) {
    case HL_KEY_I32: *(int32_t *)field = (int32_t)d; break;
    case HL_KEY_U16: *(uint16_t *)field = (uint16_t)d; break;
    case HL_KEY_U32: *(uint32_t *)field = (uint32_t)d; break;
    case HL_KEY_U64: *(uint64_t *)field = (uint64_t)d; break;
    case HL_KEY_DOUBLE: *(double *)field = d; break;
    case HL_KEY_METRES: *(hl_mm_t *)field = (hl_mm_t)lround(d * 1000.0); break;
    case HL_KEY_Q8: *(uint16_t *)field = (uint16_t)lround(d * 256.0); break;
    case HL_KEY_DEG:
        /* 180 degrees is 32768 BAM, which a gate may use to mean "any direction" */
        *(hl_bam_t *)field = fabs(d) == 180.0 && k->min >= 0 ? 32768 : hl_bam_from_deg(d);
        break;
    default: break;
    }
    return true;
}

static const hl_config_key_t *find_key(const char *section, const char *name)
{
    size_t slen = strlen(section);
    for (size_t i = 0; i < hl_config_nkeys; i++) {
        const char *full = hl_config_keys[i].name;
        if (strncmp(full, section, slen) == 0 && full[slen] == '.' &&
            strcmp(full + slen + 1, name) == 0)
            return &hl_config_keys[i];
    }
    return NULL;
}

/* ---- the file and the overrides ------------------------------------------------------ */

typedef struct parse_ctx {
    hl_config_t *c;
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
    const hl_config_key_t *k = find_key(section, name);
    char reason[REASON_LEN];
    if (!k) {
        snprintf(p->why, KEY_MSG_LEN, "unknown key '%s' in section [%s]", name, section);
    } else if (p->presets_only != hl_config_key_is_preset(k)) {
        return 1;
    } else if (set_value(p->c, k, value, reason)) {
        return 1;
    } else {
        snprintf(p->why, KEY_MSG_LEN, "key '%s': %s", k->name, reason);
    }
    p->failed = true;
    p->fail_line = p->line;
    return 0;
}

/* Runs one pass over the file's @p text. @return false with the reason in why. */
static bool parse_text(hl_config_t *c, const char *path, const char *text, bool presets_only,
                       char *why)
{
    char reason[KEY_MSG_LEN];
    parse_ctx_t p = { .c = c, .presets_only = presets_only, .why = reason, .next = text,
                      .at_line_start = true };
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
    char section[64], name[64];
    size_t slen = (size_t)(dot - o), nlen = (size_t)(eq - dot - 1);
    if (slen >= sizeof section || nlen >= sizeof name)
        return WHY("--set %s: unknown key", o), false;
    memcpy(section, o, slen);
    section[slen] = '\0';
    memcpy(name, dot + 1, nlen);
    name[nlen] = '\0';
    const hl_config_key_t *k = find_key(section, name);
    if (!k)
        return WHY("--set %s: unknown key '%s.%s'", o, section, name), false;
    if (presets_only != hl_config_key_is_preset(k))
        return true;
    char reason[REASON_LEN];
    if (!set_value(c, k, eq + 1, reason))
        return WHY("--set %.200s: %s", o, reason), false;
    return true;
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
        if (presets_only && !hl_config_apply_presets(c, why))
            return false;
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

_Static_assert(HL_DAEMON_CONFIG_WHY_LEN == HL_CONFIG_WHY_LEN, "the research tools' why buffer");

bool hl_daemon_config_slam(const char *path, const char *const *overrides, int n_overrides,
                           hl_slam_params_t *out, char why[HL_DAEMON_CONFIG_WHY_LEN])
{
    hl_config_t *c = malloc(sizeof *c);
    if (!c) {
        snprintf(why, HL_CONFIG_WHY_LEN, "config: out of memory");
        return false;
    }
    bool ok = hl_config_load(c, path, false, overrides, n_overrides, why);
    if (ok)
        *out = c->slam;
    free(c);
    return ok;
}
