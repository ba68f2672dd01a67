/* loop.c - poll() over LCM, a timerfd and a signalfd (see loop.h). */
#include "loop.h"

#include <errno.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <systemd/sd-daemon.h>
#include <time.h>
#include <unistd.h>

#include "log.h"
#include "maplock.h"
#include "houghloc/mapstore.h"
#include "houghloc/seqfile.h"

#define WHY(...) snprintf(why, HL_CONFIG_WHY_LEN, __VA_ARGS__)

enum { TIMER_STATUS, TIMER_WATCHDOG, TIMER_ROBOT, N_TIMERS };

#define ROBOT_TICK_MS 50    /* link keep-alive, timeouts and reconnection checks */

typedef struct sub_ctx {
    hl_loop_t *loop;
    hl_chan_t ch;
} sub_ctx_t;

struct hl_loop {
    hl_loop_params_t p;
    lcm_t *in, *out;            /* out == in unless a separate output URL */
    hl_cycle_t *cycle;
    hl_robot_t *robot;          /* NULL without a live robot */
    char channel[HL_CH_COUNT][HL_BUS_CHANNEL_MAX];
    sub_ctx_t subs[HL_CH_COUNT];
    int sfd, tfd;
    int64_t due[N_TIMERS], period[N_TIMERS];    /* monotonic us; period 0 = off */
    int64_t save_wake_us;       /* a SAVE request waiting for its time; INT64_MAX: none */
    bool stop, input_ended, faulted;
    bool publish_failed;
};

static int64_t mono_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static int64_t clock_cb(void *ctx)
{
    (void)ctx;
    return mono_us();
}

static int64_t wall_cb(void *ctx)
{
    (void)ctx;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* An accepted request's seq, on disk before the request is carried out (cycle.h). */
static bool keep_seq_cb(void *ctx, int64_t seq, char *why, size_t cap)
{
    hl_loop_t *l = ctx;
    char reason[HL_SEQFILE_WHY_LEN];
    if (hl_seqfile_save(l->p.state_path, seq, reason) == HL_OK)
        return true;
    snprintf(why, cap, "%s", reason);
    return false;
}

static void emit_cb(void *ctx, hl_chan_t ch, const void *data, size_t len)
{
    hl_loop_t *l = ctx;
    if (lcm_publish(l->out, l->channel[ch], data, (unsigned)len) != 0 && !l->publish_failed) {
        l->publish_failed = true;   /* logged once: a full disk or a closed network */
        hl_log(HL_LOG_ERR, "cannot publish on %s (further failures are not logged)",
               l->channel[ch]);
    }
}

static void destination_cb(void *ctx, const hl_bus_destination_t *d, int64_t now_us)
{
    hl_loop_t *l = ctx;
    if (l->robot)
        hl_robot_destination(l->robot, d, now_us / 1000);
    else
        hl_cycle_answer(l->cycle, d->seq, HL_BUS_REPLY_NO_ROBOT, "the robot is not attached yet");
}

static void stop_cb(void *ctx, int64_t seq, int64_t now_us)
{
    hl_loop_t *l = ctx;
    if (l->robot)
        hl_robot_halt(l->robot, seq, now_us / 1000);
}

hl_cycle_io_t hl_loop_io(hl_loop_t *l)
{
    return (hl_cycle_io_t){ .emit = emit_cb, .now_us = clock_cb,
                            .destination = l->p.robot ? destination_cb : NULL,
                            .stop = l->p.robot ? stop_cb : NULL, .wall_us = wall_cb,
                            .keep_seq = l->p.state_path ? keep_seq_cb : NULL, .ctx = l };
}

void hl_loop_attach_robot(hl_loop_t *l, hl_robot_t *robot)
{
    l->robot = robot;
}

static void on_lcm(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    sub_ctx_t *s = user;
    hl_cycle_on_message(s->loop->cycle, s->ch, rbuf->data, rbuf->data_size, mono_us());
}

/* LCM subscribes by regular expression: escape the prefix's '.' */
static void channel_regex(const char *name, char *out, size_t cap)
{
    size_t n = 0;
    for (const char *c = name; *c && n + 3 < cap; c++) {
        if (*c == '.')
            out[n++] = '\\';
        out[n++] = *c;
    }
    out[n] = '\0';
}

static bool subscribe(hl_loop_t *l, char *why)
{
    static const hl_chan_t inputs[] = { HL_CH_DESTINATION, HL_CH_COMMAND, HL_CH_SONAR,
                                        HL_CH_ODOMETRY };
    /* with a live robot the scans come from it: what it publishes is not read back */
    size_t n = l->p.robot ? 2 : sizeof inputs / sizeof inputs[0];
    for (size_t i = 0; i < n; i++) {
        hl_chan_t ch = inputs[i];
        char regex[2 * HL_BUS_CHANNEL_MAX];
        channel_regex(l->channel[ch], regex, sizeof regex);
        l->subs[ch] = (sub_ctx_t){ l, ch };
        lcm_subscription_t *sub = lcm_subscribe(l->in, regex, on_lcm, &l->subs[ch]);
        if (!sub)
            return WHY("cannot subscribe to %s", l->channel[ch]), false;
        lcm_subscription_set_queue_capacity(sub, l->p.queue);
    }
    return true;
}

static bool make_fds(hl_loop_t *l, char *why)
{
    sigset_t mask;
    sigemptyset(&mask);
    sigaddset(&mask, SIGTERM);
    sigaddset(&mask, SIGINT);
    sigaddset(&mask, SIGHUP);
    /* liblcm's own threads start later and inherit the mask, so signals come here only */
    if (sigprocmask(SIG_BLOCK, &mask, NULL) != 0)
        return WHY("sigprocmask: %s", strerror(errno)), false;
    signal(SIGPIPE, SIG_IGN);
    l->sfd = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
    l->tfd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
    if (l->sfd < 0 || l->tfd < 0)
        return WHY("signalfd/timerfd: %s", strerror(errno)), false;
    return true;
}

hl_loop_t *hl_loop_create(const hl_loop_params_t *p, char *why)
{
    hl_loop_t *l = calloc(1, sizeof *l);
    if (!l)
        return WHY("out of memory"), NULL;
    l->p = *p;
    l->sfd = l->tfd = -1;
    l->save_wake_us = INT64_MAX;
    for (int ch = 0; ch < HL_CH_COUNT; ch++)
        if (!hl_bus_channel(p->prefix, hl_chan_name((hl_chan_t)ch), l->channel[ch])) {
            WHY("bad channel prefix '%s'", p->prefix);
            goto err;
        }
    if (!make_fds(l, why))
        goto err;
    l->in = lcm_create(p->in_url);
    if (!l->in) {
        WHY("cannot open LCM at '%s' (for udpm: is there a multicast route? for file: does "
            "the log exist?)", p->in_url);
        goto err;
    }
    l->out = strcmp(p->out_url, p->in_url) == 0 ? l->in : lcm_create(p->out_url);
    if (!l->out) {
        WHY("cannot open LCM output at '%s'", p->out_url);
        goto err;
    }
    if (!subscribe(l, why))
        goto err;
    return l;
err:
    hl_loop_destroy(l);
    return NULL;
}

void hl_loop_destroy(hl_loop_t *l)
{
    if (!l)
        return;
    if (l->out && l->out != l->in)
        lcm_destroy(l->out);
    if (l->in)
        lcm_destroy(l->in);
    if (l->sfd >= 0)
        close(l->sfd);
    if (l->tfd >= 0)
        close(l->tfd);
    free(l);
}

/* ---- timers: a fixed table, the timerfd armed for the earliest ------------------------ */

static void arm_timer(hl_loop_t *l)
{
    int64_t next = INT64_MAX;
    for (int i = 0; i < N_TIMERS; i++)
        if (l->period[i] > 0 && l->due[i] < next)
            next = l->due[i];
    if (l->save_wake_us < next)
        next = l->save_wake_us;
    struct itimerspec its = { 0 };
    if (next != INT64_MAX) {
        its.it_value.tv_sec = next / 1000000;
        its.it_value.tv_nsec = (long)(next % 1000000) * 1000;
        if (its.it_value.tv_sec == 0 && its.it_value.tv_nsec == 0)
            its.it_value.tv_nsec = 1;   /* zero would disarm it */
    }
    timerfd_settime(l->tfd, TFD_TIMER_ABSTIME, &its, NULL);
}

static void run_timers(hl_loop_t *l)
{
    uint64_t expirations;
    while (read(l->tfd, &expirations, sizeof expirations) > 0)
        ;
    int64_t now = mono_us();
    for (int i = 0; i < N_TIMERS; i++) {
        if (l->period[i] <= 0 || now < l->due[i])
            continue;
        /* the next due time keeps the period's phase, skipping missed ones */
        l->due[i] += ((now - l->due[i]) / l->period[i] + 1) * l->period[i];
        if (i == TIMER_STATUS)
            hl_cycle_tick(l->cycle, now);
        else if (i == TIMER_ROBOT)
            hl_robot_tick(l->robot, now / 1000);
        else
            sd_notify(0, "WATCHDOG=1");
    }
    arm_timer(l);
}

static void start_timers(hl_loop_t *l)
{
    int64_t now = mono_us();
    l->period[TIMER_STATUS] = (int64_t)l->p.status_period_ms * 1000;
    uint64_t watchdog_us = 0;
    if (sd_watchdog_enabled(0, &watchdog_us) > 0 && watchdog_us > 0)
        l->period[TIMER_WATCHDOG] = (int64_t)watchdog_us / 2;  /* as systemd advises */
    if (l->robot)
        l->period[TIMER_ROBOT] = ROBOT_TICK_MS * 1000;
    for (int i = 0; i < N_TIMERS; i++)
        l->due[i] = now + l->period[i];
    arm_timer(l);
}

/* ---- saving and signals -------------------------------------------------------------- */

/* A save: written, or answered as unchanged, or (@p may_wait: a SAVE request inside the
 * least interval between writes, cycle_save.c) left to wait for the interval's end. */
static bool save(hl_loop_t *l, hl_cycle_t *cycle, bool may_wait)
{
    hl_mapfile_t m;
    char why[HL_MAPSTORE_WHY_LEN];
    hl_cycle_snapshot(cycle, &m);
    /* Only a map that changed since it was loaded or last saved is written (maplock.h:
     * which fields count and why); a SAVE request's own seq does not count. */
    int64_t request = hl_cycle_save_request(cycle);
    if (!hl_maplock_changed(&m, request != 0 && request == m.last_request_seq)) {
        /* a request flood asks this many times a second: logged only when debugging */
        hl_log(may_wait ? HL_LOG_DEBUG : HL_LOG_INFO,
               "map %s unchanged since the last save: not written", l->p.map_path);
        hl_cycle_save_unchanged(cycle);
        return true;
    }
    if (may_wait) {
        hl_cycle_save_wait(cycle);
        return true;
    }
    bool ok = hl_mapstore_save(l->p.map_path, &m, why) == HL_OK;
    if (ok) {
        hl_maplock_saved(&m);
        hl_log(HL_LOG_DEBUG, "map saved to %s (%u vectors)", l->p.map_path, m.count);
    } else {
        hl_log(HL_LOG_ERR, "%s", why);
    }
    hl_cycle_saved(cycle, ok, why);
    return ok;
}

bool hl_loop_save(hl_loop_t *l, hl_cycle_t *cycle)
{
    return save(l, cycle, false);
}

/* The save the cycle says is due, if any; the timer follows a SAVE request left waiting. */
static void save_when_due(hl_loop_t *l, hl_cycle_t *cycle)
{
    if (hl_cycle_save_due(cycle))
        save(l, cycle, hl_cycle_save_may_wait(cycle));
    int64_t wake = hl_cycle_save_wake_us(cycle);
    if (wake != l->save_wake_us) {
        l->save_wake_us = wake;
        arm_timer(l);
    }
}

static void on_signal(hl_loop_t *l)
{
    struct signalfd_siginfo si;
    while (read(l->sfd, &si, sizeof si) == (ssize_t)sizeof si) {
        if (si.ssi_signo == SIGHUP) {
            hl_log(HL_LOG_NOTICE, "SIGHUP: saving the map");
            hl_loop_save(l, l->cycle);
        } else {
            hl_log(HL_LOG_NOTICE, "%s: stopping", si.ssi_signo == SIGTERM ? "SIGTERM" : "SIGINT");
            l->stop = true;
        }
    }
}

/* One readable event on the LCM fd: exactly one lcm_handle (liblcm's own rule). */
static void on_lcm_readable(hl_loop_t *l)
{
    if (lcm_handle(l->in) == 0)
        return;
    if (l->p.batch) {
        l->input_ended = true;      /* the log provider's way of saying "end of file" */
        hl_log(HL_LOG_INFO, "end of the replayed log");
    } else {
        hl_log(HL_LOG_ERR, "LCM stopped delivering messages (lcm_handle failed)");
        hl_cycle_note_error(l->cycle, "LCM stopped delivering messages");
        l->faulted = true;
    }
}

int hl_loop_run(hl_loop_t *l, hl_cycle_t *cycle)
{
    l->cycle = cycle;
    start_timers(l);
    struct pollfd fds[4] = {
        { .fd = lcm_get_fileno(l->in), .events = POLLIN },
        { .fd = l->tfd, .events = POLLIN },
        { .fd = l->sfd, .events = POLLIN },
        { .fd = -1 },               /* the robot link, when connected */
    };
    while (!l->stop && !l->input_ended && !l->faulted) {
        fds[3].fd = l->robot ? hl_robot_fd(l->robot) : -1;
        fds[3].events = l->robot ? hl_robot_events(l->robot) : 0;
        fds[3].revents = 0;
        if (poll(fds, 4, -1) < 0) {
            if (errno == EINTR)
                continue;
            hl_log(HL_LOG_ERR, "poll: %s", strerror(errno));
            l->faulted = true;
            break;
        }
        if (fds[2].revents & POLLIN)
            on_signal(l);
        if (fds[0].revents & (POLLIN | POLLHUP | POLLERR))
            on_lcm_readable(l);
        if (fds[3].fd >= 0 && fds[3].revents)
            hl_robot_on_ready(l->robot, fds[3].revents, mono_us() / 1000);
        save_when_due(l, cycle);
        if (fds[1].revents & POLLIN)
            run_timers(l);
        if (l->robot && hl_robot_replay_ended(l->robot)) {
            l->input_ended = true;      /* a replayed capture's end, as a replayed log's */
            l->faulted = hl_robot_replay_ended(l->robot) < 0;
        }
    }
    sd_notify(0, "STOPPING=1");
    if (l->robot)
        hl_robot_stop(l->robot, mono_us() / 1000);
    int8_t state = l->faulted ? HL_BUS_STATE_FAULT : HL_BUS_STATE_STOPPING;
    hl_cycle_set_state(cycle, state, mono_us());
    hl_cycle_flush_map(cycle);
    bool saved = hl_loop_save(l, cycle);
    hl_cycle_set_state(cycle, state, mono_us());   /* the last STATUS counts the save */
    return l->faulted || !saved ? 1 : 0;
}
