/* cycle.c - scans in, poses and maps out (see cycle.h; MAP's rate: cycle_map.c). */
#include "cycle_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

static const char *const chan_names[HL_CH_COUNT] = {
    [HL_CH_SONAR] = HL_CHANNEL_SONAR,       [HL_CH_ODOMETRY] = HL_CHANNEL_ODOMETRY,
    [HL_CH_DESTINATION] = HL_CHANNEL_DESTINATION, [HL_CH_COMMAND] = HL_CHANNEL_COMMAND,
    [HL_CH_POSE] = HL_CHANNEL_POSE,         [HL_CH_MAP] = HL_CHANNEL_MAP,
    [HL_CH_STATUS] = HL_CHANNEL_STATUS,     [HL_CH_REPLY] = HL_CHANNEL_REPLY,
    [HL_CH_PATH] = HL_CHANNEL_PATH,
};

const char *hl_chan_name(hl_chan_t ch)
{
    return ch < HL_CH_COUNT ? chan_names[ch] : "?";
}

hl_cycle_t *hl_cycle_create(const hl_cycle_params_t *p, const hl_cycle_io_t *io)
{
    if (!p || !io || !io->emit || !io->now_us || p->compute_window < 1 ||
        p->compute_window > 10000 || p->save_every < 0 || p->map_period_ms < 0 ||
        p->map_input_ratio < 0 || p->map_input_ratio > HL_CYCLE_MAP_RATIO_MAX ||
        !hl_pose_in_range(p->start) || p->max_ahead_us < 0 ||
        !memchr(p->prefix, '\0', sizeof p->prefix))
        return NULL;
    hl_cycle_t *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->p = *p;
    c->io = *io;
    c->slam = hl_slam_create(&p->params);
    c->map_buf_len = c->slam ? hl_bus_map_bytes(hl_map_capacity(hl_slam_map(c->slam))) : 0;
    c->map_buf = c->slam ? malloc(c->map_buf_len) : NULL;
    c->compute_us = calloc((size_t)p->compute_window, sizeof *c->compute_us);
    c->compute_sorted = calloc((size_t)p->compute_window, sizeof *c->compute_sorted);
    if (!c->slam || !c->map_buf || !c->compute_us || !c->compute_sorted) {
        hl_cycle_destroy(c);
        return NULL;
    }
    hl_slam_reset(c->slam, p->start);
    c->state = HL_BUS_STATE_STARTING;
    c->destination_seq = -1;
    hl_stream_init(&c->sonar_order, true);
    hl_stream_init(&c->odometry_order, false);
    c->published_version = hl_map_version(hl_slam_map(c->slam));
    return c;
}

void hl_cycle_destroy(hl_cycle_t *c)
{
    if (!c)
        return;
    hl_slam_destroy(c->slam);
    free(c->map_buf);
    free(c->compute_us);
    free(c->compute_sorted);
    free(c);
}

hl_status_t hl_cycle_restore(hl_cycle_t *c, const hl_mapfile_t *m)
{
    hl_status_t st = hl_slam_restore(c->slam, &m->state, m->vectors, m->count);
    if (st != HL_OK)
        return st;
    hl_cycle_take_request_seq(c, m->last_request_seq, "the map file");
    c->scans_total = m->scans;
    /* the first change after a restart is saved at once: a daemon killed again and again
     * before a save falls due would otherwise never write a newer file */
    c->since_save = c->p.save_every > 0 ? c->p.save_every - 1 : 0;
    /* kept for the next save; the order check starts with this process's first scan, so
     * a log replayed again on a kept map is not refused */
    c->last_scan_utime = m->last_scan_utime;
    /* the loaded map is what the daemon has; publish it with the first scan */
    c->published_version = m->state.map_version - 1;
    c->map_changed_utime = m->last_scan_utime;
    return HL_OK;
}

void hl_cycle_fault(hl_cycle_t *c, int64_t *counter, const char *kind, const char *what)
{
    if (counter)
        hl_count_add(counter, 1);
    snprintf(c->last_error, sizeof c->last_error, "%s", what);
    for (int i = 0; i < c->n_fault_kinds; i++)
        if (c->fault_kinds[i] == kind)
            return;
    if (c->n_fault_kinds < HL_CYCLE_MAX_FAULT_KINDS)
        c->fault_kinds[c->n_fault_kinds++] = kind;
    hl_log(HL_LOG_WARNING, "%s (further faults of this kind are not logged: %s)", what,
           counter ? "STATUS counts them" : "STATUS's last_error shows the latest");
}

bool hl_cycle_decoded(hl_cycle_t *c, hl_status_t st, const char *channel, const char *kind,
                      const char *why)
{
    if (st == HL_OK)
        return true;
    char what[HL_BUS_TEXT_MAX];
    snprintf(what, sizeof what, "%s: %s", channel, why);
    hl_cycle_fault(c, &c->n.bad_messages, kind, what);
    return false;
}

void hl_cycle_note_error(hl_cycle_t *c, const char *what)
{
    snprintf(c->last_error, sizeof c->last_error, "%s", what);
}

/* ---- SONAR and ODOMETRY ------------------------------------------------------------- */

static float share(uint32_t part, uint32_t whole)
{
    return whole ? (float)part / (float)whole : 0.0f;
}

/* POSE for one scan: the local search's figures when it was localized, the global
 * search's when it was searched. */
static void publish_pose(hl_cycle_t *c, const hl_bus_scan_t *in, const hl_slam_step_t *step)
{
    bool localized = step->status == HL_SLAM_ACCEPTED || step->status == HL_SLAM_REJECTED_WILD;
    bool searched = step->status == HL_SLAM_RELOCALIZED || step->status == HL_SLAM_LOST;
    const hl_reloc_result_t *found = &step->search;
    hl_bus_pose_t m = {
        .utime = in->utime, .scan_seq = in->seq, .pose = step->pose,
        .status = hl_bus_pose_status(step->status),
        .confidence = localized ? (float)hl_loc_confidence(&step->loc)
                    : searched ? (float)hl_reloc_confidence(found) : 0.0f,
        .peak = localized ? (int32_t)step->loc.peak : 0,
        .second_peak = localized ? (int32_t)step->loc.second : 0,
        .votes = localized ? (int32_t)step->loc.votes : 0,
    };
    if (searched) {
        m.search_score = share(found->score, found->readings);
        m.runner_up = found->runner_up;
        m.runner_up_score = share(found->runner_up_score, found->readings);
    }
    int len = hl_bus_encode_pose(&m, c->buf, sizeof c->buf);
    if (len > 0)
        c->io.emit(c->io.ctx, HL_CH_POSE, c->buf, (size_t)len);
}

/* The start pose is where the robot stood when the odometry began: a first scan made
 * after the base moved (a live robot turns while it sounds) is placed by that motion. */
static void place_first_scan(hl_cycle_t *c, hl_pose_t scan_odometry)
{
    hl_slam_state_t st;
    hl_slam_get_state(c->slam, &st);
    if (st.started || c->have_scan || !c->have_odometry)
        return;
    hl_pose_t first;
    if (hl_pose_predict(st.pose, c->first_odometry, scan_odometry, &first))
        hl_slam_reset(c->slam, first);
}

/* The time of the newest input, for REPLY and STATUS: the later of the two streams as
 * they stand, so that a stream re-synchronized back in time takes it back too. */
static void note_newest(hl_cycle_t *c)
{
    int64_t t = INT64_MIN;
    if (c->sonar_order.started)
        t = c->sonar_order.last.utime;
    if (c->odometry_order.started && c->odometry_order.last.utime > t)
        t = c->odometry_order.last.utime;
    c->newest_utime = t == INT64_MIN ? 0 : t;
}

static void on_sonar(hl_cycle_t *c, const void *data, size_t len, int64_t now_us)
{
    char why[HL_BUS_WHY_LEN], what[HL_BUS_TEXT_MAX];
    hl_bus_scan_t *in = &c->scan;
    int64_t t0 = c->io.now_us(c->io.ctx);  /* the cycle's latency: from here to POSE out */
    if (!hl_cycle_decoded(c, hl_bus_decode_scan(data, len, in, why), HL_CHANNEL_SONAR,
                          "sonar decode", why))
        return;
    hl_stream_verdict_t order = hl_stream_offer(&c->sonar_order,
                                                (hl_stream_mark_t){ in->seq, in->utime });
    if (order == HL_STREAM_HOLD) {
        snprintf(what, sizeof what, "SONAR: scan seq %d at %lld does not follow seq %d at "
                 "%lld: dropped (%d in order with each other re-synchronize)", in->seq,
                 (long long)in->utime, c->last_scan_seq, (long long)c->last_scan_utime,
                 HL_STREAM_CONFIRM);
        hl_cycle_fault(c, &c->n.bad_messages, "sonar order", what);
        return;
    }
    if (order == HL_STREAM_RESYNC) {
        snprintf(what, sizeof what, "SONAR: re-synchronized at scan seq %d at %lld (was seq "
                 "%d at %lld): a restarted source or a clock step", in->seq,
                 (long long)in->utime, c->last_scan_seq, (long long)c->last_scan_utime);
        hl_cycle_fault(c, NULL, "sonar resync", what);
    } else if (c->have_scan && in->seq - c->last_scan_seq > 1) {
        /* a scan never seen: a full input queue or a lost network packet */
        snprintf(what, sizeof what, "SONAR: %d scan(s) missed before seq %d (all are counted "
                 "in the last log line)", in->seq - c->last_scan_seq - 1, in->seq);
        hl_count_add(&c->n.missed_scans, (int64_t)in->seq - c->last_scan_seq - 1);
        hl_cycle_fault(c, NULL, "sonar gap", what);
    }
    place_first_scan(c, in->odometry);
    hl_cycle_map_input(c, len);
    c->have_scan = true;
    c->last_scan_seq = in->seq;
    c->last_scan_utime = in->utime;
    note_newest(c);
    c->last_sonar_wall_us = now_us;

    uint64_t version = hl_map_version(hl_slam_map(c->slam));
    hl_slam_step_t step;
    hl_status_t st = hl_slam_update(c->slam, &in->scan, in->odometry, &step);
    if (st != HL_OK) {
        /* the scan is answered with the prediction (slam.h) */
        snprintf(what, sizeof what, "SONAR: scan seq %d not localized: %s", in->seq,
                 hl_status_str(st));
        hl_cycle_fault(c, NULL, "sonar update", what);
    }
    hl_slam_status_t status = step.status;
    c->scan_odometry = in->odometry;
    if (!c->have_odometry || in->utime >= c->last_odometry_utime)
        c->odometry = in->odometry;
    hl_count_add(&c->n.scans, 1);
    c->scans_total = hl_count_next(c->scans_total);
    hl_count_add(&c->n.accepted, status == HL_SLAM_ACCEPTED);
    hl_count_add(&c->n.rejected_wild, status == HL_SLAM_REJECTED_WILD);
    hl_count_add(&c->n.odometry_only, status == HL_SLAM_ODOMETRY_ONLY);
    hl_count_add(&c->n.relocalized, status == HL_SLAM_RELOCALIZED);
    hl_count_add(&c->n.lost, status == HL_SLAM_LOST);
    publish_pose(c, in, &step);
    int64_t compute_us = c->io.now_us(c->io.ctx) - t0;
    hl_cycle_record_compute(c, compute_us);
    /* after its POSE: what the recovery did, logged (the state it causes: below) */
    hl_cycle_report_recovery(c, in, &step);
    bool changed = hl_map_version(hl_slam_map(c->slam)) != version;
    if (step.turned)    /* slam.long_drive_mm: the odometry's heading had drifted */
        hl_log(HL_LOG_INFO, "scan %llu (seq %d): after a long drive, the drive turned about "
               "its start fits better: (%.3f, %.3f) m, %.1f deg, %.0f mm from the odometry's",
               (unsigned long long)c->scans_total, in->seq, step.pose.x_mm / 1000.0,
               step.pose.y_mm / 1000.0, hl_bam_to_sdeg(step.pose.theta),
               hypot((double)step.pose.x_mm - step.predicted.x_mm,
                     (double)step.pose.y_mm - step.predicted.y_mm));
    if (hl_log_enabled(HL_LOG_DEBUG)) {
        static const char *const names[] = {
            [HL_SLAM_ACCEPTED] = "ACCEPTED", [HL_SLAM_REJECTED_WILD] = "REJECTED_WILD",
            [HL_SLAM_ODOMETRY_ONLY] = "ODOMETRY_ONLY", [HL_SLAM_RELOCALIZED] = "RELOCALIZED",
            [HL_SLAM_LOST] = "LOST" };
        /* "changed": the scan went into the map, and counts towards daemon.save_every */
        /* "loops": matches with earlier stops (slam.close_loops): every stop was fitted
         * again and the map drawn again with them; then the scan's compute time, as
         * STATUS's statistics count it */
        hl_log(HL_LOG_DEBUG, "scan %llu (seq %d): %s at (%.3f, %.3f) m, %.1f deg; map %u%s; "
               "loops %u; %lld us",
               (unsigned long long)c->scans_total, in->seq, names[status],
               step.pose.x_mm / 1000.0, step.pose.y_mm / 1000.0, hl_bam_to_sdeg(step.pose.theta),
               hl_map_count(hl_slam_map(c->slam)), changed ? ", changed" : "", step.loops,
               (long long)compute_us);
    }

    if (changed) {
        c->map_changed_utime = in->utime;
        c->since_save++;
    }
    hl_cycle_maybe_publish_map(c);
    hl_cycle_scan_state(c, now_us);
}

static void on_odometry(hl_cycle_t *c, const void *data, size_t len)
{
    char why[HL_BUS_WHY_LEN], what[HL_BUS_TEXT_MAX];
    hl_bus_odometry_t o;
    if (!hl_cycle_decoded(c, hl_bus_decode_odometry(data, len, &o, why), HL_CHANNEL_ODOMETRY,
                          "odometry decode", why))
        return;
    hl_stream_verdict_t order = hl_stream_offer(&c->odometry_order,
                                                (hl_stream_mark_t){ 0, o.utime });
    if (order == HL_STREAM_HOLD) {
        snprintf(what, sizeof what, "ODOMETRY: time %lld does not follow %lld: dropped (%d in "
                 "order with each other re-synchronize)", (long long)o.utime,
                 (long long)c->last_odometry_utime, HL_STREAM_CONFIRM);
        hl_cycle_fault(c, &c->n.bad_messages, "odometry order", what);
        return;
    }
    if (order == HL_STREAM_RESYNC) {
        snprintf(what, sizeof what, "ODOMETRY: re-synchronized at time %lld (was %lld): a "
                 "restarted source or a clock step", (long long)o.utime,
                 (long long)c->last_odometry_utime);
        hl_cycle_fault(c, NULL, "odometry resync", what);
    }
    if (!c->have_odometry)
        c->first_odometry = o.pose;
    hl_cycle_map_input(c, len);
    c->have_odometry = true;
    c->last_odometry_utime = o.utime;
    note_newest(c);
    if (!c->have_scan || o.utime >= c->last_scan_utime)
        c->odometry = o.pose;
}

void hl_cycle_on_message(hl_cycle_t *c, hl_chan_t ch, const void *data, size_t len,
                         int64_t now_us)
{
    switch (ch) {
    case HL_CH_SONAR: on_sonar(c, data, len, now_us); break;
    case HL_CH_ODOMETRY: on_odometry(c, data, len); break;
    case HL_CH_DESTINATION: hl_cycle_on_destination(c, data, len, now_us); break;
    case HL_CH_COMMAND: hl_cycle_on_command(c, data, len, now_us); break;
    default: break;     /* outputs are not inputs */
    }
}

/* ---- saving (when: cycle_save.c) ------------------------------------------------------ */

void hl_cycle_snapshot(const hl_cycle_t *c, hl_mapfile_t *out)
{
    hl_map_t *map = hl_slam_map(c->slam);
    *out = (hl_mapfile_t){
        .capacity = hl_map_capacity(map), .count = hl_map_count(map),
        .vectors = (hl_vector_t *)hl_map_vectors(map),
        .last_request_seq = c->last_request_seq, .last_scan_utime = c->last_scan_utime,
        .scans = c->scans_total,
    };
    hl_slam_get_state(c->slam, &out->state);
}

const hl_cycle_counts_t *hl_cycle_counts(const hl_cycle_t *c)
{
    return &c->n;
}

const char *hl_cycle_last_error(const hl_cycle_t *c)
{
    return c->last_error;
}

hl_slam_t *hl_cycle_slam(hl_cycle_t *c)
{
    return c->slam;
}
