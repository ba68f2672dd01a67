/* robot_link.c - the live robot's link: opening it, the ARCOS connection over it, losing it
 * and trying again with a doubling wait (robot.h); or replaying a captured one (a file
 * link), which ends the daemon at its end. */
#include <poll.h>
#include <stdio.h>
#include <string.h>

#include "log.h"
#include "robot_internal.h"

/* A captured stream replayed (robot.link = file:CAPTURE): no wall-clock timeouts (its
 * SYNC echoes and SIPs are all there, read as fast as the loop takes them), no second
 * connection. */
static bool replaying(const hl_robot_t *r)
{
    return r->p.link.kind == HL_LINK_FILE;
}

/* The end of a replayed capture (@p end 1), or a capture that cannot be read (-1): the
 * loop asks hl_robot_replay_ended after each event and stops as at the end of a replayed
 * log, saving its map. */
static void end_replay(hl_robot_t *r, int end, const char *why)
{
    hl_log(end > 0 ? HL_LOG_NOTICE : HL_LOG_ERR,
           "robot link: %s: stopping, as at the end of a replayed log", why);
    r->replay_end = end;
}

int hl_robot_replay_ended(const hl_robot_t *r)
{
    return r->replay_end;
}

int hl_robot_fd(const hl_robot_t *r)
{
    return r->link && !hl_link_ended(r->link) ? hl_link_fd(r->link) : -1;
}

short hl_robot_events(const hl_robot_t *r)
{
    if (!r->link || hl_link_ended(r->link))
        return 0;
    return (short)(POLLIN | (hl_link_connecting(r->link) || r->rlink.out_len ? POLLOUT : 0));
}

/* A link fault: logged once until a different one happens, with the wait before the next
 * attempt; STATUS's last_error always has it. */
static void note_fault(hl_robot_t *r, const char *why)
{
    char what[HL_BUS_TEXT_MAX];
    snprintf(what, sizeof what, "%.120s; retrying in %.2f s", why, r->backoff_ms / 1000.0);
    if (strcmp(why, r->last_fault) != 0)
        hl_log(HL_LOG_WARNING, "robot link: %s (retrying, the wait doubling from %.2f s to "
               "%.1f s; logged again when the fault changes)", why, r->backoff_ms / 1000.0,
               r->p.reconnect_max_ms / 1000.0);
    snprintf(r->last_fault, sizeof r->last_fault, "%s", why);
    hl_cycle_note_error(r->cycle, what);
}

/* The most a lost link's last bytes (the STOP the ARCOS connection queued) may hold the
 * loop: a serial port at 9600 baud takes the few bytes in about 15 ms. */
#define STOP_FLUSH_MS 200

/* Writes what the ARCOS connection still holds (its STOP and CLOSE to a robot lost to
 * silence) to a link that still takes bytes, waiting for room up to STOP_FLUSH_MS.
 * @return NULL when all of it went out, else what stopped it (in @p why). */
static const char *flush_before_close(hl_robot_t *r, char *why)
{
    size_t n;
    const uint8_t *out = hl_rlink_pending(&r->rlink, &n);
    int waited_ms = 0;
    while (n > 0) {
        ssize_t put = hl_link_write(r->link, out, n, why);
        if (put < 0)
            return why;
        if (put == 0) {
            /* full: wait for room in slices, so that the bound holds whatever wakes us */
            struct pollfd p = { .fd = hl_link_fd(r->link), .events = POLLOUT };
            if (waited_ms >= STOP_FLUSH_MS)
                return "the link took no more bytes";
            poll(&p, 1, 10);
            waited_ms += 10;
            continue;
        }
        hl_rlink_sent(&r->rlink, (size_t)put);
        out = hl_rlink_pending(&r->rlink, &n);
    }
    return NULL;
}

/* @p head, @p middle and @p tail joined into @p out (@p cap bytes): the middle is cut
 * short when they do not fit, never the head or the tail. */
static void join(char *out, size_t cap, const char *head, const char *middle,
                 const char *tail)
{
    size_t nh = strlen(head), nt = strlen(tail), nm = strlen(middle);
    if (nh + nt >= cap)
        nt = 0;         /* cannot happen with this file's texts; stay in bounds anyway */
    if (nh >= cap)
        nh = cap - 1;
    if (nm > cap - 1 - nh - nt)
        nm = cap - 1 - nh - nt;
    memmove(out, head, nh);
    memmove(out + nh, middle, nm);
    memmove(out + nh + nm, tail, nt);
    out[nh + nm + nt] = '\0';
}

/* The link is lost: closed, the destination failed, a retry scheduled. @p writable: the
 * link itself did not fail (the ARCOS connection gave up on it), so what that queued for
 * the robot (a STOP, after silence) is written before it is closed. */
static void drop_link(hl_robot_t *r, const char *cause, bool writable, int64_t now_ms)
{
    /* copies: the cause may be the ARCOS link's own text (hl_rlink_why), which
     * hl_rlink_lost below rewrites; no text is formatted onto itself */
    char why[HL_LINK_WHY_LEN], err[HL_LINK_WHY_LEN], stop[96] = "";
    snprintf(why, sizeof why, "%s", cause);
    if (writable && r->link && hl_rlink_stop_queued(&r->rlink)) {
        const char *failed = flush_before_close(r, err);
        join(stop, sizeof stop, failed ? "; stop not sent: " : "; stop sent",
             failed ? failed : "", "");
    }
    char full[HL_LINK_WHY_LEN], what[HL_BUS_TEXT_MAX];
    join(full, sizeof full, "", why, stop);
    join(what, sizeof what, "robot link lost: ", why, stop);
    note_fault(r, full);
    hl_link_close(r->link);
    r->link = NULL;
    r->up = false;
    /* Silence is not a closed connection: the robot went on obeying what it was last
     * told until the STOP reached it (or its own watchdog fired), and nothing of that
     * motion was heard. */
    if (hl_rlink_stop_queued(&r->rlink) &&
        (r->dest_seq >= 0 || hl_sounder_state(&r->sounder) == HL_SOUNDER_BUSY))
        r->moved_unseen = true;
    hl_rlink_lost(&r->rlink, full);
    robot_abandon(r, what, now_ms);
    r->retry_at_ms = now_ms + r->backoff_ms;
    r->backoff_ms = r->backoff_ms * 2 > r->p.reconnect_max_ms ? r->p.reconnect_max_ms
                                                              : r->backoff_ms * 2;
    robot_set_state(r, HL_BUS_STATE_FAULT, now_ms);
}

/* Follows the ARCOS connection's state after anything that may change it. */
static void check_connection(hl_robot_t *r, int64_t now_ms)
{
    uint64_t bad = hl_rlink_bad_packets(&r->rlink);
    if (bad != r->bad_reported) {
        hl_cycle_set_bad_packets(r->cycle, bad > HL_COUNT_MAX ? HL_COUNT_MAX : (int64_t)bad);
        r->bad_reported = bad;
    }
    if (r->link && !hl_link_connecting(r->link) && hl_rlink_state(&r->rlink) == HL_RLINK_DOWN) {
        drop_link(r, hl_rlink_why(&r->rlink), true, now_ms);
        return;
    }
    if (r->up || hl_rlink_state(&r->rlink) != HL_RLINK_UP)
        return;
    r->up = true;
    r->backoff_ms = FIRST_BACKOFF_MS;
    r->last_fault[0] = '\0';
    hl_log(HL_LOG_NOTICE, "robot '%s' (%s %s) connected", r->rlink.id.name, r->rlink.id.cls,
           r->rlink.id.subclass);
    robot_link_up(r, now_ms);
}

/* A lockstep simulator's clock: the SIP just dealt with is answered with STEP when the
 * robot has something to do; while it is idle the clock is held (the STEP stays owed until
 * a destination, a sounding or a STOP's braking gives it something to do again), and the
 * silence that follows is no fault. */
static void lockstep(hl_robot_t *r, int64_t now_ms)
{
    if (!r->step_owed || !r->up)
        return;
    if (!robot_busy(r)) {
        hl_rlink_hold(&r->rlink, now_ms);
        return;
    }
    r->step_owed = false;
    robot_command(r, HL_ARCOS_STEP, false, 0, now_ms);
}

void robot_flush(hl_robot_t *r, int64_t now_ms)
{
    char why[HL_LINK_WHY_LEN];
    lockstep(r, now_ms);
    size_t n;
    const uint8_t *out = hl_rlink_pending(&r->rlink, &n);
    while (r->link && !hl_link_connecting(r->link) && n > 0) {
        ssize_t put = hl_link_write(r->link, out, n, why);
        if (put < 0) {
            drop_link(r, why, false, now_ms);
            return;
        }
        if (put == 0)
            return;     /* the socket is full: POLLOUT brings us back */
        hl_rlink_sent(&r->rlink, (size_t)put);
        out = hl_rlink_pending(&r->rlink, &n);
    }
}

static void connect_now(hl_robot_t *r, int64_t now_ms)
{
    char why[HL_LINK_WHY_LEN];
    r->link = hl_link_open(&r->p.link, why);
    if (!r->link && replaying(r)) {
        hl_log(HL_LOG_ERR, "robot link: %s", why);
        hl_cycle_note_error(r->cycle, why);
        end_replay(r, -1, "the capture cannot be replayed");
        r->retry_at_ms = INT64_MAX;     /* no second try at a file */
        return;
    }
    if (!r->link) {
        drop_link(r, why, false, now_ms);
        return;
    }
    if (!hl_link_connecting(r->link))
        hl_rlink_begin(&r->rlink, now_ms);
}

void hl_robot_on_ready(hl_robot_t *r, short revents, int64_t now_ms)
{
    char why[HL_LINK_WHY_LEN];
    if (!r->link || hl_link_ended(r->link))
        return;
    if (hl_link_connecting(r->link)) {
        if (!(revents & (POLLOUT | POLLERR | POLLHUP)))
            return;
        if (!hl_link_connected(r->link, why)) {
            drop_link(r, why, false, now_ms);
            return;
        }
        hl_rlink_begin(&r->rlink, now_ms);
    } else if (revents & (POLLIN | POLLERR | POLLHUP)) {
        uint8_t in[512];
        robot_sip_ctx_t ctx = { r, now_ms };
        for (int rounds = 0; r->link && rounds < 16; rounds++) {
            /* A live robot starts its SIPs only after the OPEN that answers SYNC2's echo,
             * so the connection is up (and the sounding on connect started) before the
             * first SIP. A capture holds both already: read its handshake byte by byte,
             * so that it comes up at the same point of the stream. */
            size_t want = replaying(r) && hl_rlink_state(&r->rlink) != HL_RLINK_UP ? 1 : sizeof in;
            ssize_t got = hl_link_read(r->link, in, want, why);
            if (got < 0 && hl_link_ended(r->link)) {
                end_replay(r, 1, why);
                return;
            }
            if (got < 0) {
                drop_link(r, why, false, now_ms);
                return;
            }
            if (got == 0)
                break;
            hl_rlink_feed(&r->rlink, in, (size_t)got, now_ms, robot_on_sip, &ctx);
            check_connection(r, now_ms);
        }
    }
    check_connection(r, now_ms);
    robot_flush(r, now_ms);
}

void hl_robot_tick(hl_robot_t *r, int64_t now_ms)
{
    if (!r->link) {
        if (now_ms >= r->retry_at_ms)
            connect_now(r, now_ms);
    } else if (!hl_link_connecting(r->link) && !replaying(r)) {
        hl_rlink_tick(&r->rlink, now_ms);
    }
    check_connection(r, now_ms);
    robot_flush(r, now_ms);
}

void hl_robot_stop(hl_robot_t *r, int64_t now_ms)
{
    robot_abandon(r, "houghlocd is stopping", now_ms);
    if (r->link && r->up) {
        robot_command(r, HL_ARCOS_STOP, false, 0, now_ms);
        hl_rlink_close(&r->rlink, "houghlocd stopped", now_ms);
        robot_flush(r, now_ms);
    }
    hl_link_close(r->link);
    r->link = NULL;
    r->up = false;
}
