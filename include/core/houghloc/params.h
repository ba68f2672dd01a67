/*
 * params.h - the tracker's parameters: one table of every setting of the localizer, the
 * map, the guard, loop closure and the global search, each with its name, type, range,
 * default and one line of help; set and read by name, as text; and the sensor profiles,
 * presets of the table.
 *
 *     hl_params_t p;
 *     hl_params_default(&p);                              // sonar-stops, the defaults
 *     if (hl_params_set(&p, "slam.profile", "laser") != HL_OK ||
 *         hl_params_set(&p, "slam.map_capacity", "30000") != HL_OK ||
 *         hl_params_check(&p) != HL_OK)
 *         fprintf(stderr, "%s\n", hl_params_error(&p));   // one line naming the key
 *     hl_slam_t *s = hl_slam_create(&p);                  // slam.h
 *
 * Keys are "section.name" (slam.*, localize.*, echo.*, normals.*, reloc.*), the sections
 * of houghlocd's configuration file, which passes them here unchanged. Values are text as
 * such a file writes them: whole numbers, numbers, true/false (also yes/no, on/off, 1/0),
 * angles in degrees. Units are in the names (_mm, _deg, _pct).
 *
 * slam.profile is a preset: setting it puts every other key at that profile's value (the
 * defaults, then the profile's settings), so a program sets it first and its own keys
 * after. The profiles: sonar-stops (the defaults: the paper's sonar ring sounded at
 * stops), sonar-continuous (a sonar ring sounded several times a second), laser (a 2-D
 * laser scanner) and paper (the paper's method alone).
 *
 * Levels (hl_param_info_t.level): an operator's keys, a research program's (the expert
 * keys), the laboratory's studies' (accepted here, not offered by houghlocd), and keys
 * that are no longer settings: fixed at the value the table gives, which hl_params_set
 * still accepts (and refuses any other), so that an old file reads as before or is told
 * what changed. Why each is fixed: the constant's comment in the core.
 *
 * hl_params_t is a value: the caller owns it (on the stack, in a struct), copies it with
 * =, and needs no cleanup; its contents are private. Not thread-safe per object (each
 * call may write the object's error line); distinct objects are independent.
 */
#ifndef HOUGHLOC_PARAMS_H
#define HOUGHLOC_PARAMS_H

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/export.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Room in hl_params_t, bytes; the core checks at build time that its values fit. */
#define HL_PARAMS_SIZE 2048
/* The longest error line hl_params_error returns, with its NUL. */
#define HL_PARAMS_WHY_LEN 400

typedef struct hl_params {
    union {                     /* private: read and written by the functions below */
        uint64_t align_u64;
        double align_double;
        void *align_ptr;
        unsigned char bytes[HL_PARAMS_SIZE];
    } private_;
} hl_params_t;

typedef enum hl_param_type {
    HL_PARAM_INT = 0,       /* a whole number */
    HL_PARAM_REAL = 1,      /* a number */
    HL_PARAM_BOOL = 2,      /* true or false (yes/no, on/off, 1/0 read as well) */
    HL_PARAM_DEG = 3,       /* an angle, degrees */
    HL_PARAM_PRESET = 4,    /* a profile's name: sets every other key (above) */
    HL_PARAM_WORD = 5,      /* one word (a fixed key's) */
} hl_param_type_t;

typedef enum hl_param_level {
    HL_PARAM_OPERATOR = 0,  /* what a robot's operator sets (houghlocd --print-config) */
    HL_PARAM_EXPERT = 1,    /* a research knob a program offers (--print-config=all) */
    HL_PARAM_STUDY = 2,     /* a setting of the laboratory's studies: the library takes
                               it, houghlocd does not */
    HL_PARAM_FIXED = 3,     /* no longer a setting: fixed at `value` */
} hl_param_level_t;

/* One key of the table. Every string is static. */
typedef struct hl_param_info {
    const char *key;        /* "section.name" */
    hl_param_type_t type;
    hl_param_level_t level;
    const char *range;      /* "1..1000", "0 or 8..1000", "true or false", or the
                               profiles' names; NULL for a fixed key */
    const char *value;      /* the default as text (a fixed key: its value) */
    const char *help;       /* one line (a fixed key: what replaces it, or NULL) */
} hl_param_info_t;

/* One setting of a preset, as a configuration file would write it. */
typedef struct hl_param_setting {
    const char *key;
    const char *value;
    const char *why;        /* one line */
} hl_param_setting_t;

/* A profile: the settings slam.profile = name makes over the defaults. */
typedef struct hl_param_preset {
    const char *name;       /* "sonar-stops", "sonar-continuous", "laser", "paper" */
    const char *summary;    /* one line: what it is for */
    const hl_param_setting_t *settings;
    size_t count;           /* 0 for sonar-stops, the defaults */
} hl_param_preset_t;

/** Fills @p p with the defaults (the sonar-stops profile); clears its error line.
 *  @p p must not be NULL. */
HL_API void hl_params_default(hl_params_t *p);

/**
 * Sets the key @p key ("section.name") to @p value (text, as above). slam.profile sets
 * every other key first (above). A fixed key takes its own value only, and changes nothing.
 * @return HL_OK; HL_ERR_ARG for NULL or an unknown key; HL_ERR_PARSE for a value of the
 *         wrong form (not a number, not a whole number, not true or false, not a
 *         profile); HL_ERR_RANGE for a number outside the key's range, or another value
 *         for a fixed key. On error @p p's values are unchanged and hl_params_error(@p p)
 *         says why in one line naming the key ("localize.cell_mm: 0 is outside 1..1000").
 */
HL_API hl_status_t hl_params_set(hl_params_t *p, const char *key, const char *value);

/**
 * Writes @p key's value in @p p as text that hl_params_set reads back to the same value
 * (the fewest decimals that do; degrees for angles) into @p buf of @p cap bytes
 * (truncated to fit, NUL-terminated when @p cap > 0; 32 bytes hold any value). A fixed
 * key's value is its fixed one.
 * @return HL_OK; HL_ERR_ARG for NULL or an unknown key (@p buf then empty).
 */
HL_API hl_status_t hl_params_get(const hl_params_t *p, const char *key, char *buf,
                                 size_t cap);

/**
 * The rules over several keys (a blur wider than ten cells, a search window larger than
 * the raster, a cull that needs another key, ...), after the keys are set.
 * @return HL_OK, or HL_ERR_RANGE with hl_params_error(@p p) naming every key involved
 *         with its value ("localize.blur_sigma_mm (300) must be at most 10 x
 *         localize.cell_mm (24)"); HL_ERR_ARG for NULL.
 */
HL_API hl_status_t hl_params_check(hl_params_t *p);

/** The line saying why the last hl_params_set or hl_params_check on @p p failed; NULL
 *  when it succeeded (or none ran since hl_params_default). Valid until the next call on
 *  @p p. */
HL_API const char *hl_params_error(const hl_params_t *p);

/** The table's key @p i (0, 1, ... in the order houghlocd prints them; the fixed keys
 *  last), or NULL past the last: `for (i = 0; (k = hl_params_info(i)); i++)`. */
HL_API const hl_param_info_t *hl_params_info(size_t i);

/** Profile @p i (sonar-stops first, the default), or NULL past the last. */
HL_API const hl_param_preset_t *hl_params_preset(size_t i);

/* The forms hl_params_set reads, for a program's own settings to read alike
 * (houghlocd's keys). */

/** @p s as a finite number (blanks after it allowed). @return false, *out unchanged,
 *  for anything else. */
static inline bool hl_params_parse_number(const char *s, double *out)
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

/** true, yes, on, 1 / false, no, off, 0. @return false, *out unchanged, for anything
 *  else. */
static inline bool hl_params_parse_bool(const char *s, bool *out)
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

#ifdef __cplusplus
}
#endif
#endif
