/*
 * robot.h - the live robot: houghlocd's side of the robot link. It owns the byte stream
 * (link.h) and runs the ARCOS connection (rlink.h), the rotating sounding (sounder.h) and
 * the drive to a destination (drive.h), and turns what the robot reports into the same
 * SONAR and ODOMETRY messages a replay would carry: each is published (so lcm-logger
 * records everything a replay needs) and handed to the cycle, exactly as the loop hands
 * it messages from LCM. A replay of the log therefore gives the same POSE stream.
 *
 * Time: link timeouts run on the wall clock; sounding and driving on robot time, counted
 * from the robot's own packets (one SIP per 100 ms), so they scale with a simulated
 * robot that runs faster than real time. With a lockstep simulator (lockstep, arcos.h's
 * STEP) the daemon also sets that pace: each SIP is answered with STEP once it has been
 * dealt with, and while the robot is idle (no destination, no sounding, at rest) the
 * daemon holds the clock, so that a run is the same on an idle and on a busy machine.
 *
 * Driving: each destination is planned on the robot's own map (robot_nav.c, plan.h) and
 * driven leg by leg, replanned after each sounding; the sonar readings of each SIP feed
 * the safety stop (safety.h, drive.h). STOP (hl_robot_halt) stops the base at once. A lost link is retried with a doubling backoff;
 * the map and the pose are kept, and the odometry is re-anchored on reconnection so a
 * robot whose odometry restarted at zero does not jump. A file link (a recorded stream)
 * has no wall-clock timeouts and no second try: its end ends the daemon
 * (hl_robot_replay_ended).
 */
#ifndef HOUGHLOC_DAEMON_ROBOT_H
#define HOUGHLOC_DAEMON_ROBOT_H

#include <stdbool.h>
#include <stdint.h>

#include "cycle.h"
#include "houghloc/arcos.h"
#include "houghloc/drive.h"
#include "houghloc/rlink.h"
#include "houghloc/sounder.h"
#include "link.h"

typedef struct hl_robot_params {
    hl_link_spec_t link;
    hl_robot_profile_t profile;
    hl_sounder_params_t sounder;
    hl_drive_params_t drive;
    hl_rlink_params_t rlink;
    hl_arcos_conv_t conv;           /* the base's units */
    int32_t reconnect_max_ms;       /* longest wait between connection attempts */
    bool sound_on_connect;          /* sound once when the link first comes up */
    int32_t lost_soundings;         /* soundings made standing still when the daemon is
                                       lost, before it gives up relocalizing */
    int32_t radius_mm;              /* the robot's body: the planner keeps its centre this
                                       far from walls, the safety stop watches this wide */
    bool lockstep;                  /* the robot is houghloc-sim --lockstep: answer each
                                       SIP with STEP, hold the clock while idle */
} hl_robot_params_t;

typedef struct hl_robot hl_robot_t;

/** @return NULL on invalid parameters or no memory. Nothing is opened yet: the first
 *  hl_robot_tick connects. */
hl_robot_t *hl_robot_create(const hl_robot_params_t *p, hl_cycle_t *cycle,
                            const hl_cycle_io_t *io);
void hl_robot_destroy(hl_robot_t *r);   /* accepts NULL */

/** The fd to poll (-1 while there is no connection) and the events to poll it for. */
int hl_robot_fd(const hl_robot_t *r);
short hl_robot_events(const hl_robot_t *r);

/** The fd is ready with @p revents. @p now_ms: the monotonic clock. */
void hl_robot_on_ready(hl_robot_t *r, short revents, int64_t now_ms);

/** Periodic (every 50 ms or so): connects, reconnects, keeps the ARCOS connection alive. */
void hl_robot_tick(hl_robot_t *r, int64_t now_ms);

/** A destination the cycle admitted (authentic, fresh, inside the fence); the robot
 *  answers it on REPLY: ACCEPTED, then ARRIVED or FAILED; NO_ROBOT when the link is down. */
void hl_robot_destination(hl_robot_t *r, const hl_bus_destination_t *d, int64_t now_ms);

/** STOP (request @p seq): the base stops at once and stays still; the sounding and any
 *  destination are given up (FAILED). The robot moves again for the next destination
 *  (or a RELOCALIZE's soundings). Nothing happens when the link is down. */
void hl_robot_halt(hl_robot_t *r, int64_t seq, int64_t now_ms);

/** A replayed capture (robot.link = file:CAPTURE) has ended: the daemon stops as at the
 *  end of a replayed log. @return 0 while it goes on (or for a live link), 1 at the end
 *  of the capture, -1 when the capture could not be opened. */
int hl_robot_replay_ended(const hl_robot_t *r);

/** At shutdown: stops the base, ends the ARCOS connection, closes the link. */
void hl_robot_stop(hl_robot_t *r, int64_t now_ms);

#endif
