/*
 * runlog.c - one record per scan from the logs of a houghlocd run (runlog.h).
 */
#include "runlog.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/logcheck.h"

int hl_runlog_each_event(const char *prog, const char *path, hl_runlog_event_fn fn,
                         void *user)
{
    char why[HL_LOG_WHY_LEN];
    if (hl_log_check(path, NULL, why) != HL_OK) {
        fprintf(stderr, "%s: %s\n", prog, why);
        return 1;
    }
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log) {
        fprintf(stderr, "%s: %s: %s\n", prog, path, strerror(errno));
        return 1;
    }
    int rc = 0;
    lcm_eventlog_event_t *ev;
    while (rc == 0 && (ev = lcm_eventlog_read_next_event(log)) != NULL) {
        char bwhy[HL_BUS_WHY_LEN] = "";
        if (!fn(user, ev, bwhy)) {
            fprintf(stderr, "%s: %s: event %lld on %.*s: %s\n", prog, path,
                    (long long)ev->eventnum, (int)ev->channellen, ev->channel, bwhy);
            rc = 1;
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    return rc;
}

bool hl_runlog_is_channel(const lcm_eventlog_event_t *ev, const char *name)
{
    return (size_t)ev->channellen == strlen(name) && memcmp(ev->channel, name, ev->channellen) == 0;
}

/* The stop with @p seq, appended if new. */
static hl_runlog_stop_t *stop_for(hl_runlog_t *r, int32_t seq)
{
    for (size_t i = r->n; i-- > 0;)     /* the newest first: logs come in order */
        if (r->stops[i].seq == seq)
            return &r->stops[i];
    if (r->n >= HL_RUNLOG_MAX_STOPS)
        return NULL;
    r->stops[r->n] = (hl_runlog_stop_t){ .seq = seq };
    return &r->stops[r->n++];
}

static void note_first_truth(hl_runlog_t *r, hl_pose_t truth)
{
    if (!r->has_first_truth) {
        r->first_truth = truth;
        r->has_first_truth = true;
    }
}

/* IN: scans (their time and odometry) and ground truth. */
static bool on_input(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    hl_runlog_t *r = user;
    if (hl_runlog_is_channel(ev, HL_CHANNEL_SONAR)) {
        static hl_bus_scan_t scan;  /* large: not on the stack */
        if (hl_bus_decode_scan(ev->data, (size_t)ev->datalen, &scan, why) != HL_OK)
            return false;
        hl_runlog_stop_t *s = stop_for(r, scan.seq);
        if (!s)
            return snprintf(why, HL_BUS_WHY_LEN, "more than %d scans", HL_RUNLOG_MAX_STOPS),
                   false;
        s->utime = scan.utime;
        s->odometry = scan.odometry;
        s->has_scan = true;
    } else if (hl_runlog_is_channel(ev, HL_CHANNEL_GROUND_TRUTH)) {
        hl_bus_pose_t p;
        if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &p, why) != HL_OK)
            return false;
        hl_runlog_stop_t *s = stop_for(r, p.scan_seq);
        if (!s)
            return snprintf(why, HL_BUS_WHY_LEN, "more than %d scans", HL_RUNLOG_MAX_STOPS),
                   false;
        s->truth = p.pose;
        s->has_truth = true;
        note_first_truth(r, p.pose);
    }
    return true;
}

/* OUT: the daemon's poses. */
static bool on_output(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    hl_runlog_t *r = user;
    if (!hl_runlog_is_channel(ev, HL_CHANNEL_POSE))
        return true;
    hl_bus_pose_t p;
    if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &p, why) != HL_OK)
        return false;
    for (size_t i = r->n; i-- > 0;) {
        hl_runlog_stop_t *s = &r->stops[i];
        if (s->seq == p.scan_seq) {
            if (s->has_pose)
                return snprintf(why, HL_BUS_WHY_LEN, "a second POSE for scan %d", p.scan_seq),
                       false;
            s->pose = p.pose;
            s->status = p.status;
            s->has_pose = true;
            return true;
        }
    }
    return snprintf(why, HL_BUS_WHY_LEN, "POSE for scan %d, which the input lacks", p.scan_seq),
           false;
}

int hl_runlog_load_input(hl_runlog_t *r, const char *path)
{
    r->n = 0;
    r->has_first_truth = false;
    r->stops = calloc(HL_RUNLOG_MAX_STOPS, sizeof *r->stops);
    if (!r->stops)
        return fprintf(stderr, "%s: out of memory\n", r->prog), 1;
    if (hl_runlog_each_event(r->prog, path, on_input, r) != 0)
        return 1;
    for (size_t i = 0; i < r->n; i++)
        if (r->stops[i].has_scan && r->stops[i].has_truth)
            return 0;
    fprintf(stderr, "%s: %s: no SONAR scan with a GROUND_TRUTH pose\n", r->prog, path);
    return 1;
}

/* A live run's one log: every scan takes the last GROUND_TRUTH before it (a robot stands
 * still while it sounds), and its POSE by seq. */
typedef struct live {
    hl_runlog_t *r;
    bool poses;                 /* take the POSE messages of this log too */
    hl_pose_t truth;
    bool has_truth;
} live_t;

static bool on_live(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    live_t *l = user;
    if (hl_runlog_is_channel(ev, HL_CHANNEL_GROUND_TRUTH)) {
        hl_bus_pose_t p;
        if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &p, why) != HL_OK)
            return false;
        l->truth = p.pose;
        l->has_truth = true;
        note_first_truth(l->r, p.pose);
        return true;
    }
    if (hl_runlog_is_channel(ev, HL_CHANNEL_POSE))
        return !l->poses || on_output(l->r, ev, why);
    if (!hl_runlog_is_channel(ev, HL_CHANNEL_SONAR))
        return true;
    size_t n = l->r->n;
    if (!on_input(l->r, ev, why))
        return false;
    if (l->r->n == n)
        return snprintf(why, HL_BUS_WHY_LEN, "a second SONAR scan with seq %d",
                        l->r->stops[n - 1].seq), false;
    l->r->stops[n].truth = l->truth;
    l->r->stops[n].has_truth = l->has_truth;
    return true;
}

int hl_runlog_load_live(hl_runlog_t *r, const char *path, bool poses)
{
    r->n = 0;
    r->has_first_truth = false;
    r->stops = calloc(HL_RUNLOG_MAX_STOPS, sizeof *r->stops);
    if (!r->stops)
        return fprintf(stderr, "%s: out of memory\n", r->prog), 1;
    live_t l = { .r = r, .poses = poses };
    return hl_runlog_each_event(r->prog, path, on_live, &l);
}

int hl_runlog_load_output(hl_runlog_t *r, const char *path)
{
    return hl_runlog_each_event(r->prog, path, on_output, r);
}

void hl_runlog_free(hl_runlog_t *r)
{
    free(r->stops);
    r->stops = NULL;
    r->n = 0;
}
