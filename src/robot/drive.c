/* drive.c - legs of turn, drive, sound and localize towards a destination (drive.h). */
#include "houghloc/drive.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A motion is over once the base has moved and stopped again, or has stayed still this
 * long after the command (a turn already within a degree never starts). */
#define NO_START_MS 1000

/* The slowest a leg is driven near an obstacle: a quarter of the speed (at least
 * MIN_SPEED_MM_S, which a base still drives smoothly). At 75 mm/s a Pioneer-like base
 * (300 mm/s^2) brakes in about 10 mm, and the robot crawls less than 40 mm between two
 * readings of the ring's front transducers. */
#define SLOW_SHARE 4
#define MIN_SPEED_MM_S 50

void hl_drive_params_default(hl_drive_params_t *p)
{
    p->arrive_mm = 150;
    p->max_leg_mm = 1500;
    p->max_legs = 20;       /* a way round furniture takes several legs; 20 x 1.5 m crosses
                               any building the map holds (fixed for houghlocd) */
    p->speed_mm_s = 300;
    p->turn_deg_s = 45;
    p->slack_ms = 5000;     /* a motion's timeout past its expected duration: a base that
                               stalls for 5 s has stopped (fixed for houghlocd) */
    /* The robot's radius (250 mm for houghloc-sim and a Pioneer 3) and 100 mm more: what
     * the robot crawls (at most 40 mm at the slow speed) between two readings of its front
     * transducers, what it takes to brake from there (about 10 mm) and the calibration's
     * error, with room to spare. */
    p->stop_mm = 350;
    /* Braking from 300 mm/s takes 150 mm, and the front readings come every half second
     * or so (150 mm at full speed): the slowing starts well before the stop. */
    p->slow_mm = 800;
}

const char *hl_drive_params_error(const hl_drive_params_t *p)
{
    if (!p)
        return "no drive parameters";
    if (p->arrive_mm < 10 || p->arrive_mm > 5000)
        return "drive arrive distance must be 10..5000 mm";
    if (p->max_leg_mm < p->arrive_mm || p->max_leg_mm > 30000)
        return "drive.max_leg_mm must be from drive.arrive_mm to 30000 mm";
    if (p->max_legs < 1 || p->max_legs > 1000)
        return "drive legs must be 1..1000";
    if (p->speed_mm_s < 10 || p->speed_mm_s > 5000)
        return "drive speed must be 10..5000 mm/s";
    if (p->turn_deg_s < 1 || p->turn_deg_s > 720)
        return "drive turn rate must be 1..720 deg/s";
    if (p->slack_ms < 0 || p->slack_ms > 600000)
        return "drive slack must be 0..600000 ms";
    if (p->stop_mm < 0 || p->stop_mm > 5000)
        return "drive.stop_mm must be 0..5000 mm";
    if (p->slow_mm != 0 && (p->slow_mm <= p->stop_mm || p->slow_mm > 10000))
        return "drive.slow_mm must be 0 (off) or from above drive.stop_mm to 10000 mm";
    return NULL;
}

hl_status_t hl_drive_init(hl_drive_t *d, const hl_drive_params_t *p)
{
    if (!d || hl_drive_params_error(p))
        return HL_ERR_ARG;
    memset(d, 0, sizeof *d);
    d->p = *p;
    d->blocked_mm = -1;
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
    d->has_via = false;
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
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_HEAD, whole_degrees(d->aim), 0 };
}

/* Where the next leg aims: the via point when one is set, else the goal. */
static void aim_point(const hl_drive_t *d, int32_t *x, int32_t *y)
{
    *x = d->has_via ? d->via_x : d->goal_x;
    *y = d->has_via ? d->via_y : d->goal_y;
}

static int32_t distance_to(hl_pose_t from, int32_t x, int32_t y)
{
    return (int32_t)lround(hypot((double)x - from.x_mm, (double)y - from.y_mm));
}

void hl_drive_set_via(hl_drive_t *d, int32_t x_mm, int32_t y_mm)
{
    d->has_via = true;
    d->via_x = x_mm;
    d->via_y = y_mm;
}

/* The next leg from the estimate: turn towards the aim (the drive follows the turn). */
static void next_leg(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    if (d->legs >= d->p.max_legs) {
        char why[96];
        snprintf(why, sizeof why, "still %.2f m from the destination after %d legs",
                 hl_drive_remaining(d, in->estimate) / 1000.0, d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0, 0 };
        return;
    }
    if (d->blocks > HL_DRIVE_MAX_BLOCKS) {
        char why[96];
        snprintf(why, sizeof why, "blocked: an obstacle %.2f m ahead (stopped %d times)",
                 d->last_block_mm / 1000.0, d->blocks);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0, 0 };
        return;
    }
    d->legs++;
    int32_t x, y;
    aim_point(d, &x, &y);
    double a = atan2((double)y - in->estimate.y_mm, (double)x - in->estimate.x_mm);
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
    d->blocks = 0;
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
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_NONE, 0, 0 };
    d->blocked_mm = -1;
    if (hl_drive_remaining(d, in->estimate) > d->p.arrive_mm) {
        d->turned_final = false;
        next_leg(d, in, out);
        return;
    }
    d->has_via = false;     /* within reach: no more legs */
    if (heading_off(d, in)) {
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

static int32_t slow_speed(const hl_drive_t *d)
{
    int32_t v = d->p.speed_mm_s / SLOW_SHARE;
    return v < MIN_SPEED_MM_S ? (d->p.speed_mm_s < MIN_SPEED_MM_S ? d->p.speed_mm_s
                                                                  : MIN_SPEED_MM_S) : v;
}

/* Whether the leg about to start from @p at towards (x, y) heads into what stopped the
 * last one: within stop_mm and 30 degrees of the way. Driving it would creep closer at
 * each try, before the first reading stops it again. */
static bool heads_into_block(const hl_drive_t *d, hl_pose_t at, int32_t x, int32_t y)
{
    if (d->blocks == 0)
        return false;
    int32_t dist = distance_to(at, d->block_x, d->block_y);
    if (dist > d->p.stop_mm)
        return false;
    double leg = atan2((double)y - at.y_mm, (double)x - at.x_mm);
    double to = atan2((double)d->block_y - at.y_mm, (double)d->block_x - at.x_mm);
    const double turn = 6.283185307179586;
    return fabs(remainder(leg - to, turn)) < turn / 12.0;     /* 30 degrees */
}

static void start_move(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    int32_t x, y;
    aim_point(d, &x, &y);
    if (heads_into_block(d, in->estimate, x, y)) {
        /* blocked again without moving: sound, and let the caller plan again */
        d->blocked_mm = d->last_block_mm = distance_to(in->estimate, d->block_x, d->block_y);
        d->blocks++;
        d->has_via = false;
        d->phase = HL_DRIVE_SOUND;
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_SOUND, 0, 0 };
        return;
    }
    int32_t left = distance_to(in->estimate, x, y);
    d->has_via = false;
    d->leg_mm = left < d->p.max_leg_mm ? left : d->p.max_leg_mm;
    d->phase = HL_DRIVE_MOVE;
    d->cmd_ms = in->robot_ms;
    /* the whole leg may be driven at the slow speed, near walls */
    d->deadline_ms = in->robot_ms + d->p.slack_ms + (int64_t)d->leg_mm * 1000 / slow_speed(d);
    d->seen_moving = false;
    d->speed_mm_s = d->p.speed_mm_s;
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_MOVE, d->leg_mm, d->speed_mm_s };
}

/* The safety stop and the slowing before it, on each packet of a leg. @return true when
 * the leg is stopped (out says STOP). */
static bool watch_ahead(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    if (in->ahead_mm <= 0 || d->blocked_mm >= 0)
        return false;
    if (in->ahead_mm <= d->p.stop_mm) {
        d->blocked_mm = d->last_block_mm = in->ahead_mm;
        d->blocks++;
        /* where it lies, roughly: ahead of the estimate along the leg */
        double th = hl_bam_to_rad(in->estimate.theta);
        d->block_x = in->estimate.x_mm + (int32_t)lround(in->ahead_mm * cos(th));
        d->block_y = in->estimate.y_mm + (int32_t)lround(in->ahead_mm * sin(th));
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0, 0 };
        return true;
    }
    if (d->p.slow_mm == 0 || in->ahead_mm >= d->p.slow_mm)
        return false;
    /* from full speed at slow_mm down to the slow speed at stop_mm, never faster again
     * within the leg (a reading that is not repeated is no all-clear) */
    int64_t span = d->p.slow_mm - d->p.stop_mm;
    int32_t v = (int32_t)(slow_speed(d) + (int64_t)(d->p.speed_mm_s - slow_speed(d)) *
                                              (in->ahead_mm - d->p.stop_mm) / span);
    if (v < d->speed_mm_s) {
        d->speed_mm_s = v;
        out->speed_mm_s = v;
    }
    return false;
}

void hl_drive_on_sip(hl_drive_t *d, const hl_drive_in_t *in, hl_drive_out_t *out)
{
    *out = (hl_drive_out_t){ HL_DRIVE_CMD_NONE, 0, 0 };
    if (d->phase != HL_DRIVE_TURN && d->phase != HL_DRIVE_MOVE && d->phase != HL_DRIVE_FINAL_TURN)
        return;
    static const char *const doing[] = { [HL_DRIVE_TURN] = "turning",
                                         [HL_DRIVE_MOVE] = "driving",
                                         [HL_DRIVE_FINAL_TURN] = "turning to the heading" };
    char why[96];
    if (in->stalled) {
        snprintf(why, sizeof why, "the base stalled while %s (leg %d)", doing[d->phase], d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0, 0 };
        return;
    }
    if (d->phase == HL_DRIVE_MOVE && watch_ahead(d, in, out))
        return;
    if (in->robot_ms > d->deadline_ms) {
        snprintf(why, sizeof why, "timed out %s after %.1f s of robot time (leg %d)",
                 doing[d->phase], (in->robot_ms - d->cmd_ms) / 1000.0, d->legs);
        hl_drive_fail(d, why);
        *out = (hl_drive_out_t){ HL_DRIVE_CMD_STOP, 0, 0 };
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
            *out = (hl_drive_out_t){ HL_DRIVE_CMD_SOUND, 0, 0 };
    }
}
