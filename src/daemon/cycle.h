/*
 * cycle.h - the daemon's state machine: messages in -> localize -> integrate ->
 * messages out. It owns no file descriptor and reads no clock of its own: input arrives
 * as bytes with the channel they came on, output leaves through the emit callback, and
 * wall-clock time (for STATUS, compute times and the idle state) comes from the caller.
 * Everything published on POSE and MAP is a function of the input messages and the
 * parameters only, so a replay reproduces it byte for byte.
 *
 * Saving the map is file I/O, so the cycle only says when a save is due
 * (hl_cycle_save_due), lends its state for it (hl_cycle_snapshot) and is told the outcome
 * (hl_cycle_saved), which answers a pending SAVE request. SAVE requests write the map at
 * most once per HL_CYCLE_SAVE_MIN_INTERVAL_MS (cycle_save.c).
 */
#ifndef HOUGHLOC_DAEMON_CYCLE_H
#define HOUGHLOC_DAEMON_CYCLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/auth.h"
#include "houghloc/bus.h"
#include "fence.h"
#include "houghloc/slam.h"
#include "houghloc/mapstore.h"

typedef enum hl_chan {
    HL_CH_SONAR,            /* inputs */
    HL_CH_ODOMETRY,
    HL_CH_DESTINATION,
    HL_CH_COMMAND,
    HL_CH_POSE,             /* outputs */
    HL_CH_MAP,
    HL_CH_STATUS,
    HL_CH_REPLY,
    HL_CH_PATH,             /* the planned way to a destination (the robot's) */
    HL_CH_COUNT
} hl_chan_t;

/** The base name of a channel ("SONAR", ...). */
const char *hl_chan_name(hl_chan_t ch);

typedef struct hl_cycle_io {
    /** Publishes @p len bytes on @p ch. */
    void (*emit)(void *ctx, hl_chan_t ch, const void *data, size_t len);
    /** A monotonic clock in microseconds, read around each localization. */
    int64_t (*now_us)(void *ctx);
    /** A destination the cycle admitted (authentic, fresh, inside the fence), for the
     *  robot to answer on REPLY; NULL when no robot is attached: NO_ROBOT. */
    void (*destination)(void *ctx, const hl_bus_destination_t *d, int64_t now_us);
    /** STOP (request @p seq): stop the robot at once and cancel its destination; NULL
     *  when no robot is attached (the STOP is answered all the same). */
    void (*stop)(void *ctx, int64_t seq, int64_t now_us);
    /** The wall clock (CLOCK_REALTIME) in microseconds, which request seqs follow: a
     *  seq more than max_ahead_us ahead of it is refused. NULL: no such check. */
    int64_t (*wall_us)(void *ctx);
    /** Keeps @p seq, the highest request seq accepted, durably (the request state file,
     *  seqfile.h) before the request it belongs to is carried out; called only when
     *  requests are authenticated. @return false with one line in @p why (@p cap bytes):
     *  the request is then refused (FAILED) and the seq not taken. NULL: not kept. */
    bool (*keep_seq)(void *ctx, int64_t seq, char *why, size_t cap);
    void *ctx;
} hl_cycle_io_t;

/** The largest map_input_ratio: MAP bytes per byte of input. */
#define HL_CYCLE_MAP_RATIO_MAX 1000

typedef struct hl_cycle_params {
    hl_params_t params;         /* the tracker's (houghloc/params.h) */
    hl_pose_t start;            /* where the first scan is placed */
    hl_fence_t fence;           /* destinations must lie inside */
    bool authenticate;          /* requests must carry a MAC made with key, and every
                                   REPLY is signed with it */
    hl_auth_key_t key;
    char prefix[HL_BUS_PREFIX_MAX + 1];     /* the channel prefix, which every MAC covers */
    int64_t max_ahead_us;       /* a request seq further ahead of io.wall_us is refused,
                                   and a stored one clamped (auth.max_ahead_s); 0: none */
    int32_t save_every;         /* integrations between saves; 0 = only when asked */
    int32_t map_period_ms;      /* least message time between two MAP messages */
    int32_t map_input_ratio;    /* 0..HL_CYCLE_MAP_RATIO_MAX: after the first, a MAP goes
                                   out only once the SONAR and ODOMETRY bytes received
                                   since the previous one, times this, reach its size
                                   (cycle_map.c); 0 = no bound in bytes */
    int32_t idle_after_ms;      /* wall time without SONAR before the state is IDLE */
    int32_t compute_window;     /* scans in the compute-time statistics, 1..10000 */
} hl_cycle_params_t;

/** Counters, as STATUS reports them: 64-bit, stopping at HL_COUNT_MAX (count.h). */
typedef struct hl_cycle_counts {
    int64_t scans, accepted, rejected_wild, odometry_only, relocalized, lost;
    int64_t bad_messages, rejected_requests, saves;
    int64_t missed_scans;       /* SONAR seqs skipped: never seen (not in STATUS; logged) */
} hl_cycle_counts_t;

typedef struct hl_cycle hl_cycle_t;

/** @return NULL on invalid parameters or no memory (all memory is allocated here). */
hl_cycle_t *hl_cycle_create(const hl_cycle_params_t *p, const hl_cycle_io_t *io);
void hl_cycle_destroy(hl_cycle_t *c);    /* accepts NULL */

/**
 * Continues from a saved map file (mapstore.h). @return HL_OK, or HL_ERR_CAPACITY /
 * HL_ERR_RANGE when it does not fit these parameters; nothing changes on error.
 */
hl_status_t hl_cycle_restore(hl_cycle_t *c, const hl_mapfile_t *m);

/**
 * One message from outside, as received. Malformed or out-of-order input is counted,
 * logged once per kind of fault and otherwise ignored. @p now_us is the wall clock.
 */
void hl_cycle_on_message(hl_cycle_t *c, hl_chan_t ch, const void *data, size_t len,
                         int64_t now_us);

/** The periodic timer: STATUS, and LOCALIZING -> IDLE after idle_after_ms without SONAR. */
void hl_cycle_tick(hl_cycle_t *c, int64_t now_us);

/** Publishes STATUS now with @p state (HL_BUS_STATE_*) and remembers the state. */
void hl_cycle_set_state(hl_cycle_t *c, int8_t state, int64_t now_us);

/** Publishes a MAP whose change was held back by map_period_ms or map_input_ratio, if any
 *  (at shutdown: the last MAP of a run is the final map). */
void hl_cycle_flush_map(hl_cycle_t *c);

/** SAVE requests write the map file at most once in this much wall time: a write costs
 *  the whole file and two fsyncs, and a client asking many times a second must not hold
 *  up POSE; 5 s still answers an operator's SAVE within seconds. */
#define HL_CYCLE_SAVE_MIN_INTERVAL_MS 5000

/** Whether the map should be saved now (save_every reached, or a SAVE request: at once
 *  when it came, or at the end of the interval once it waits, hl_cycle_save_wait). */
bool hl_cycle_save_due(const hl_cycle_t *c);
/** A due save that is only a SAVE request's, inside HL_CYCLE_SAVE_MIN_INTERVAL_MS after
 *  the last write: a map unchanged since is answered (hl_cycle_save_unchanged), a changed
 *  one may wait (hl_cycle_save_wait) instead of being written now. */
bool hl_cycle_save_may_wait(const hl_cycle_t *c);
/** The request waits: due again (and answered once written) when the interval ends. */
void hl_cycle_save_wait(hl_cycle_t *c);
/** The wall-clock time (the io's clock) a waiting save falls due; INT64_MAX if none. */
int64_t hl_cycle_save_wake_us(const hl_cycle_t *c);
/**
 * Takes @p seq, the highest request seq a store kept (the request state file, or the map
 * file: hl_cycle_restore takes that one), as the last accepted one if it is above the
 * cycle's. One further ahead of io.wall_us than max_ahead_us is clamped to that bound
 * (logged, with @p from naming the store): nothing above it is accepted anyway, and a
 * far-ahead seq must not lock every client out for good.
 */
void hl_cycle_take_request_seq(hl_cycle_t *c, int64_t seq, const char *from);
/** The highest request seq accepted (or taken from a store), 0 when none. */
int64_t hl_cycle_request_seq(const hl_cycle_t *c);

/** Fills @p out with the state to save; out->vectors points into the cycle's map. */
void hl_cycle_snapshot(const hl_cycle_t *c, hl_mapfile_t *out);
/** The outcome of a save: answers a pending SAVE request and resets the count. */
void hl_cycle_saved(hl_cycle_t *c, bool ok, const char *why);
/** The seq of the SAVE request waiting for the next save, 0 when none. */
int64_t hl_cycle_save_request(const hl_cycle_t *c);
/** A due save that wrote nothing, the map file holding the state already: as
 *  hl_cycle_saved(c, true, ...), it answers a pending SAVE request (ACCEPTED, "map
 *  unchanged since the last save", with its age when this process wrote it) and resets
 *  the count, but it counts no save and does not start a new interval. */
void hl_cycle_save_unchanged(hl_cycle_t *c);

const hl_cycle_counts_t *hl_cycle_counts(const hl_cycle_t *c);

/* ---- for the live robot (robot.h), which feeds the cycle and answers destinations ---- */

/** The estimate now: the last pose moved by the odometry received since its scan. */
hl_pose_t hl_cycle_estimate(const hl_cycle_t *c);
/** The newest odometry pose the cycle knows (from a message, or a restored map's last
 *  scan). @return false when it knows none. */
bool hl_cycle_odometry(const hl_cycle_t *c, hl_pose_t *out);
/** Publishes a REPLY to request @p seq. */
void hl_cycle_answer(hl_cycle_t *c, int64_t seq, int8_t result, const char *message);
/** Where destinations may lie (cycle params' fence), for the robot's planner. */
const hl_fence_t *hl_cycle_fence(const hl_cycle_t *c);
/** The destination STATUS reports (-1: none). */
void hl_cycle_set_destination(hl_cycle_t *c, int64_t seq);
/** Robot packets dropped so far, as STATUS reports them. */
void hl_cycle_set_bad_packets(hl_cycle_t *c, int64_t n);
/** The last rejection or fault, one line ("" when none). */
const char *hl_cycle_last_error(const hl_cycle_t *c);
/** Records a fault from outside the cycle (STATUS's last_error). */
void hl_cycle_note_error(hl_cycle_t *c, const char *what);
hl_slam_t *hl_cycle_slam(hl_cycle_t *c);

/* ---- lost (cycle_lost.c) ---------------------------------------------------------------- */

/** Whether the pose is unknown: each scan searches the whole map (STATUS state LOST). */
bool hl_cycle_lost(const hl_cycle_t *c);
/** How many times the daemon became lost (the robot sounds again for each). */
uint32_t hl_cycle_lost_epoch(const hl_cycle_t *c);
/** Forgets the pose (a RELOCALIZE command): @p why is logged. */
void hl_cycle_enter_lost(hl_cycle_t *c, const char *why, int64_t now_us);
/** Stops relocalizing (the robot sounded as often as it may): tracking goes on from the
 *  current estimate, which the ambiguous scans kept following; @p why is logged. */
void hl_cycle_give_up_lost(hl_cycle_t *c, const char *why, int64_t now_us);

#endif
