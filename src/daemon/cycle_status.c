/* cycle_status.c - STATUS: the state, the counters, the current estimate and the compute
 * time statistics. Not part of the reproducible output (it reads the wall clock). */
#include <string.h>

#include "cycle_internal.h"
#include "log.h"

void hl_cycle_record_compute(hl_cycle_t *c, int64_t us)
{
    if (us < 0)
        us = 0;
    c->compute_us[c->compute_next] = us > INT32_MAX ? INT32_MAX : (int32_t)us;
    c->compute_next = (c->compute_next + 1) % c->p.compute_window;
    if (c->compute_n < c->p.compute_window)
        c->compute_n++;
}

/* Shell sort in place: glibc's qsort may allocate for large arrays, and nothing after
 * start-up may (the window is at most 10000 values, sorted once a second). */
static void sort_i32(int32_t *v, int32_t n)
{
    for (int32_t gap = n / 2; gap > 0; gap = gap == 2 ? 1 : gap * 5 / 11) {
        for (int32_t i = gap; i < n; i++) {
            int32_t x = v[i], j = i;
            for (; j >= gap && v[j - gap] > x; j -= gap)
                v[j] = v[j - gap];
            v[j] = x;
        }
    }
}

/* Nearest-rank percentile of the window (p in 1..100). */
static int32_t percentile(const int32_t *sorted, int32_t n, int p)
{
    int32_t rank = (int32_t)(((int64_t)p * n + 99) / 100);    /* ceil(p/100 * n) */
    return sorted[rank < 1 ? 0 : rank - 1];
}

hl_pose_t hl_cycle_estimate(const hl_cycle_t *c)
{
    hl_pose_t est = hl_slam_pose(c->slam);
    if (c->have_scan)
        hl_pose_predict(est, c->scan_odometry, c->odometry, &est);
    return est;
}

void hl_cycle_publish_status(hl_cycle_t *c)
{
    hl_map_t *map = hl_slam_map(c->slam);
    hl_bus_status_t s = {
        .utime = c->newest_utime, .state = c->state, .destination_seq = c->destination_seq,
        .scans = c->n.scans, .accepted = c->n.accepted, .rejected_wild = c->n.rejected_wild,
        .odometry_only = c->n.odometry_only, .relocalized = c->n.relocalized,
        .lost = c->n.lost, .bad_messages = c->n.bad_messages,
        .rejected_requests = c->n.rejected_requests,
        .map_vectors = (int32_t)hl_map_count(map), .map_version = (int64_t)hl_map_version(map),
        .saves = c->n.saves, .pose = hl_cycle_estimate(c),
        .bad_packets = c->bad_packets, .compute_samples = c->compute_n,
    };
    if (c->compute_n > 0) {
        memcpy(c->compute_sorted, c->compute_us, (size_t)c->compute_n * sizeof(int32_t));
        sort_i32(c->compute_sorted, c->compute_n);
        s.compute_median_us = percentile(c->compute_sorted, c->compute_n, 50);
        s.compute_p99_us = percentile(c->compute_sorted, c->compute_n, 99);
    }
    memcpy(s.last_error, c->last_error, sizeof s.last_error);
    int len = hl_bus_encode_status(&s, c->buf, sizeof c->buf);
    if (len > 0)
        c->io.emit(c->io.ctx, HL_CH_STATUS, c->buf, (size_t)len);
}

static const char *state_name(int8_t state)
{
    static const char *const names[] = { "STARTING", "SOUNDING", "LOCALIZING", "MOVING",
                                         "IDLE", "FAULT", "STOPPING", "LOST" };
    return state >= 0 && state <= HL_BUS_STATE_LOST ? names[state] : "?";
}

void hl_cycle_set_state(hl_cycle_t *c, int8_t state, int64_t now_us)
{
    (void)now_us;
    /* lost outranks what the robot is doing; a fault or the way out outranks lost */
    if (hl_slam_lost(c->slam) && state != HL_BUS_STATE_FAULT && state != HL_BUS_STATE_STOPPING)
        state = HL_BUS_STATE_LOST;
    if (state != c->state)
        hl_log(HL_LOG_INFO, "state %s -> %s", state_name(c->state), state_name(state));
    c->state = state;
    hl_cycle_publish_status(c);
}

bool hl_cycle_odometry(const hl_cycle_t *c, hl_pose_t *out)
{
    if (c->have_scan || c->have_odometry) {
        *out = c->odometry;
        return true;
    }
    hl_slam_state_t st;
    hl_slam_get_state(c->slam, &st);
    *out = st.odom;
    return st.started;
}

const hl_fence_t *hl_cycle_fence(const hl_cycle_t *c)
{
    return &c->p.fence;
}

void hl_cycle_set_destination(hl_cycle_t *c, int64_t seq)
{
    c->destination_seq = seq;
}

void hl_cycle_set_bad_packets(hl_cycle_t *c, int64_t n)
{
    c->bad_packets = n;
}

void hl_cycle_tick(hl_cycle_t *c, int64_t now_us)
{
    if (c->state == HL_BUS_STATE_LOCALIZING &&
        now_us - c->last_sonar_wall_us >= (int64_t)c->p.idle_after_ms * 1000) {
        hl_cycle_set_state(c, HL_BUS_STATE_IDLE, now_us);
        return;
    }
    hl_cycle_publish_status(c);
}
