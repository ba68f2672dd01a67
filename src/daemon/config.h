/*
 * config.h - houghlocd's configuration: compiled-in defaults, an INI file (libinih),
 * command-line overrides, validation with the file, line, key and reason.
 *
 * Every key is "section.key" (the INI section and the key in it). The daemon's own keys
 * (the bus, the map and key files, the start pose, the fence, the robot link, sounding
 * and drive) are config_keys.c's, with their types, ranges and one-line descriptions;
 * the tracker's sections ([slam], [localize], [echo], [normals], [reloc]) go to the
 * core's table unchanged (houghloc/params.h: hl_params_set), which owns their types,
 * ranges, defaults and help. packaging/houghlocd.conf is the commented default file of
 * the operator's keys (hl_config_print_operator).
 *
 * Two keys are presets, applied before every other key wherever they are written, so
 * that single keys can adjust them: slam.profile (the sensor, or the paper's method: the
 * core's presets) and robot.profile (the robot, sounder.h: its transducers and its
 * calibration under the calibration.* keys).
 *
 * A key that is no longer a setting (the table's fixed keys, and the daemon's retired
 * ones below) is read with a warning when it names its fixed value, and refused with
 * that value named otherwise; daemon.lost_after and daemon.search_every are read as
 * slam.lost_after and slam.search_every, with a warning.
 */
#ifndef HOUGHLOC_DAEMON_CONFIG_H
#define HOUGHLOC_DAEMON_CONFIG_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "houghloc/bus.h"
#include "houghloc/drive.h"
#include "fence.h"
#include "houghloc/params.h"
#include "houghloc/rlink.h"
#include "houghloc/sounder.h"
#include "profiles.h"

#define HL_CONFIG_DEFAULT_PATH "/etc/houghloc/houghlocd.conf"
#define HL_CONFIG_PATH_MAX 512
#define HL_CONFIG_URL_MAX 512
#define HL_CONFIG_WHY_LEN 640
#define HL_CONFIG_MAX_OVERRIDES 64
/* Warnings of one load (a retired key, a renamed one): at most this many lines kept. */
#define HL_CONFIG_MAX_NOTES 8
#define HL_CONFIG_NOTE_LEN 400

typedef struct hl_config {
    /* [lcm] */
    char lcm_url[HL_CONFIG_URL_MAX];    /* "" = $LCM_DEFAULT_URL, else host-only udpm */
    char lcm_out[HL_CONFIG_URL_MAX];    /* "" = the input URL (or, for a log replay, the
                                           live default) */
    char prefix[HL_BUS_PREFIX_MAX + 1];
    int32_t queue;                      /* liblcm queue per subscription, messages */
    /* [daemon] */
    char map_file[HL_CONFIG_PATH_MAX];  /* "" = the default location (map_location.h) */
    int32_t save_every;                 /* save after this many integrations; 0 = only
                                           on exit and on SAVE */
    int32_t map_period_ms;              /* MAP at most this often, in message time (not a
                                           key: HL_CONFIG_MAP_PERIOD_MS) */
    int32_t map_input_ratio;            /* MAP bytes per byte of SONAR and ODOMETRY taken
                                           (cycle_map.c); 0 = no bound in bytes */
    int32_t status_period_ms;           /* STATUS this often, wall clock */
    int32_t idle_after_ms;              /* no SONAR this long (wall clock): state IDLE (not
                                           a key: HL_CONFIG_IDLE_AFTER_MS) */
    int32_t compute_window;             /* scans in STATUS's compute median and p99 */
    int32_t log_level;                  /* HL_LOG_* */
    /* [auth] */
    char key_file[HL_CONFIG_PATH_MAX];  /* "" = requests are not authenticated */
    char state_file[HL_CONFIG_PATH_MAX];    /* the request state file; "" = requests.seq
                                               in the map file's folder (seqfile.h) */
    int32_t max_ahead_s;                /* request seqs further ahead of the clock are
                                           refused */
    /* [start] */
    hl_pose_t start;                    /* where the first scan is placed */
    /* [fence] */
    hl_fence_t fence;
    char fence_text[1024];              /* as given, for --print-config */
    /* [slam], [localize], [echo], [normals], [reloc]: the core's (params.h) */
    hl_params_t params;
    /* [robot], [calibration], [drive], [link]: the live robot (robot.h) */
    char robot_link[272];               /* "" = none: SONAR and ODOMETRY come over LCM */
    char robot_profile[16];             /* a robot profile (sounder.h) */
    bool robot_sound_on_connect;
    int32_t robot_lost_soundings;       /* not a key: HL_CONFIG_LOST_SOUNDINGS */
    int32_t robot_reconnect_max_ms;     /* not a key: HL_CONFIG_RECONNECT_MAX_MS */
    int32_t robot_radius_mm;        /* the body (planning, the safety stop) */
    bool robot_lockstep;            /* houghloc-sim --lockstep's clock (robot.h) */
    hl_sounder_params_t sounder;        /* with the calibration */
    hl_drive_params_t drive;
    hl_rlink_params_t rlink;
    /* What the last load warned about (main.c logs them): */
    int n_notes;
    char notes[HL_CONFIG_MAX_NOTES][HL_CONFIG_NOTE_LEN];
} hl_config_t;

/* Values that were keys once and are fixed now: nothing set them (no profile, study or
 * documented need), and the measurements behind them stand (docs/design/expert-keys.md). */
#define HL_CONFIG_MAP_PERIOD_MS 1000    /* MAP at most once a second of message time: the
                                           console redraws no faster; map_input_ratio
                                           bounds the bytes */
#define HL_CONFIG_IDLE_AFTER_MS 5000    /* no SONAR for 5 s: IDLE (a sounding at stops
                                           takes 2-3 s) */
#define HL_CONFIG_RECONNECT_MAX_MS 5000 /* a lost robot link retried after 0.25 s,
                                           doubling up to 5 s */
#define HL_CONFIG_LOST_SOUNDINGS 3      /* soundings standing still while LOST: the global
                                           search takes 3 scans together (reloc.scans) */

/** The map capacity @p c's slam.map_capacity gives. */
uint32_t hl_config_map_capacity(const hl_config_t *c);

/** The compiled-in defaults (sensor profile sonar-stops, robot profile bonnie, host-only
 *  LCM, a 20 m square fence). */
void hl_config_defaults(hl_config_t *c);

/**
 * Builds the effective configuration: defaults, the presets named by slam.profile and
 * robot.profile (in the file or the overrides, the overrides winning),
 * the file's other keys, then @p overrides ("section.key=value", in order).
 * @param path      the INI file (a regular file of at most 1 MiB holding no NUL byte, or
 *                  /dev/null: config_file.h); NULL for none.
 * @param optional  a missing file is not an error (the default path).
 * @return true, or false with one line in @p why ("FILE: reason" for the file itself,
 *         "FILE:LINE: key 'x.y': reason" for its lines, "--set x.y=v: reason" for an
 *         override, "config: x.y (v) must ... z.w (u)" for a combination of values,
 *         naming each key with its value: config_check.h). A load that succeeds leaves
 *         its warnings (a key no longer a setting, at its fixed value; a renamed key) in
 *         @p c->notes, for the caller to log.
 */
bool hl_config_load(hl_config_t *c, const char *path, bool optional,
                    const char *const *overrides, int n_overrides, char *why);

/** Writes the effective configuration, every key with its comment, as an INI file that
 *  hl_config_load reads back (--print-config=all). */
void hl_config_print(const hl_config_t *c, FILE *out);

/** Writes the operator's keys, and any other key whose value differs from what the
 *  presets give it, as an INI file that hl_config_load reads back to the same
 *  configuration (--print-config; packaging/houghlocd.conf is it for the defaults). */
void hl_config_print_operator(const hl_config_t *c, FILE *out);

#endif
