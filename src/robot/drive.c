/* drive.c - legs of turn, drive, sound and localize towards a destination (drive.h). */
#include "houghloc/drive.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A motion is over once the base has moved and stopped again, or has stayed still this
 * long after the command (a turn already within a degree never starts). */
#define NO_START_MS 1000

void hl_drive_params_default(hl_drive_params_t *p)
{
    p->arrive_mm = 150;
    p->max_leg_mm = 1500;
    p->max_legs = 12;
    p->speed_mm_s = 300;
    p->turn_deg_s = 45;
    p->slack_ms = 5000;
}

const char *hl_drive_params_error(const hl_drive_params_t *p)
{
    if (!p)
        return "no drive parameters";
    if (p->arrive_mm < 10 || p->arrive_mm > 5000)
        return "drive arrive distance must be 10..5000 mm";
    if (p->max_leg_mm < p->arrive_mm || p->max_leg_mm > 30000)
        return "drive leg length must be from the arrive distance to 30000 mm";
    if (p->max_legs < 1 || p->max_legs > 1000)
        return "drive legs must be 1..1000";
    if (p->speed_mm_s < 10 || p->speed_mm_s > 5000)
        return "drive speed must be 10..5000 mm/s";
    if (p->turn_deg_s < 1 || p->turn_deg_s > 720)
        return "drive turn rate must be 1..720 deg/s";
    if (p->slack_ms < 0 || p->slack_ms > 600000)
        return "drive slack must be 0..600000 ms";
    return NULL;
}

hl_status_t hl_drive_init(hl_drive_t *d, const hl_drive_params_t *p)
{
    if (!d || hl_drive_params_error(p))
        return HL_ERR_ARG;
    memset(d, 0, sizeof *d);
    d->p = *p;
    return HL_OK;
}

int32_t hl_drive_remaining(const hl_drive_t *d, hl_pose_t estimate)
{
    double dx = (double)d->goal_x - estimate.x_mm, dy = (double)d->goal_y - estimate.y_mm;
    return (int32_t)lround(sqrt(dx * dx + dy * dy));
}

void hl_drive_fail(hl_drive_t *d, const char *why)
{
    snprintf(d->why, sizeof d->why, "%s", why);
    d->phase = HL_DRIVE_FAILED;
}

static int32_t whole_degrees(hl_bam_t a)
{
    return (int32_t)(((int64_t)a * 360 + 32768) / 65536) % 360;
}

/* Commands a turn so that the estimate's heading becomes @p map_heading. */
static void turn_to(hl_drive_t *d, hl_drive_phase_t phase, hl_bam_t map_heading,
                    const hl_drive_in_t *in, hl_drive_out_t *out)
{
    int32_t turn = hl_bam_diff(map_heading, in->estimate.theta);
    d->aim = (hl_bam_t)(in->odometry.theta + turn);
    d->phase = phase;
    d->cmd_ms = in->robot_ms;
    d->deadline_ms = in->robot_ms + d->p.slack_ms +
                     (int64_t)abs(turn) * 360 * 1000 / 65536 / d->p.turn_deg_s;
    d->seen_moving = false;
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_HEAD, whole_degrees(d->aim) };
}

/* The next leg from the estimate: turn towards the goal (the drive follows the turn). */
static void next_leg(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    if (d->legs >= d->p.max_legs) {
        char why[96];
        snprintf(why, sizeof why, "still %.2f m from the destination after %d legs",
                 hl_drive_remaining(d, in->estimate) / 1000.0, d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0 };
        return;
    }
    d->legs++;
    double a = atan2((double)d->goal_y - in->estimate.y_mm, (double)d->goal_x - in->estimate.x_mm);
    turn_to(d, HL_DRIVE_TURN, hl_bam_from_rad(a), in, out);
}

void hl_drive_start(hl_drive_t *d, int32_t x_mm, int32_t y_mm, bool has_heading,
                    hl_bam_t heading, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    d->goal_x = x_mm;
    d->goal_y = y_mm;
    d->has_heading = has_heading;
    d->heading = heading;
    d->legs = 0;
    d->turned_final = d->last_turn = false;
    d->why[0] = '\0';
    hl_drive_localized(d, in, out);
}

/* Whether the estimate's heading is off the requested one by more than a degree. */
static bool heading_off(const hl_drive_t *d, const hl_drive_in_t *in)
{
    return d->has_heading && abs(hl_bam_diff(d->heading, in->estimate.theta)) > 182;
}

void hl_drive_localized(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_NONE, 0 };
    if (hl_drive_remaining(d, in->estimate) > d->p.arrive_mm) {
        d->turned_final = false;
        next_leg(d, in, out);
    } else if (heading_off(d, in)) {
        /* The first final turn is followed by a sounding; that sounding turns the body by
         * its steps, so a second turn without one restores the heading. */
        d->last_turn = d->turned_final;
        d->turned_final = true;
        turn_to(d, HL_DRIVE_FINAL_TURN, d->heading, in, out);
    } else {
        d->phase = HL_DRIVE_ARRIVED;
    }
}

/* Whether the commanded motion has ended: the base moved and is still again, or never
 * started. */
static bool motion_over(hl_drive_t *d, const hl_drive_in_t *in)
{
    if (in->moving) {
        d->seen_moving = true;
        return false;
    }
    return d->seen_moving || in->robot_ms - d->cmd_ms >= NO_START_MS;
}

static void start_move(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    int32_t left = hl_drive_remaining(d, in->estimate);
    d->leg_mm = left < d->p.max_leg_mm ? left : d->p.max_leg_mm;
    d->phase = HL_DRIVE_MOVE;
    d->cmd_ms = in->robot_ms;
    d->deadline_ms = in->robot_ms + d->p.slack_ms + (int64_t)d->leg_mm * 1000 / d->p.speed_mm_s;
    d->seen_moving = false;
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_MOVE, d->leg_mm };
}

void hl_drive_on_sip(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_NONE, 0 };
    if (d->phase != HL_DRIVE_TURN && d->phase != HL_DRIVE_MOVE && d->phase != HL_DRIVE_FINAL_TURN)
        return;
    static const char *const doing[] = { [HL_DRIVE_TURN] = "turning",
                                         [HL_DRIVE_MOVE] = "driving",
                                         [HL_DRIVE_FINAL_TURN] = "turning to the heading" };
    char why[96];
    if (in->stalled) {
        snprintf(why, sizeof why, "the base stalled while %s (leg %d)", doing[d->phase], d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0 };
        return;
    }
    if (in->robot_ms > d->deadline_ms) {
        snprintf(why, sizeof why, "timed out %s after %.1f s of robot time (leg %d)",
                 doing[d->phase], (in->robot_ms - d->cmd_ms) / 1000.0, d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0 };
        return;
    }
    if (!motion_over(d, in))
        return;
    if (d->phase == HL_DRIVE_TURN) {
        start_move(d, in, out);
    } else {
        /* a leg or a turn is over: localize before deciding anything more */
        bool done = d->phase == HL_DRIVE_FINAL_TURN && d->last_turn;
        d->phase = done ? HL_DRIVE_ARRIVED : HL_DRIVE_SOUND;
        if (!done)
            *out = (hl_drive_out_t){ HL_DRIVE_CMD_SOUND, 0 };
    }
}
