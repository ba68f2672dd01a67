/*
 * support.h - what the daemon tests share: the simulated tour's messages read once from
 * logs/tour.lcmlog (or $HL_TOUR_LOG), and a cycle whose output is captured in memory and
 * whose clock is a counter the test controls.
 */
#ifndef HOUGHLOC_TESTS_DAEMON_SUPPORT_H
#define HOUGHLOC_TESTS_DAEMON_SUPPORT_H

#include <lcm/eventlog.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cycle.h"

#define MAX_EVENTS 8192
#define MAX_OUT 4096

typedef struct event {
    hl_chan_t ch;
    uint8_t *data;
    size_t len;
    int64_t utime;
} event_t;

/* The tour's SONAR and ODOMETRY messages, in log order. */
static event_t tour[MAX_EVENTS];
static size_t n_tour;

static inline void load_tour(void)
{
    if (n_tour)
        return;
    const char *path = getenv("HL_TOUR_LOG") ? getenv("HL_TOUR_LOG") : "logs/tour.lcmlog";
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log)
        abort();
    lcm_eventlog_event_t *ev;
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL && n_tour < MAX_EVENTS) {
        hl_chan_t ch = HL_CH_COUNT;
        if (ev->channellen == 5 && memcmp(ev->channel, "SONAR", 5) == 0)
            ch = HL_CH_SONAR;
        else if (ev->channellen == 8 && memcmp(ev->channel, "ODOMETRY", 8) == 0)
            ch = HL_CH_ODOMETRY;
        if (ch != HL_CH_COUNT) {
            event_t *e = &tour[n_tour++];
            e->ch = ch;
            e->len = (size_t)ev->datalen;
            e->data = malloc(e->len);
            memcpy(e->data, ev->data, e->len);
            e->utime = ev->timestamp;
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
}

/* Captured output. */
typedef struct out_msg {
    hl_chan_t ch;
    uint8_t *data;
    size_t len;
} out_msg_t;

typedef struct capture {
    out_msg_t msgs[MAX_OUT];
    size_t n;
    int64_t clock_us;           /* the fake monotonic clock */
    int64_t clock_step_us;      /* added on every read */
} capture_t;

static inline void capture_emit(void *ctx, hl_chan_t ch, const void *data, size_t len)
{
    capture_t *c = ctx;
    if (c->n >= MAX_OUT)
        abort();
    out_msg_t *m = &c->msgs[c->n++];
    m->ch = ch;
    m->len = len;
    m->data = malloc(len);
    memcpy(m->data, data, len);
}

static inline int64_t capture_clock(void *ctx)
{
    capture_t *c = ctx;
    c->clock_us += c->clock_step_us;
    return c->clock_us;
}

static inline void capture_clear(capture_t *c)
{
    for (size_t i = 0; i < c->n; i++)
        free(c->msgs[i].data);
    c->n = 0;
}

static inline size_t capture_count(const capture_t *c, hl_chan_t ch)
{
    size_t n = 0;
    for (size_t i = 0; i < c->n; i++)
        n += c->msgs[i].ch == ch;
    return n;
}

/* The k-th captured message on ch, or NULL. */
static inline const out_msg_t *capture_nth(const capture_t *c, hl_chan_t ch, size_t k)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->msgs[i].ch == ch && k-- == 0)
            return &c->msgs[i];
    return NULL;
}

static inline hl_cycle_params_t test_params(void)
{
    hl_cycle_params_t p = { .save_every = 0, .map_period_ms = 0, .idle_after_ms = 5000,
                            .compute_window = 100 };
    /* the tracker alone: the LOST state's tests turn it on (test_cycle_lost.c) */
    hl_params_default(&p.params);
    assert_int_equal(hl_params_set(&p.params, "slam.lost_after", "0"), HL_OK);
    assert_int_equal(hl_params_set(&p.params, "slam.search_every", "0"), HL_OK);
    hl_fence_rect(&p.fence, -10000, -10000, 10000, 10000);
    return p;
}

static inline hl_cycle_t *capture_cycle(capture_t *cap, const hl_cycle_params_t *p)
{
    hl_cycle_io_t io = { .emit = capture_emit, .now_us = capture_clock, .ctx = cap };
    return hl_cycle_create(p, &io);
}

/* Feeds the tour's first @p n_scans scans (and the odometry between them). */
static inline void feed_tour(hl_cycle_t *c, size_t n_scans)
{
    load_tour();
    size_t scans = 0;
    for (size_t i = 0; i < n_tour && scans < n_scans; i++) {
        hl_cycle_on_message(c, tour[i].ch, tour[i].data, tour[i].len, tour[i].utime);
        scans += tour[i].ch == HL_CH_SONAR;
    }
}

#endif
