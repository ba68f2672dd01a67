/* cycle_requests.c - DESTINATION and COMMAND: authenticity, freshness, the geofence,
 * and one REPLY (signed when there is a key) for every request whose seq could be read.
 *
 * Freshness is a window: a request's seq must be above the last accepted one and at most
 * max_ahead_us ahead of the wall clock (senders stamp their wall clock in microseconds),
 * so that one request from a client whose clock is wrong cannot move the window a year
 * ahead and lock every other client out. With a key, the accepted seq is kept in the
 * request state file (io.keep_seq) before the request is carried out: a crash, a new map
 * or a lost map file cannot reopen the window to requests captured before. */
#include <stdio.h>

#include "cycle_internal.h"
#include "log.h"

void hl_cycle_reply(hl_cycle_t *c, int64_t seq, int8_t result, const char *message)
{
    hl_bus_reply_t r = { .utime = c->newest_utime, .seq = seq, .result = result };
    snprintf(r.message, sizeof r.message, "%s", message);
    /* signed, so that a client holding the key can tell the daemon's answer from a forged
     * one (a false ARRIVED); a reply that does not sign does not encode either */
    if (c->p.authenticate)
        hl_auth_sign_reply(&c->p.key, c->p.prefix, &r);
    int len = hl_bus_encode_reply(&r, c->buf, sizeof c->buf);
    if (len > 0)
        c->io.emit(c->io.ctx, HL_CH_REPLY, c->buf, (size_t)len);
    /* refusals are logged once per kind by hl_cycle_fault, and NO_ROBOT changes nothing: a
     * flood of either must not flood the log */
    bool quiet = result != HL_BUS_REPLY_ACCEPTED && result != HL_BUS_REPLY_ARRIVED &&
                 result != HL_BUS_REPLY_FAILED;
    hl_log(quiet ? HL_LOG_DEBUG : HL_LOG_INFO, "request %lld: %s: %s", (long long)seq,
           hl_bus_reply_name(result), message);
}

/* Refuses a request: counted, logged once per kind, answered. */
static void refuse(hl_cycle_t *c, const char *channel, int64_t seq, int8_t result,
                   const char *kind, const char *why)
{
    char what[HL_BUS_TEXT_MAX];
    snprintf(what, sizeof what, "%s seq %lld: %s: %.100s", channel, (long long)seq,
             hl_bus_reply_name(result), why);
    hl_cycle_fault(c, &c->n.rejected_requests, kind, what);
    hl_cycle_reply(c, seq, result, why);
}

/* How far @p seq is ahead of the wall clock, in microseconds (<= 0: not ahead); 0 when
 * the cycle has no wall clock. */
static int64_t ahead_of_clock(const hl_cycle_t *c, int64_t seq)
{
    if (!c->io.wall_us)
        return 0;
    int64_t now = c->io.wall_us(c->io.ctx);
    return now < 0 || seq <= now ? 0 : seq - now;
}

/* Authentic and fresh? Answers and returns false if not; else keeps the seq (with a
 * key: durably, before anything is done) and takes it. */
static bool admit(hl_cycle_t *c, const char *channel, int64_t seq, bool mac_ok)
{
    char why[HL_BUS_TEXT_MAX], kept[HL_BUS_TEXT_MAX];
    if (c->p.authenticate && !mac_ok) {
        refuse(c, channel, seq, HL_BUS_REPLY_REJECTED_AUTH, "request auth",
               "missing or wrong MAC: sign requests with the daemon's key");
        return false;
    }
    if (seq <= c->last_request_seq) {
        snprintf(why, sizeof why, "seq %lld is not above the last accepted %lld (a replay?)",
                 (long long)seq, (long long)c->last_request_seq);
        refuse(c, channel, seq, HL_BUS_REPLY_REJECTED_REPLAY, "request replay", why);
        return false;
    }
    int64_t ahead = ahead_of_clock(c, seq);
    if (c->p.max_ahead_us > 0 && ahead > c->p.max_ahead_us) {
        snprintf(why, sizeof why, "seq %lld is %.0f s ahead of the daemon's clock, more than "
                 "auth.max_ahead_s (%.0f s): is the sender's clock (or the daemon's) wrong?",
                 (long long)seq, ahead / 1e6, c->p.max_ahead_us / 1e6);
        refuse(c, channel, seq, HL_BUS_REPLY_REJECTED_REPLAY, "request ahead", why);
        return false;
    }
    if (c->p.authenticate && c->io.keep_seq &&
        !c->io.keep_seq(c->io.ctx, seq, kept, sizeof kept)) {
        snprintf(why, sizeof why, "not done: the request state cannot be kept: %.110s", kept);
        refuse(c, channel, seq, HL_BUS_REPLY_FAILED, "request state", why);
        return false;
    }
    c->last_request_seq = seq;
    return true;
}

void hl_cycle_take_request_seq(hl_cycle_t *c, int64_t seq, const char *from)
{
    if (seq > c->last_request_seq)
        c->last_request_seq = seq;
    int64_t ahead = ahead_of_clock(c, c->last_request_seq);
    if (c->p.max_ahead_us > 0 && ahead > c->p.max_ahead_us) {
        int64_t bound = c->last_request_seq - ahead + c->p.max_ahead_us;
        hl_log(HL_LOG_NOTICE, "the last accepted request seq %lld (from %s) is %.0f s ahead of "
               "the clock: taken as %lld, auth.max_ahead_s ahead (requests above that are "
               "refused anyway)", (long long)c->last_request_seq, from, ahead / 1e6,
               (long long)bound);
        c->last_request_seq = bound;
    }
}

int64_t hl_cycle_request_seq(const hl_cycle_t *c)
{
    return c->last_request_seq;
}

void hl_cycle_answer(hl_cycle_t *c, int64_t seq, int8_t result, const char *message)
{
    hl_cycle_reply(c, seq, result, message);
}

void hl_cycle_on_destination(hl_cycle_t *c, const void *data, size_t len, int64_t now_us)
{
    char why[HL_BUS_WHY_LEN], what[HL_BUS_TEXT_MAX];
    hl_bus_destination_t d;
    if (!hl_cycle_decoded(c, hl_bus_decode_destination(data, len, &d, why),
                          HL_CHANNEL_DESTINATION, "destination decode", why))
        return;
    bool mac_ok = c->p.authenticate && hl_auth_check_destination(&c->p.key, c->p.prefix, &d);
    if (!admit(c, HL_CHANNEL_DESTINATION, d.seq, mac_ok))
        return;
    if (!hl_fence_contains(&c->p.fence, d.x_mm, d.y_mm)) {
        snprintf(what, sizeof what, "(%.3f, %.3f) m is outside the geofence", d.x_mm / 1000.0,
                 d.y_mm / 1000.0);
        refuse(c, HL_CHANNEL_DESTINATION, d.seq, HL_BUS_REPLY_REJECTED_FENCE, "request fence",
               what);
        return;
    }
    if (c->io.destination)
        c->io.destination(c->io.ctx, &d, now_us);   /* the robot answers it */
    else
        hl_cycle_reply(c, d.seq, HL_BUS_REPLY_NO_ROBOT, HL_BUS_NO_ROBOT_UNCONFIGURED);
}

static void set_pose(hl_cycle_t *c, const hl_bus_command_t *cmd, int64_t now_us)
{
    char what[HL_BUS_TEXT_MAX];
    hl_pose_t odometry = c->have_scan || c->have_odometry ? c->odometry : cmd->pose;
    bool was_lost = hl_slam_lost(c->slam);
    if (hl_slam_set_pose(c->slam, cmd->pose, odometry) != HL_OK) {
        hl_cycle_reply(c, cmd->seq, HL_BUS_REPLY_REJECTED_INVALID, "pose out of range");
        return;
    }
    if (was_lost)   /* a pose set by hand ends the lost state (slam.h) */
        hl_log(HL_LOG_NOTICE, "no longer lost: the pose was set by hand");
    snprintf(what, sizeof what, "pose set to (%.3f, %.3f) m, %.1f deg; map kept",
             cmd->pose.x_mm / 1000.0, cmd->pose.y_mm / 1000.0, hl_bam_to_sdeg(cmd->pose.theta));
    hl_cycle_reply(c, cmd->seq, HL_BUS_REPLY_ACCEPTED, what);
    /* STATUS shows the new estimate at once */
    hl_cycle_set_state(c, c->state == HL_BUS_STATE_LOST ? HL_BUS_STATE_IDLE : c->state, now_us);
}

/* STOP is never refused: a stop must stop, whoever sends it and whatever its seq (an
 * operator's client whose key or counter is wrong is exactly when one is needed). It needs
 * no MAC and does not take the seq (so it cannot move the replay window of the requests
 * that do); the seq is logged, so that a stop can be traced to its sender. */
static void stop(hl_cycle_t *c, int64_t seq, int64_t now_us)
{
    hl_log(HL_LOG_NOTICE, "STOP (request seq %lld)", (long long)seq);
    if (c->io.stop)
        c->io.stop(c->io.ctx, seq, now_us);
    hl_cycle_reply(c, seq, HL_BUS_REPLY_ACCEPTED,
                   c->io.stop ? "stopped" : "stopped (no robot link is configured)");
}

void hl_cycle_on_command(hl_cycle_t *c, const void *data, size_t len, int64_t now_us)
{
    char why[HL_BUS_WHY_LEN];
    hl_bus_command_t cmd;
    if (!hl_cycle_decoded(c, hl_bus_decode_command(data, len, &cmd, why), HL_CHANNEL_COMMAND,
                          "command decode", why))
        return;
    if (cmd.kind == HL_BUS_COMMAND_STOP) {
        stop(c, cmd.seq, now_us);
        return;
    }
    bool mac_ok = c->p.authenticate && hl_auth_check_command(&c->p.key, c->p.prefix, &cmd);
    if (!admit(c, HL_CHANNEL_COMMAND, cmd.seq, mac_ok))
        return;
    switch (cmd.kind) {
    case HL_BUS_COMMAND_SET_POSE:
        set_pose(c, &cmd, now_us);
        break;
    case HL_BUS_COMMAND_SAVE:
        hl_cycle_on_save(c, cmd.seq);   /* answered when the loop has saved (cycle_save.c) */
        break;
    case HL_BUS_COMMAND_RELOCALIZE:
        hl_cycle_enter_lost(c, "RELOCALIZE command", now_us);
        hl_cycle_reply(c, cmd.seq, HL_BUS_REPLY_ACCEPTED,
                       "lost: the next scans search the whole map");
        break;
    default:    /* the decoder admits only the kinds above */
        hl_cycle_reply(c, cmd.seq, HL_BUS_REPLY_REJECTED_INVALID, "unknown command kind");
        break;
    }
}
