/* robot.c - the live robot: soundings, destinations and the robot's packets (robot.h);
 * the connection is robot_link.c's. */
#include "robot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "log.h"
#include "robot_internal.h"

/* The utime of robot time 0 in a replayed capture: any fixed instant (the simulated data
 * sets' base, 1e15 us, in 2001). */
#define REPLAY_EPOCH_US 1000000000000000LL

hl_robot_t *hl_robot_create(const hl_robot_params_t *p, hl_cycle_t *cycle,
                            const hl_cycle_io_t *io)
{
    hl_robot_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->cycle = cycle;
    r->io = *io;
    r->dest_seq = -1;
    if (hl_rlink_init(&r->rlink, &p->rlink) != HL_OK ||
        hl_sounder_init(&r->sounder, &p->sounder, &p->profile) != HL_OK ||
        hl_drive_init(&r->drive, &p->drive) != HL_OK || p->reconnect_max_ms < FIRST_BACKOFF_MS ||
        !robot_nav_create(r)) {
        free(r);
        return NULL;
    }
    /* A replayed capture's messages carry a fixed time, so that two replays publish the
     * same bytes (the ARCOS golden); a live robot's, the wall clock's. */
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    r->epoch_us = p->link.kind == HL_LINK_FILE ? REPLAY_EPOCH_US
                                               : (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
    r->backoff_ms = FIRST_BACKOFF_MS;
    return r;
}

void hl_robot_destroy(hl_robot_t *r)
{
    if (!r)
        return;
    hl_link_close(r->link);
    robot_nav_destroy(r);
    free(r);
}

/* ---- messages out: published, and handed to the cycle as if they came from LCM -------- */

static void deliver(hl_robot_t *r, hl_chan_t ch, int len, int64_t now_ms)
{
    if (len <= 0) {
        hl_log(HL_LOG_ERR, "cannot encode a %s message", hl_chan_name(ch));
        return;
    }
    r->io.emit(r->io.ctx, ch, r->buf, (size_t)len);
    hl_cycle_on_message(r->cycle, ch, r->buf, (size_t)len, now_ms * 1000);
}

static int64_t utime_now(const hl_robot_t *r)
{
    return r->epoch_us + r->robot_ms * 1000;
}

static void reply(hl_robot_t *r, int64_t seq, int8_t result, const char *what)
{
    hl_cycle_answer(r->cycle, seq, result, what);
}

void robot_set_state(hl_robot_t *r, int8_t state, int64_t now_ms)
{
    hl_cycle_set_destination(r->cycle, r->dest_seq);
    hl_cycle_set_state(r->cycle, state, now_ms * 1000);
}

/* ---- commands to the base ------------------------------------------------------------ */

void robot_command(hl_robot_t *r, uint8_t number, bool has_arg, int32_t arg, int64_t now_ms)
{
    bool ok = has_arg ? hl_rlink_send_int(&r->rlink, number, arg, now_ms)
                      : hl_rlink_send(&r->rlink, number, now_ms);
    hl_rlink_sent_at(&r->rlink, r->robot_ms);
    if (!ok)
        hl_log(HL_LOG_WARNING, "robot command %u not sent (link down or output full)", number);
}

bool robot_busy(const hl_robot_t *r)
{
    return r->dest_seq >= 0 || r->dest_pending ||
           hl_sounder_state(&r->sounder) == HL_SOUNDER_BUSY || r->last_in.moving;
}

static void end_destination(hl_robot_t *r, int8_t result, const char *what, int64_t now_ms)
{
    if (r->dest_seq < 0)
        return;
    robot_nav_end(r);
    hl_log(result == HL_BUS_REPLY_ARRIVED ? HL_LOG_INFO : HL_LOG_WARNING,
           "destination %lld: %s", (long long)r->dest_seq, what);
    reply(r, r->dest_seq, result, what);
    if (result != HL_BUS_REPLY_ARRIVED)
        hl_cycle_note_error(r->cycle, what);
    r->dest_seq = -1;
    robot_set_state(r, HL_BUS_STATE_IDLE, now_ms);
}

static void start_sounding(hl_robot_t *r, int64_t now_ms)
{
    robot_nav_polling(r, false, now_ms);
    hl_sounder_start(&r->sounder);
    robot_set_state(r, HL_BUS_STATE_SOUNDING, now_ms);
}

static void drive_do(hl_robot_t *r, const hl_drive_out_t *out, int64_t now_ms)
{
    int32_t ahead;
    if (hl_drive_blocked(&r->drive, &ahead) && r->drive.blocks != r->blocks_logged) {
        r->blocks_logged = r->drive.blocks;
        hl_log(HL_LOG_NOTICE, "destination %lld: safety stop: a sonar reading %.2f m ahead "
               "(%d on this destination); sounding, then planning round it",
               (long long)r->dest_seq, ahead / 1000.0, r->drive.blocks);
    }
    if (out->speed_mm_s > 0)
        robot_command(r, HL_ARCOS_SETV, true, out->speed_mm_s, now_ms);
    switch (out->cmd) {
    case HL_DRIVE_CMD_STOP: robot_command(r, HL_ARCOS_STOP, false, 0, now_ms); break;
    case HL_DRIVE_CMD_HEAD: robot_command(r, HL_ARCOS_HEAD, true, out->arg, now_ms); break;
    case HL_DRIVE_CMD_MOVE:
        robot_nav_polling(r, true, now_ms);
        robot_command(r, HL_ARCOS_MOVE, true, out->arg, now_ms);
        break;
    case HL_DRIVE_CMD_SOUND: start_sounding(r, now_ms); break;
    case HL_DRIVE_CMD_NONE: break;
    }
    if (out->cmd == HL_DRIVE_CMD_HEAD || out->cmd == HL_DRIVE_CMD_MOVE)
        robot_set_state(r, HL_BUS_STATE_MOVING, now_ms);
    char what[HL_BUS_TEXT_MAX];
    switch (hl_drive_phase(&r->drive)) {
    case HL_DRIVE_ARRIVED:
        snprintf(what, sizeof what, "arrived %.3f m from the destination after %d legs",
                 hl_drive_remaining(&r->drive, hl_cycle_estimate(r->cycle)) / 1000.0,
                 r->drive.legs);
        end_destination(r, HL_BUS_REPLY_ARRIVED, what, now_ms);
        break;
    case HL_DRIVE_FAILED:
        end_destination(r, HL_BUS_REPLY_FAILED, hl_drive_why(&r->drive), now_ms);
        break;
    default:
        break;
    }
}

/* Plans the next leg towards the destination under way unless the robot is within reach
 * of it (then no leg follows). @return false when there is no way: the destination has
 * failed, with the planner's reason. */
static bool plan_leg(hl_robot_t *r, int32_t goal_x, int32_t goal_y, int64_t now_ms)
{
    hl_pose_t at = hl_cycle_estimate(r->cycle);
    if (hypot((double)goal_x - at.x_mm, (double)goal_y - at.y_mm) <= r->p.drive.arrive_mm)
        return true;
    char why[HL_BUS_TEXT_MAX], reason[HL_BUS_TEXT_MAX];
    if (robot_nav_plan(r, goal_x, goal_y, reason, sizeof reason))
        return true;
    int32_t ahead;
    if (hl_drive_blocked(&r->drive, &ahead))   /* the safety stop showed the way is shut */
        snprintf(why, sizeof why, "blocked: an obstacle %.2f m ahead; %.120s",
                 ahead / 1000.0, reason);
    else
        snprintf(why, sizeof why, "%s", reason);
    hl_drive_fail(&r->drive, why);
    robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
    end_destination(r, HL_BUS_REPLY_FAILED, why, now_ms);
    return false;
}

/* Starts the drive to destination @p d (its seq is r->dest_seq), planned already when
 * @p planned. */
static void begin_destination(hl_robot_t *r, const hl_bus_destination_t *d, bool planned,
                              int64_t now_ms)
{
    r->dest_seq = d->seq;
    r->last_in.estimate = hl_cycle_estimate(r->cycle);
    hl_log(HL_LOG_INFO, "destination %lld: to (%.3f, %.3f) m", (long long)d->seq,
           d->x_mm / 1000.0, d->y_mm / 1000.0);
    if (!planned && !plan_leg(r, d->x_mm, d->y_mm, now_ms))
        return;
    hl_drive_out_t out;
    r->blocks_logged = 0;
    hl_drive_start(&r->drive, d->x_mm, d->y_mm, d->has_heading, d->heading, &r->last_in, &out);
    drive_do(r, &out, now_ms);
}

void hl_robot_destination(hl_robot_t *r, const hl_bus_destination_t *d, int64_t now_ms)
{
    if (!r->up) {
        char what[HL_BUS_TEXT_MAX];
        snprintf(what, sizeof what, "robot link down: %s",
                 r->link ? "connecting" : hl_rlink_why(&r->rlink));
        reply(r, d->seq, HL_BUS_REPLY_NO_ROBOT, what);
        return;
    }
    if (hl_cycle_lost(r->cycle)) {
        reply(r, d->seq, HL_BUS_REPLY_FAILED, "lost: the pose is unknown; wait for the daemon "
              "to relocalize, or send SET_POSE");
        return;
    }
    if (r->dest_seq >= 0 || r->dest_pending) {
        char what[HL_BUS_TEXT_MAX];
        snprintf(what, sizeof what, "superseded by destination %lld", (long long)d->seq);
        if (r->dest_pending)
            reply(r, r->pending.seq, HL_BUS_REPLY_FAILED, what);
        r->dest_pending = false;
        hl_drive_fail(&r->drive, what);
        end_destination(r, HL_BUS_REPLY_FAILED, what, now_ms);
    }
    r->halted = false;
    if (hl_sounder_state(&r->sounder) == HL_SOUNDER_BUSY) {
        reply(r, d->seq, HL_BUS_REPLY_ACCEPTED, "under way (after the sounding in progress)");
        r->pending = *d;            /* the sounding in progress ends first; planned then */
        r->dest_pending = true;
        return;
    }
    /* planned before it is accepted: a destination with no way is refused at once */
    char why[HL_BUS_TEXT_MAX];
    r->dest_seq = d->seq;
    bool planned = robot_nav_plan(r, d->x_mm, d->y_mm, why, sizeof why);
    r->dest_seq = -1;
    if (!planned) {
        hl_log(HL_LOG_WARNING, "destination %lld: %s", (long long)d->seq, why);
        reply(r, d->seq, HL_BUS_REPLY_FAILED, why);
        hl_cycle_note_error(r->cycle, why);
        return;
    }
    reply(r, d->seq, HL_BUS_REPLY_ACCEPTED, "under way");
    robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
    begin_destination(r, d, true, now_ms);
}

void hl_robot_halt(hl_robot_t *r, int64_t seq, int64_t now_ms)
{
    char why[HL_BUS_TEXT_MAX];
    snprintf(why, sizeof why, "stopped by STOP (request seq %lld)", (long long)seq);
    r->halted = true;
    r->halted_epoch = hl_cycle_lost_epoch(r->cycle);
    if (!r->up)
        return;
    robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
    robot_flush(r, now_ms);         /* at once, before anything else is dealt with */
    robot_abandon(r, why, now_ms);
    robot_set_state(r, HL_BUS_STATE_IDLE, now_ms);
}

/* ---- the robot's packets -------------------------------------------------------------- */

/* The SIP's odometry in the published frame, anchored at the first SIP of a connection
 * so that it continues where the last one (or the saved map) left off. */
static bool odometry_of(hl_robot_t *r, const hl_arcos_sip_t *sip, hl_pose_t *robot_frame,
                        hl_pose_t *published)
{
    if (!r->anchored)
        hl_arcos_odom_init(&r->odom, r->p.conv.angle_units_per_turn);
    if (hl_arcos_odom_unwrap(&r->odom, sip) != HL_OK)
        return false;
    int64_t x = r->odom.x * r->p.conv.dist_um / 1000, y = r->odom.y * r->p.conv.dist_um / 1000;
    if (x < -HL_COORD_MAX_MM || x > HL_COORD_MAX_MM || y < -HL_COORD_MAX_MM || y > HL_COORD_MAX_MM)
        return false;
    *robot_frame = (hl_pose_t){ (hl_mm_t)x, (hl_mm_t)y,
                                hl_arcos_angle_to_bam(&r->p.conv, r->odom.th) };
    if (!r->anchored) {
        hl_pose_t anchor;
        bool have = r->have_published || hl_cycle_odometry(r->cycle, &anchor);
        if (r->have_published)
            anchor = r->published;
        r->offset = have ? hl_pose_compose(anchor, hl_pose_between(*robot_frame,
                                                                    (hl_pose_t){ 0, 0, 0 }))
                         : (hl_pose_t){ 0, 0, 0 };
        r->anchored = true;
    }
    *published = hl_pose_compose(r->offset, *robot_frame);
    return hl_pose_in_range(*published);
}

static void publish_odometry(hl_robot_t *r, const hl_arcos_sip_t *sip, hl_pose_t pose,
                             int64_t now_ms)
{
    int32_t v = (sip->vel_left + sip->vel_right) / 2 * (int32_t)r->p.conv.vel_um_s / 1000;
    hl_bus_odometry_t o = { .utime = utime_now(r), .pose = pose,
                            .velocity_mm_s = (int16_t)(v < -32768 ? -32768 : v > 32767 ? 32767 : v),
                            .stopped = sip->type == HL_ARCOS_SIP_STOPPED };
    r->published = pose;
    r->have_published = true;
    deliver(r, HL_CH_ODOMETRY, hl_bus_encode_odometry(&o, r->buf, sizeof r->buf), now_ms);
}

/* While the daemon is lost the robot stands still and sounds, each sounding searching
 * the whole map, up to lost_soundings times for each time it became lost; a destination
 * under way is given up (the estimate it steers by is unknown). True when it acted. */
static bool lost_sound(hl_robot_t *r, int64_t now_ms)
{
    if (!hl_cycle_lost(r->cycle))
        return false;
    if (r->halted && r->halted_epoch == hl_cycle_lost_epoch(r->cycle))
        return false;               /* stopped by STOP: still until told to move */
    if (r->dest_seq >= 0 || r->dest_pending)
        robot_abandon(r, "lost: the pose is unknown (the daemon is relocalizing)", now_ms);
    if (r->lost_epoch != hl_cycle_lost_epoch(r->cycle)) {
        r->lost_epoch = hl_cycle_lost_epoch(r->cycle);
        r->lost_soundings = 0;
    }
    if (r->lost_soundings >= r->p.lost_soundings) {
        /* Soundings from the same spot tell no more: going on lost would refuse every
         * destination until an operator came. Tracking kept following the ambiguous
         * scans; go on from there. */
        char why[HL_BUS_TEXT_MAX];
        snprintf(why, sizeof why, "still lost after %d soundings standing still "
                 "(the global search's scans)", r->lost_soundings);
        hl_cycle_give_up_lost(r->cycle, why, now_ms * 1000);
        return false;
    }
    r->lost_soundings++;
    robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
    start_sounding(r, now_ms);
    return true;
}

static void finish_sounding(hl_robot_t *r, int64_t now_ms)
{
    hl_pose_t robot_frame;
    if (hl_sounder_take(&r->sounder, &r->msg.scan, &robot_frame) != HL_OK)
        return;
    r->msg.utime = utime_now(r);
    r->msg.seq = ++r->scan_seq;
    r->msg.odometry = hl_pose_compose(r->offset, robot_frame);
    deliver(r, HL_CH_SONAR, hl_bus_encode_scan(&r->msg, r->buf, sizeof r->buf), now_ms);
    r->sounded_once = true;
    r->last_in.estimate = hl_cycle_estimate(r->cycle);
    if (lost_sound(r, now_ms))
        return;
    if (r->dest_pending) {
        r->dest_pending = false;
        begin_destination(r, &r->pending, false, now_ms);
    } else if (r->dest_seq >= 0 && hl_drive_phase(&r->drive) == HL_DRIVE_SOUND) {
        if (hl_drive_blocked(&r->drive, NULL))
            robot_nav_blocked(r);
        if (!plan_leg(r, r->drive.goal_x, r->drive.goal_y, now_ms))
            return;
        hl_drive_out_t out;
        hl_drive_localized(&r->drive, &r->last_in, &out);
        drive_do(r, &out, now_ms);
    } else {
        robot_set_state(r, HL_BUS_STATE_IDLE, now_ms);
    }
}

static void sounder_step(hl_robot_t *r, const hl_arcos_sip_t *sip, hl_pose_t robot_frame,
                         int64_t now_ms)
{
    hl_sounder_sip_t in = { .robot_ms = r->robot_ms, .odometry = robot_frame,
                            .moving = sip->type == HL_ARCOS_SIP_MOVING,
                            .readings = sip->sonar_count };
    for (int32_t i = 0; i < in.readings; i++) {
        in.transducer[i] = sip->sonar[i].transducer;
        in.raw[i] = sip->sonar[i].range;
    }
    int32_t head = 0;
    hl_sounder_cmd_t cmd = hl_sounder_on_sip(&r->sounder, &in, &head);
    if (cmd == HL_SOUNDER_CMD_STOP)
        robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
    else if (cmd == HL_SOUNDER_CMD_HEAD)
        robot_command(r, HL_ARCOS_HEAD, true, head, now_ms);
    if (hl_sounder_state(&r->sounder) == HL_SOUNDER_DONE) {
        finish_sounding(r, now_ms);
    } else if (hl_sounder_state(&r->sounder) == HL_SOUNDER_FAILED) {
        hl_log(HL_LOG_WARNING, "%s", hl_sounder_why(&r->sounder));
        hl_cycle_note_error(r->cycle, hl_sounder_why(&r->sounder));
        hl_sounder_cancel(&r->sounder);
        hl_drive_fail(&r->drive, hl_sounder_why(&r->sounder));
        end_destination(r, HL_BUS_REPLY_FAILED, hl_sounder_why(&r->sounder), now_ms);
        robot_set_state(r, HL_BUS_STATE_IDLE, now_ms);
    }
}

void robot_on_sip(void *ctx, const hl_arcos_sip_t *sip)
{
    robot_sip_ctx_t *c = ctx;
    hl_robot_t *r = c->r;
    r->robot_ms += SIP_PERIOD_MS;
    hl_pose_t robot_frame, published;
    if (!odometry_of(r, sip, &robot_frame, &published)) {
        hl_cycle_note_error(r->cycle, "robot odometry out of range");
        return;
    }
    publish_odometry(r, sip, published, c->now_ms);
    hl_rlink_keepalive(&r->rlink, r->robot_ms);
    r->last_in = (hl_drive_in_t){
        .robot_ms = r->robot_ms, .estimate = hl_cycle_estimate(r->cycle),
        .odometry = robot_frame, .moving = sip->type == HL_ARCOS_SIP_MOVING,
        .stalled = (sip->stall_bumpers & (HL_ARCOS_STALL_LEFT | HL_ARCOS_STALL_RIGHT)) != 0,
        .ahead_mm = 0 };
    r->step_owed = r->p.lockstep;
    if (r->dest_seq >= 0 && hl_drive_phase(&r->drive) == HL_DRIVE_MOVE &&
        !hl_drive_blocked(&r->drive, NULL))
        r->last_in.ahead_mm = robot_nav_ahead(r, sip);
    if (hl_sounder_state(&r->sounder) == HL_SOUNDER_BUSY) {
        sounder_step(r, sip, robot_frame, c->now_ms);
    } else if (lost_sound(r, c->now_ms)) {
        return;     /* lost by a command between soundings: sound now */
    } else if (r->dest_seq >= 0) {
        hl_drive_out_t out;
        hl_drive_on_sip(&r->drive, &r->last_in, &out);
        drive_do(r, &out, c->now_ms);
    }
}

void robot_link_up(hl_robot_t *r, int64_t now_ms)
{
    r->anchored = false;
    /* The firing order is the robot's, not the connection's: ARCOS keeps a POLLING until
     * told otherwise, so a client killed while driving leaves the robot firing its front
     * transducers alone, and a sounding would wait for the others in vain. The whole ring
     * is set explicitly. */
    r->polling_ahead = true;
    robot_nav_polling(r, false, now_ms);
    /* A robot that moved while its link was silent is somewhere the odometry did not
     * see: found again as a lost one is, by soundings searched over the whole map,
     * rather than tracked from where it was last heard. */
    if (r->moved_unseen) {
        r->moved_unseen = false;
        hl_cycle_enter_lost(r->cycle, "the robot moved while its link was silent",
                            now_ms * 1000);
    }
    if (r->p.sound_on_connect && !r->sounded_once)
        start_sounding(r, now_ms);
    else
        robot_set_state(r, HL_BUS_STATE_IDLE, now_ms);
}

void robot_abandon(hl_robot_t *r, const char *why, int64_t now_ms)
{
    hl_sounder_cancel(&r->sounder);
    if (r->dest_pending)
        reply(r, r->pending.seq, HL_BUS_REPLY_FAILED, why);
    r->dest_pending = false;
    hl_drive_fail(&r->drive, why);
    end_destination(r, HL_BUS_REPLY_FAILED, why, now_ms);
}
