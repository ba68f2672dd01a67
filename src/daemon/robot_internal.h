/* robot_internal.h - the live robot's state, shared by robot.c (what the robot does:
 * soundings, destinations, its packets) and robot_link.c (the connection). */
#ifndef HOUGHLOC_DAEMON_ROBOT_INTERNAL_H
#define HOUGHLOC_DAEMON_ROBOT_INTERNAL_H

#include "houghloc/plan.h"
#include "robot.h"

#define SIP_PERIOD_MS 100           /* ARCOS's standard SIP cycle: robot time per SIP */
#define FIRST_BACKOFF_MS 250

struct hl_robot {
    hl_robot_params_t p;
    hl_cycle_t *cycle;
    hl_cycle_io_t io;

    hl_link_t *link;
    hl_rlink_t rlink;
    bool up;                        /* the ARCOS connection was UP at the last check */
    int64_t retry_at_ms, backoff_ms;
    char last_fault[HL_LINK_WHY_LEN];   /* logged once until it changes */
    int replay_end;                 /* hl_robot_replay_ended's answer */

    hl_sounder_t sounder;
    hl_drive_t drive;
    int64_t dest_seq;               /* the destination being driven to, -1 if none */
    bool dest_pending;              /* accepted during a sounding: starts after it */
    hl_bus_destination_t pending;
    bool sounded_once;
    bool moved_unseen;              /* the link fell silent while the robot was under way
                                       (a leg or a sounding): where it stopped is unknown */
    uint32_t lost_epoch;            /* the cycle's lost epoch that lost_soundings counts */
    int32_t lost_soundings;         /* soundings made for it */

    /* odometry: unwrapped robot units -> the robot's frame -> the published frame */
    hl_arcos_odom_t odom;
    bool anchored;                  /* offset set since this connection began */
    hl_pose_t offset;               /* published = offset o robot */
    bool have_published;
    hl_pose_t published;            /* last published odometry pose */
    hl_drive_in_t last_in;          /* the last SIP, as the drive sees it */

    /* lockstep (robot.lockstep) */
    bool step_owed;                 /* a SIP was dealt with and no STEP sent for it yet */
    /* STOP: still until the next destination, or a new lost epoch's soundings */
    bool halted;
    uint32_t halted_epoch;

    /* navigation (robot_nav.c) */
    hl_planner_t *planner;
    hl_mm_t block_x, block_y;       /* where the reading that stopped the leg lies (map) */
    int32_t blocks_logged;          /* the drive's safety stops logged so far */
    bool polling_ahead;             /* the sonar fires the front transducers alone */

    int64_t robot_ms;               /* robot time: SIP_PERIOD_MS per SIP */
    int64_t epoch_us;               /* utime of robot time 0 (the wall clock at start) */
    int32_t scan_seq;
    uint64_t bad_reported;

    hl_bus_scan_t msg;              /* too big for the stack */
    uint8_t buf[HL_BUS_SCAN_MAX_BYTES];
};

/* robot.c */
typedef struct robot_sip_ctx {
    hl_robot_t *r;
    int64_t now_ms;
} robot_sip_ctx_t;

/** One SIP of the ARCOS connection (an hl_rlink_sip_fn; ctx is a robot_sip_ctx_t). */
void robot_on_sip(void *ctx, const hl_arcos_sip_t *sip);
/** The ARCOS connection is up: re-anchor the odometry; sound once if asked. */
void robot_link_up(hl_robot_t *r, int64_t now_ms);
/** Gives up the sounding and any destination (pending or under way) with @p why. */
void robot_abandon(hl_robot_t *r, const char *why, int64_t now_ms);
/** Publishes STATUS with @p state and the destination under way. */
void robot_set_state(hl_robot_t *r, int8_t state, int64_t now_ms);
/** Queues a command for the base (logged when it cannot be sent). */
void robot_command(hl_robot_t *r, uint8_t number, bool has_arg, int32_t arg, int64_t now_ms);
/** Whether the robot has something to do: a destination, a sounding, or it still moves
 *  (a lockstep clock runs only then). */
bool robot_busy(const hl_robot_t *r);

/* robot_link.c */
/** Writes what the ARCOS connection has queued (and a lockstep STEP when due) now. */
void robot_flush(hl_robot_t *r, int64_t now_ms);

/* robot_nav.c */
bool robot_nav_create(hl_robot_t *r);
void robot_nav_destroy(hl_robot_t *r);
/** Plans from the estimate to the destination under way (@p goal_x, @p goal_y), aims the
 *  drive's next leg at the way's first corner and publishes PATH. @return false with one
 *  line in @p why when there is no way. */
bool robot_nav_plan(hl_robot_t *r, int32_t goal_x, int32_t goal_y, char *why, size_t cap);
/** The destination has ended: an empty PATH, the safety stops' obstacles forgotten. */
void robot_nav_end(hl_robot_t *r);
/** The nearest reading of @p sip in the way ahead, mm (0: none); where it lies is kept
 *  for robot_nav_blocked. */
int32_t robot_nav_ahead(hl_robot_t *r, const hl_arcos_sip_t *sip);
/** The last leg was stopped by the safety stop: its reading becomes an obstacle. */
void robot_nav_blocked(hl_robot_t *r);
/** The sonar's firing order (POLLING): @p ahead, the front transducers alone, the ones
 *  nearest ahead twice (while a leg is driven: the safety stop hears ahead about every
 *  0.15 s instead of every 0.6 s); else the whole ring (a sounding needs a fresh reading
 *  of every transducer at each step). Sent only when it changes. */
void robot_nav_polling(hl_robot_t *r, bool ahead, int64_t now_ms);

#endif
