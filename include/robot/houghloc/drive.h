/*
 * drive.h - taking the robot to a destination the way the paper's robot moved: turn
 * towards the next point of the way, drive straight, stop, sound, localize; repeat until
 * the localized estimate is within reach of the goal; then turn to the final heading if
 * one was given.
 *
 * The way is the caller's: before each leg it may set a via point (the planner's next
 * corner, plan.h), and the leg aims there instead of at the goal. Legs are at most
 * max_leg_mm long, so the robot localizes at least that often and odometry drift stays
 * short. Motion is commanded in the robot's own odometry frame (an absolute heading, a
 * speed, then a distance), aimed from the localized estimate in the map frame. Every
 * motion has a timeout in robot time (its expected duration plus slack) and stops at once
 * when the base reports a stall.
 *
 * The safety stop: while a leg is driven, the caller reports the nearest sonar reading in
 * the way ahead (hl_drive_in_t.ahead_mm, safety.h). Within slow_mm the speed falls with
 * the distance; within stop_mm the robot stops, sounds and localizes, and the caller plans
 * again round the obstacle (hl_drive_blocked says where the leg was stopped). A destination
 * blocked more than HL_DRIVE_MAX_BLOCKS times fails, its reason naming how far the
 * obstacle was.
 *
 * Pure: the caller feeds the robot's packets and the localization results and sends the
 * commands it answers with (hl_drive_out_t). The sounding itself is the caller's
 * (sounder.h): this module asks for one and is told its outcome.
 */
#ifndef HOUGHLOC_DRIVE_H
#define HOUGHLOC_DRIVE_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/scan.h"
#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_drive_params {
    int32_t arrive_mm;          /* arrived when the estimate is this close (default 150) */
    int32_t max_leg_mm;         /* longest drive between soundings (default 1500) */
    int32_t max_legs;           /* legs before giving up (default 20) */
    int32_t speed_mm_s;         /* the base's driving speed, for timeouts (default 300) */
    int32_t turn_deg_s;         /* its turning speed, for timeouts (default 45) */
    int32_t slack_ms;           /* added to every motion's expected time (default 5000) */
    int32_t stop_mm;            /* a reading ahead this close stops a leg (default 350) */
    int32_t slow_mm;            /* ... and this close slows it (default 800; 0: never) */
} hl_drive_params_t;

/* Safety stops a destination may take before it fails: each one plans round what the
 * sonar heard, and a way blocked again and again is not there. */
#define HL_DRIVE_MAX_BLOCKS 4

void hl_drive_params_default(hl_drive_params_t *p);
/** A one-line description of what is wrong with @p p, or NULL if nothing. */
const char *hl_drive_params_error(const hl_drive_params_t *p);

typedef enum hl_drive_phase {
    HL_DRIVE_IDLE = 0,
    HL_DRIVE_TURN,              /* turning towards the goal */
    HL_DRIVE_MOVE,              /* driving a leg */
    HL_DRIVE_SOUND,             /* waiting for a sounding and its localization */
    HL_DRIVE_FINAL_TURN,        /* turning to the requested heading */
    HL_DRIVE_ARRIVED,
    HL_DRIVE_FAILED,            /* hl_drive_why says why */
} hl_drive_phase_t;

/** What the robot reports, as the drive needs it. */
typedef struct hl_drive_in {
    int64_t robot_ms;
    hl_pose_t estimate;         /* localized pose moved by odometry: the map frame */
    hl_pose_t odometry;         /* the robot's own odometry */
    bool moving;
    bool stalled;
    int32_t ahead_mm;           /* the nearest reading in the way ahead, mm; 0 for none
                                   (safety.h); read only while a leg is driven */
} hl_drive_in_t;

typedef enum hl_drive_cmd {
    HL_DRIVE_CMD_NONE = 0,
    HL_DRIVE_CMD_STOP,
    HL_DRIVE_CMD_HEAD,          /* turn to absolute heading arg (whole degrees, 0..359) */
    HL_DRIVE_CMD_MOVE,          /* drive arg mm straight ahead */
    HL_DRIVE_CMD_SOUND,         /* sound and localize, then call hl_drive_localized */
} hl_drive_cmd_t;

typedef struct hl_drive_out {
    hl_drive_cmd_t cmd;
    int32_t arg;
    int32_t speed_mm_s;         /* > 0: set the base's top speed to this first (SETV) */
} hl_drive_out_t;

typedef struct hl_drive {
    hl_drive_params_t p;
    hl_drive_phase_t phase;
    int32_t goal_x, goal_y;
    bool has_heading;
    hl_bam_t heading;
    int32_t legs;
    int64_t cmd_ms, deadline_ms;
    bool seen_moving;           /* the base has reported motion since the command */
    bool turned_final;          /* the final heading was commanded once (then sounded) */
    bool last_turn;             /* this final turn ends the destination */
    hl_bam_t aim;               /* odometry heading commanded (TURN, FINAL_TURN) */
    int32_t leg_mm;             /* distance commanded (MOVE) */
    bool has_via;               /* the next leg aims at (via_x, via_y), not the goal */
    int32_t via_x, via_y;
    int32_t speed_mm_s;         /* the speed commanded for this leg */
    int32_t blocks;             /* safety stops on this destination */
    int32_t blocked_mm;         /* the leg under way was stopped by a reading this far;
                                   -1 when it was not */
    int32_t last_block_mm;      /* the last safety stop's reading, for the reason */
    int32_t block_x, block_y;   /* ... and where it lies ahead, map frame, mm */
    char why[96];
} hl_drive_t;

/** @return HL_OK, or HL_ERR_ARG for NULL or invalid parameters. */
hl_status_t hl_drive_init(hl_drive_t *d, const hl_drive_params_t *p);

/** Starts towards (x, y), map frame, mm; with a final heading when @p has_heading.
 *  @p out says what to do first. */
void hl_drive_start(hl_drive_t *d, int32_t x_mm, int32_t y_mm, bool has_heading,
                    hl_bam_t heading, const hl_drive_in_t *in, hl_drive_out_t *out);

/** One robot packet while turning or driving. */
void hl_drive_on_sip(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out);

/** The sounding asked for is localized: @p in->estimate is the new estimate. */
void hl_drive_localized(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out);

/** The next leg (from hl_drive_start or hl_drive_localized) aims at (x, y), map frame, mm,
 *  instead of at the goal; cleared once that leg is commanded. */
void hl_drive_set_via(hl_drive_t *d, int32_t x_mm, int32_t y_mm);

/** Whether the last leg was stopped by the safety stop, with the reading's distance. */
static inline bool hl_drive_blocked(const hl_drive_t *d, int32_t *ahead_mm)
{
    if (ahead_mm)
        *ahead_mm = d->blocked_mm;
    return d->blocked_mm >= 0;
}

/** Gives up with @p why (the sounding failed, the link went down, a new destination). */
void hl_drive_fail(hl_drive_t *d, const char *why);

static inline hl_drive_phase_t hl_drive_phase(const hl_drive_t *d) { return d->phase; }
static inline const char *hl_drive_why(const hl_drive_t *d) { return d->why; }
/** Distance from @p estimate to the goal, mm. */
int32_t hl_drive_remaining(const hl_drive_t *d, hl_pose_t estimate);

#ifdef __cplusplus
}
#endif
#endif
