/* config_keys.h - the table of configuration keys (private to the config*.c modules). */
#ifndef HOUGHLOC_DAEMON_CONFIG_KEYS_H
#define HOUGHLOC_DAEMON_CONFIG_KEYS_H

#include <stdbool.h>
#include <stddef.h>

enum hl_key_type {
    HL_KEY_STR,         /* char[size] */
    HL_KEY_I32,         /* int32_t (also hl_mm_t) */
    HL_KEY_U16,
    HL_KEY_U32,
    HL_KEY_U64,
    HL_KEY_DOUBLE,
    HL_KEY_BOOL,
    HL_KEY_DEG,         /* hl_bam_t, written in degrees */
    HL_KEY_METRES,      /* hl_mm_t, written in metres */
    HL_KEY_Q8,          /* uint16_t x 256, written as a plain number */
    HL_KEY_LEVEL,       /* log level name */
    HL_KEY_MODE,        /* slam.mode preset */
    HL_KEY_SENSOR_PROFILE, /* slam.profile preset: a sensor profile name (profiles.h) */
    HL_KEY_FENCE_RECT,
    HL_KEY_FENCE_POLYGON,
    HL_KEY_LINK,        /* char[size]: "" or a robot link (link.h) */
    HL_KEY_ROBOT_PROFILE, /* robot.profile preset: a robot profile name (sounder.h) */
};

typedef struct hl_config_key {
    const char *name;   /* "section.key" */
    enum hl_key_type type;
    size_t offset;      /* into hl_config_t */
    size_t size;        /* HL_KEY_STR: the array's size */
    double min, max;    /* numeric types, in the written unit */
    const char *help;   /* one line */
} hl_config_key_t;

extern const hl_config_key_t hl_config_keys[];
extern const size_t hl_config_nkeys;

/** An operator's key: printed by --print-config and in packaging/houghlocd.conf; the
 *  others are research knobs, printed there only when set away from their default. */
bool hl_config_key_for_operator(const hl_config_key_t *k);

/** A preset key (slam.mode, slam.profile, robot.profile): read before every other key. */
bool hl_config_key_is_preset(const hl_config_key_t *k);

/** The key named @p name ("section.key"), or NULL. */
const hl_config_key_t *hl_config_key_find(const char *name);

/* hl_config_t is declared in config.h, which includes this file's users. */
struct hl_config;

/* Room for any key's value as the file writes it (the longest: the fence's text). */
#define HL_CONFIG_VALUE_LEN 1100

/** Writes @p k's value in @p c as the file writes it (config_print.c), so that a message
 *  quotes a value in the unit the operator typed (degrees, metres), not the field's. */
void hl_config_format_value(const struct hl_config *c, const hl_config_key_t *k, char *buf,
                            size_t cap);

/** Applies @p c's presets, in order: slam.mode's parameters afresh, slam.profile's keys
 *  over them, robot.profile's calibration. @return false with "config: ..." in @p why
 *  (HL_CONFIG_WHY_LEN bytes) when a profile names a key the table cannot set. */
bool hl_config_apply_presets(struct hl_config *c, char *why);

#endif
