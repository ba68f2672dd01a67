/*
 * sounder.h - the paper's sounding procedure on a live robot: stop, then turn the body
 * in small steps, taking a fresh reading from every transducer at each step, until the
 * ring of transducers has swept the gaps between them (16 transducers x 8 steps of
 * 2.8125 degrees = 128 readings 2.8 degrees apart).
 *
 * The sounder is pure: it is fed the robot's information packets one at a time, already
 * decoded (hl_sounder_sip_t), and answers with the motion command to send, if any. Time
 * is robot time, counted by the caller from the robot's own packets (ARCOS sends one
 * every 100 ms), so a simulated robot running faster than real time scales every wait.
 *
 * The bearings come from the measured rotation, not the commanded one: a reading taken
 * at step k lies at the transducer's bearing plus the heading change from step k to the
 * last step, whose odometry pose is the scan's. The robot's heading command takes whole
 * degrees, so each step aims at the nearest whole degree of the ideal heading and the
 * small difference is absorbed by measuring.
 */
#ifndef HOUGHLOC_SOUNDER_H
#define HOUGHLOC_SOUNDER_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/calib.h"
#include "houghloc/scan.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_ROBOT_MAX_TRANSDUCERS 32
#define HL_SOUNDER_MAX_STEPS 32

/** A robot: where its sonar transducers point (robot frame, counter-clockwise from
 *  ahead) and how its raw ranges read in millimetres. */
typedef struct hl_robot_profile {
    char name[16];
    int32_t transducers;                        /* 1..HL_ROBOT_MAX_TRANSDUCERS */
    hl_bam_t bearing[HL_ROBOT_MAX_TRANSDUCERS]; /* transducer k's axis */
    hl_calib_t calib;                           /* its sonar calibration (the daemon's
                                                   calibration.* keys override it) */
} hl_robot_profile_t;

/* The built-in profiles' names, for messages. */
#define HL_ROBOT_PROFILE_NAMES "bonnie, pioneer3 or houghloc-sim"

/**
 * The built-in profiles: "bonnie" (the paper's robot: 16 transducers 22.5 degrees apart,
 * transducer 0 ahead), "pioneer3" (a Pioneer 3's front and rear rings), both with the
 * default calibration (raw values taken as millimetres), and "houghloc-sim" (the simulated
 * robot: bonnie's ring, with the calibration hl-calibrate measures for its simulated
 * transducers).
 * @return HL_OK, or HL_ERR_ARG for NULL or an unknown name.
 */
hl_status_t hl_robot_profile_find(const char *name, hl_robot_profile_t *out);

typedef struct hl_sounder_params {
    int32_t steps;          /* body positions per sounding, 1..32 (default 8) */
    hl_bam_t step;          /* turn between positions (default 2.8125 deg) */
    int32_t settle_ms;      /* robot time the base must report still before readings
                               count (default 300) */
    int32_t step_timeout_ms;/* robot time allowed for one position: turning, settling and
                               a fresh reading from every transducer (default 8000) */
    hl_calib_t calib;       /* raw range -> mm, and the validity filter */
} hl_sounder_params_t;

void hl_sounder_params_default(hl_sounder_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_sounder_params_error(const hl_sounder_params_t *p);

/** One robot information packet, as the sounder needs it. */
typedef struct hl_sounder_sip {
    int64_t robot_ms;       /* robot time of this packet */
    hl_pose_t odometry;     /* the robot's own odometry (its frame) */
    bool moving;            /* the base reports motion */
    int32_t readings;       /* sonar readings in this packet, 0..HL_ROBOT_MAX_TRANSDUCERS */
    uint8_t transducer[HL_ROBOT_MAX_TRANSDUCERS];
    uint16_t raw[HL_ROBOT_MAX_TRANSDUCERS];
} hl_sounder_sip_t;

/** What the robot should do after a packet. */
typedef enum hl_sounder_cmd {
    HL_SOUNDER_CMD_NONE = 0,
    HL_SOUNDER_CMD_STOP,        /* stop the base */
    HL_SOUNDER_CMD_HEAD,        /* turn to the absolute heading head_deg (robot's frame) */
} hl_sounder_cmd_t;

typedef enum hl_sounder_state {
    HL_SOUNDER_IDLE = 0,
    HL_SOUNDER_BUSY,
    HL_SOUNDER_DONE,            /* a scan is ready: hl_sounder_scan */
    HL_SOUNDER_FAILED,          /* gave up: hl_sounder_why */
} hl_sounder_state_t;

typedef struct hl_sounder {
    hl_sounder_params_t p;
    hl_robot_profile_t profile;
    hl_sounder_state_t state;
    int32_t step;               /* current body position, 0..steps-1 */
    bool turning;               /* a HEAD command of this step is under way */
    int64_t step_start_ms, still_since_ms;
    bool still;
    bool at_rest;               /* settled at this position, its heading recorded */
    hl_bam_t start_heading;     /* at step 0 */
    hl_bam_t step_heading[HL_SOUNDER_MAX_STEPS];
    bool have[HL_SOUNDER_MAX_STEPS][HL_ROBOT_MAX_TRANSDUCERS];
    uint16_t raw[HL_SOUNDER_MAX_STEPS][HL_ROBOT_MAX_TRANSDUCERS];
    int32_t missing;            /* transducers without a fresh reading at this step */
    hl_pose_t odometry;         /* the last step's pose: the scan's */
    int64_t done_ms;
    char why[128];
} hl_sounder_t;

/** @return HL_OK, or HL_ERR_ARG for NULL or invalid parameters. */
hl_status_t hl_sounder_init(hl_sounder_t *s, const hl_sounder_params_t *p,
                            const hl_robot_profile_t *profile);

/** Starts a sounding; the first packet after it stops the base. */
void hl_sounder_start(hl_sounder_t *s);

/** Gives up the sounding in progress (the link went down, say): state IDLE. */
void hl_sounder_cancel(hl_sounder_t *s);

/**
 * Feeds one packet. Readings count only while the base has been still for settle_ms at
 * the current position. @p head_deg receives the heading, 0..359 whole degrees, when the
 * command is HL_SOUNDER_CMD_HEAD.
 */
hl_sounder_cmd_t hl_sounder_on_sip(hl_sounder_t *s, const hl_sounder_sip_t *sip,
                                   int32_t *head_deg);

static inline hl_sounder_state_t hl_sounder_state(const hl_sounder_t *s) { return s->state; }
/** Why the last sounding failed (one line), "" otherwise. */
static inline const char *hl_sounder_why(const hl_sounder_t *s) { return s->why; }

/**
 * The finished scan: every reading of every position in bearing order, ranges through
 * the calibration (invalid where it says so), and the odometry pose of the last position.
 * @return HL_OK; HL_ERR_EMPTY unless the state is HL_SOUNDER_DONE; HL_ERR_ARG for NULL.
 * The sounder returns to IDLE.
 */
hl_status_t hl_sounder_take(hl_sounder_t *s, hl_scan_t *scan, hl_pose_t *odometry);

#ifdef __cplusplus
}
#endif
#endif
