/*
 * loop.h - houghlocd's event loop: one thread, one poll() over the LCM file descriptor,
 * a timerfd, a signalfd and, with a live robot, the robot link's fd. LCM messages go to
 * the cycle, one lcm_handle per readable event; timers publish STATUS, keep the robot
 * link alive and feed systemd's watchdog; SIGTERM and SIGINT stop the loop cleanly (the
 * robot is stopped first), SIGHUP saves the map.
 */
#ifndef HOUGHLOC_DAEMON_LOOP_H
#define HOUGHLOC_DAEMON_LOOP_H

#include <stdbool.h>

#include "config.h"
#include "cycle.h"
#include "robot.h"

typedef struct hl_loop hl_loop_t;

typedef struct hl_loop_params {
    const char *in_url;         /* LCM URL to listen on */
    const char *out_url;        /* LCM URL to publish on; may equal in_url */
    bool batch;                 /* in_url replays a log: exit at its end */
    const char *prefix;         /* channel prefix */
    int queue;                  /* liblcm queue per subscription */
    int status_period_ms;
    const char *map_path;       /* where to save */
    const char *state_path;     /* the request state file (seqfile.h), written on every
                                   accepted request; NULL: none (no key) */
    bool robot;                 /* a live robot will be attached: SONAR and ODOMETRY come
                                   from it, not from LCM, and it answers destinations */
} hl_loop_params_t;

/**
 * Opens LCM, subscribes, blocks the signals it handles and creates its fds. The cycle is
 * created by the caller with hl_loop_io as its io, so that it publishes through the loop.
 * @return NULL with a one-line reason in @p why (HL_CONFIG_WHY_LEN bytes).
 */
hl_loop_t *hl_loop_create(const hl_loop_params_t *p, char *why);
void hl_loop_destroy(hl_loop_t *l);     /* accepts NULL */

/** The io the cycle publishes and reads the clock through. */
hl_cycle_io_t hl_loop_io(hl_loop_t *l);

/** Attaches the live robot (params.robot): its fd joins the poll, its timer the loop's. */
void hl_loop_attach_robot(hl_loop_t *l, hl_robot_t *robot);

/** Runs until a signal or the end of a replayed log; saves the map on the way out.
 *  @return the process exit code: 0 after a clean stop, 1 after a fault. */
int hl_loop_run(hl_loop_t *l, hl_cycle_t *cycle);

/** Saves the map now through mapstore. @return true on success. */
bool hl_loop_save(hl_loop_t *l, hl_cycle_t *cycle);

#endif
