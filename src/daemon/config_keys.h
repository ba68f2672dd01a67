/* config_keys.h - the table of the daemon's own configuration keys (private to the
 * config*.c modules); the tracker's keys are the core's (houghloc/params.h). */
#ifndef HOUGHLOC_DAEMON_CONFIG_KEYS_H
#define HOUGHLOC_DAEMON_CONFIG_KEYS_H

#include <stdbool.h>
#include <stddef.h>

#include "houghloc/params.h"

enum hl_key_type {
    HL_KEY_STR,         /* char[size] */
    HL_KEY_I32,         /* int32_t (also hl_mm_t) */
    HL_KEY_U16,
    HL_KEY_BOOL,
    HL_KEY_DEG,         /* hl_bam_t, written in degrees */
    HL_KEY_METRES,      /* hl_mm_t, written in metres */
    HL_KEY_LEVEL,       /* log level name */
    HL_KEY_FENCE_RECT,
    HL_KEY_FENCE_POLYGON,
    HL_KEY_LINK,        /* char[size]: "" or a robot link (link.h) */
    HL_KEY_ROBOT_PROFILE, /* robot.profile preset: a robot profile name (sounder.h) */
    HL_KEY_CORE,        /* where the core's keys go among the daemon's (printing) */
};

typedef struct hl_config_key {
    const char *name;   /* "section.key" */
    enum hl_key_type type;
    size_t offset;      /* into hl_config_t */
    size_t size;        /* HL_KEY_STR: the array's size */
    double min, max;    /* numeric types, in the written unit */
    const char *help;   /* one line; NULL: no longer a key (config_keys.c, RETIRED) */
} hl_config_key_t;

extern const hl_config_key_t hl_config_keys[];
extern const size_t hl_config_nkeys;

/** An operator's key: printed by --print-config and in packaging/houghlocd.conf; the
 *  others are research knobs, printed there only when set away from their default. */
bool hl_config_key_for_operator(const hl_config_key_t *k);

/** The daemon's key named @p name ("section.key"), or NULL (also for the core's keys). */
const hl_config_key_t *hl_config_key_find(const char *name);

/* hl_config_t is declared in config.h, which includes this file's users. */
struct hl_config;

/* Room for any key's value as the file writes it (the longest: the fence's text). */
#define HL_CONFIG_VALUE_LEN 1100

/** Writes the value of @p name (a daemon key or the core's) in @p c as the file writes it
 *  (config_print.c), so that a message quotes a value in the unit the operator typed
 *  (degrees, metres), not the field's. */
void hl_config_format_value(const struct hl_config *c, const char *name, char *buf,
                            size_t cap);

/** Applies @p c's robot.profile: its calibration (calibration.*, before the file's). */
void hl_config_apply_robot_profile(struct hl_config *c);

/** The core's key @p name if houghlocd takes it (an operator's or expert key), else NULL. */
const hl_param_info_t *hl_config_core_key(const char *name);

#endif
