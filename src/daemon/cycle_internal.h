/* cycle_internal.h - the cycle's state, shared by cycle.c and its parts cycle_*.c
 * only. */
#ifndef HOUGHLOC_DAEMON_CYCLE_INTERNAL_H
#define HOUGHLOC_DAEMON_CYCLE_INTERNAL_H

#include "cycle.h"
#include "stream.h"

#define HL_CYCLE_MAX_FAULT_KINDS 32

struct hl_cycle {
    hl_cycle_params_t p;
    hl_cycle_io_t io;
    hl_slam_t *slam;
    hl_cycle_counts_t n;
    int8_t state;
    int64_t last_sonar_wall_us;     /* wall clock of the last scan, for IDLE */

    /* input order: each stream's, and what the cycle took last */
    hl_stream_t sonar_order, odometry_order;
    bool have_scan, have_odometry;
    int32_t last_scan_seq;
    int64_t last_scan_utime, last_odometry_utime, newest_utime;
    hl_pose_t scan_odometry;        /* odometry of the last scan */
    hl_pose_t odometry;             /* newest odometry, from ODOMETRY or a scan */
    hl_pose_t first_odometry;       /* the first ODOMETRY: where the start pose stands */
    int64_t last_request_seq;       /* highest DESTINATION/COMMAND seq accepted */
    int64_t destination_seq;        /* current destination, -1 if none */
    int64_t bad_packets;            /* robot packets dropped, from the robot link */
    uint64_t scans_total;           /* over the map's life, saved with it */

    /* MAP publishing (cycle_map.c) */
    uint64_t published_version;
    bool map_published;
    int64_t map_published_utime, map_changed_utime;
    int64_t input_since_map;        /* SONAR and ODOMETRY bytes taken since the last MAP */
    uint8_t *map_buf;
    size_t map_buf_len;

    /* saving (cycle_save.c) */
    int32_t since_save;
    bool save_requested;
    int64_t save_request_seq;       /* 0 when none */
    bool saved_once;                /* this process wrote the map file (last_save_us) */
    int64_t last_save_us;           /* wall clock of the last write, to rate SAVE requests */
    bool save_waiting;              /* the SAVE request waits for the interval's end */

    /* compute time per scan, the last compute_window of them */
    int32_t *compute_us, *compute_sorted;
    int32_t compute_n, compute_next;

    /* faults: each kind is logged once, the last is in STATUS */
    const char *fault_kinds[HL_CYCLE_MAX_FAULT_KINDS];
    int n_fault_kinds;
    char last_error[HL_BUS_TEXT_MAX];

    hl_bus_scan_t scan;             /* decode target: too big for the stack */
    uint8_t buf[HL_BUS_STATUS_MAX_BYTES + HL_BUS_REPLY_MAX_BYTES + HL_BUS_POSE_BYTES];
};

/** Counts a fault in @p counter (may be NULL; stops at HL_COUNT_MAX), keeps @p what as
 *  the last error and logs it if no fault of the same @p kind (a constant string) was
 *  logged before. */
void hl_cycle_fault(hl_cycle_t *c, int64_t *counter, const char *kind, const char *what);

/** @return true when @p st is HL_OK; else counts a bad message on @p channel with the
 *  decoder's reason @p why, as a fault of @p kind. */
bool hl_cycle_decoded(hl_cycle_t *c, hl_status_t st, const char *channel, const char *kind,
                      const char *why);

void hl_cycle_on_destination(hl_cycle_t *c, const void *data, size_t len, int64_t now_us);
void hl_cycle_on_command(hl_cycle_t *c, const void *data, size_t len, int64_t now_us);
/** An admitted SAVE request (cycle_save.c): the one waiting before it is superseded. */
void hl_cycle_on_save(hl_cycle_t *c, int64_t seq);
void hl_cycle_reply(hl_cycle_t *c, int64_t seq, int8_t result, const char *message);
void hl_cycle_publish_status(hl_cycle_t *c);
void hl_cycle_record_compute(hl_cycle_t *c, int64_t us);

/** Counts @p len bytes of SONAR or ODOMETRY taken (valid and in order) towards the next
 *  MAP's byte allowance (cycle_map.c). */
void hl_cycle_map_input(hl_cycle_t *c, size_t len);
/** Publishes MAP if the map changed and both bounds allow it (cycle_map.c). */
void hl_cycle_maybe_publish_map(hl_cycle_t *c);

/** What the tracker's recovery did with scan @p in (hl_slam_update's @p step), after its
 *  POSE: each change of the lost state logged, and kept as STATUS's last error
 *  (cycle_lost.c). It publishes nothing: the state follows (hl_cycle_scan_state). */
void hl_cycle_report_recovery(hl_cycle_t *c, const hl_bus_scan_t *in,
                              const hl_slam_step_t *step);
/** The state a scan leaves, derived here alone: LOST while the tracker is lost, else
 *  LOCALIZING; STATUS is published when it changed. Called last in a scan's handling,
 *  after its POSE (cycle_lost.c). */
void hl_cycle_scan_state(hl_cycle_t *c, int64_t now_us);

#endif
