/*
 * latency.c - hl-eval latency: how long houghlocd took from each scan to its POSE, as two
 * recorders on the same host saw them (the save-flood trial, tools/lab/trials/
 * save_flood.sh). The input log records SONAR where the daemon reads it, the output log
 * POSE where it publishes; each event's time is the recorder's receipt time (lcm-logger's
 * wall clock), so a POSE's latency is its event time minus its scan's (paired by seq).
 * Unlike STATUS compute_p99_us, which starts at the SONAR handler, this also counts the
 * time a scan waited for the loop while it did something else (a save).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "latency.h"
#include "runlog.h"

#define MAX_SCANS HL_RUNLOG_MAX_STOPS

typedef struct pairs {
    int64_t *sent;              /* per scan seq: the SONAR's event time, 0 if unseen */
    int32_t max_seq;
    double *ms;                 /* the latencies found */
    size_t n, unanswered_pose;  /* POSE whose scan is not in the input */
} pairs_t;

static hl_bus_scan_t scan;      /* too big for the stack */

static bool on_input(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    pairs_t *p = user;
    if (!hl_runlog_is_channel(ev, HL_CHANNEL_SONAR))
        return true;
    if (hl_bus_decode_scan(ev->data, (size_t)ev->datalen, &scan, why) != HL_OK)
        return false;
    if (scan.seq < 0 || scan.seq >= MAX_SCANS)
        return snprintf(why, HL_BUS_WHY_LEN, "scan seq %d outside 0..%d", scan.seq,
                        MAX_SCANS - 1), false;
    if (!p->sent[scan.seq])
        p->sent[scan.seq] = ev->timestamp;
    if (scan.seq > p->max_seq)
        p->max_seq = scan.seq;
    return true;
}

static bool on_output(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    pairs_t *p = user;
    hl_bus_pose_t pose;
    if (!hl_runlog_is_channel(ev, HL_CHANNEL_POSE))
        return true;
    if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &pose, why) != HL_OK)
        return false;
    if (pose.scan_seq < 0 || pose.scan_seq >= MAX_SCANS || !p->sent[pose.scan_seq]) {
        p->unanswered_pose++;
        return true;
    }
    p->ms[p->n++] = (double)(ev->timestamp - p->sent[pose.scan_seq]) / 1000.0;
    p->sent[pose.scan_seq] = 0;     /* one POSE per scan */
    return true;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The p-th percentile (nearest rank) of the n sorted values. */
static double percentile(const double *v, size_t n, double p)
{
    size_t rank = (size_t)(p / 100.0 * (double)n + 0.999999);
    return v[rank == 0 ? 0 : rank - 1];
}

int hl_eval_latency(const char *prog, const char *in, const char *out)
{
    pairs_t p = { .sent = calloc(MAX_SCANS, sizeof *p.sent), .max_seq = -1,
                  .ms = calloc(MAX_SCANS, sizeof *p.ms) };
    int rc = 1;
    if (!p.sent || !p.ms) {
        fprintf(stderr, "%s: out of memory\n", prog);
        goto done;
    }
    if (hl_runlog_each_event(prog, in, on_input, &p) != 0 ||
        hl_runlog_each_event(prog, out, on_output, &p) != 0)
        goto done;
    if (p.n == 0) {
        fprintf(stderr, "%s: no POSE in %s answers a SONAR scan of %s\n", prog, out, in);
        goto done;
    }
    size_t scans = 0;
    for (int32_t s = 0; s <= p.max_seq; s++)
        scans += p.sent[s] != 0;    /* left: scans no POSE answered */
    qsort(p.ms, p.n, sizeof *p.ms, by_value);
    printf("latency poses=%zu p50_ms=%.1f p99_ms=%.1f max_ms=%.1f scans_unanswered=%zu "
           "poses_unpaired=%zu\n", p.n, percentile(p.ms, p.n, 50), percentile(p.ms, p.n, 99),
           p.ms[p.n - 1], scans, p.unanswered_pose);
    rc = 0;
done:
    free(p.sent);
    free(p.ms);
    return rc;
}
