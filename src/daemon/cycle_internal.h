/* cycle_internal.h - the cycle's state, shared by cycle.c and its parts cycle_*.c
 * only. */
#ifndef HOUGHLOC_DAEMON_CYCLE_INTERNAL_H
#define HOUGHLOC_DAEMON_CYCLE_INTERNAL_H

#include "cycle.h"

#define HL_CYCLE_MAX_FAULT_KINDS 32

struct hl_cycle {
    hl_cycle_params_t p;
    hl_cycle_io_t io;
    hl_slam_t *slam;
    hl_cycle_counts_t n;
    int8_t state;
    int64_t last_sonar_wall_us;     /* wall clock of the last scan, for IDLE */

    /* input order */
    bool have_scan, have_odometry;
    int32_t last_scan_seq;
    int64_t last_scan_utime, last_odometry_utime, newest_utime;
    hl_pose_t scan_odometry;        /* odometry of the last scan */
    hl_pose_t odometry;             /* newest odometry, from ODOMETRY or a scan */
    hl_pose_t first_odometry;       /* the first ODOMETRY: where the start pose stands */
    int64_t last_request_seq;       /* highest DESTINATION/COMMAND seq accepted */
    int64_t destination_seq;        /* current destination, -1 if none */
    int32_t bad_packets;            /* robot packets dropped, from the robot link */
    uint64_t scans_total;           /* over the map's life, saved with it */

    /* MAP publishing (cycle_map.c) */
    uint32_t published_version;
    bool map_published;
    int64_t map_published_utime, map_changed_utime;
    int64_t input_since_map;        /* SONAR and ODOMETRY bytes taken since the last MAP */
    uint8_t *map_buf;
    size_t map_buf_len;

    /* saving */
    int32_t since_save;
    bool save_requested;
    int64_t save_request_seq;       /* 0 when none */

    /* compute time per scan, the last compute_window of them */
    int32_t *compute_us, *compute_sorted;
    int32_t compute_n, compute_next;

    /* faults: each kind is logged once, the last is in STATUS */
    const char *fault_kinds[HL_CYCLE_MAX_FAULT_KINDS];
    int n_fault_kinds;
    char last_error[HL_BUS_TEXT_MAX];

    /* lost (cycle_lost.c) */
    bool lost;
    uint32_t lost_epoch;            /* times lost was entered */
    int32_t doubtful_run;           /* doubtful tracking scans in a row (hl_cycle_track) */
    int32_t accepted_run;           /* ... and well-matched ones while lost */
    bool have_candidate;            /* the global search found this, to be confirmed */
    hl_pose_t candidate, candidate_odometry;

    hl_bus_scan_t scan;             /* decode target: too big for the stack */
    uint8_t buf[HL_BUS_STATUS_MAX_BYTES + HL_BUS_REPLY_MAX_BYTES + HL_BUS_POSE_BYTES];
};

/** Counts a fault in @p counter (may be NULL), keeps @p what as the last error and logs it
 *  if no fault of the same @p kind (a constant string) was logged before. */
void hl_cycle_fault(hl_cycle_t *c, int32_t *counter, const char *kind, const char *what);

/** @return true when @p st is HL_OK; else counts a bad message on @p channel with the
 *  decoder's reason @p why, as a fault of @p kind. */
bool hl_cycle_decoded(hl_cycle_t *c, hl_status_t st, const char *channel, const char *kind,
                      const char *why);

void hl_cycle_on_destination(hl_cycle_t *c, const void *data, size_t len, int64_t now_us);
void hl_cycle_on_command(hl_cycle_t *c, const void *data, size_t len, int64_t now_us);
void hl_cycle_reply(hl_cycle_t *c, int64_t seq, int8_t result, const char *message);
void hl_cycle_publish_status(hl_cycle_t *c);
void hl_cycle_record_compute(hl_cycle_t *c, int64_t us);

/** Counts @p len bytes of SONAR or ODOMETRY taken (valid and in order) towards the next
 *  MAP's byte allowance (cycle_map.c). */
void hl_cycle_map_input(hl_cycle_t *c, size_t len);
/** Publishes MAP if the map changed and both bounds allow it (cycle_map.c). */
void hl_cycle_maybe_publish_map(hl_cycle_t *c);

/** Not lost, no candidate, no runs counted (the lost state's bookkeeping, cleared). */
void hl_cycle_clear_lost(hl_cycle_t *c);
/**
 * The ordinary cycle on one scan (hl_slam_update; a failure answers @p prediction).
 * @return true when the scan is doubtful: rejected, or accepted with a peak far below
 *         the recent ones (daemon.lost_peak_ratio).
 */
bool hl_cycle_track(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                    hl_slam_step_t *step);
/**
 * While tracking (daemon.search_every): the global search on this scan, and whether it
 * finds the robot somewhere else that explains the scan clearly better than where
 * tracking would put it. If so the daemon is lost with that candidate (to be confirmed by
 * the next scan), @p step holds it and @p found the search, and nothing was tracked.
 */
bool hl_cycle_kidnapped(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                        hl_slam_step_t *step, hl_reloc_result_t *found, int64_t now_us);
/**
 * One scan while lost (cycle_lost.c): confirms the candidate or searches the whole map.
 * @param prediction  the pose to publish when nothing is found.
 * @param tracked     this scan already went through hl_cycle_track (it made the daemon
 *                    lost), with its result in @p step: it is not tracked again.
 * @return the POSE status: HL_SLAM_ACCEPTED (tracking again), HL_BUS_POSE_RELOCALIZED
 *         (a candidate found) or HL_BUS_POSE_LOST; @p step holds the pose (and the local
 *         search of an accepted scan), @p found the search.
 */
int8_t hl_cycle_lost_scan(hl_cycle_t *c, const hl_bus_scan_t *in, hl_pose_t prediction,
                          bool tracked, hl_slam_step_t *step, hl_reloc_result_t *found,
                          int64_t now_us);

#endif
