/*
 * runlog.h - reads the LCM logs of one houghlocd run into one record per scan, for the
 * offline tools (hl-eval, houghloc-eval, houghloc-map).
 *
 * The daemon's input log gives each scan's time and odometry (SONAR) and its true pose
 * (GROUND_TRUTH, matched by scan_seq); its output log gives the POSE it published for
 * the scan (matched by scan_seq too). Every log is checked with hl_log_check before
 * liblcm reads it, because liblcm trusts the length fields it finds.
 *
 * Errors are printed here, as one line on stderr that starts with the program's name
 * and names the file (and the event, for a message that does not decode), so a caller
 * only passes the exit status on.
 */
#ifndef HOUGHLOC_TOOLS_RUNLOG_H
#define HOUGHLOC_TOOLS_RUNLOG_H

#include <lcm/eventlog.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "houghloc/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HL_RUNLOG_MAX_STOPS 100000

/** One scan of a run: what the input and the output logs say about it. */
typedef struct hl_runlog_stop {
    int32_t seq;
    int64_t utime;              /* the SONAR scan's time (has_scan) */
    hl_pose_t truth;            /* GROUND_TRUTH (has_truth) */
    hl_pose_t odometry;         /* the scan's odometry, odometry frame (has_scan) */
    hl_pose_t pose;             /* the daemon's POSE (has_pose) */
    int8_t status;              /* that POSE's HL_SLAM_* status (has_pose) */
    bool has_truth, has_scan, has_pose;
} hl_runlog_stop_t;

/** The scans of a run in the order the input log first names them. */
typedef struct hl_runlog {
    const char *prog;           /* the program's name, first on every error line */
    hl_runlog_stop_t *stops;    /* HL_RUNLOG_MAX_STOPS entries, n of them used */
    size_t n;
    hl_pose_t first_truth;      /* the log's first GROUND_TRUTH (has_first_truth): where
                                   the robot stood when the run began */
    bool has_first_truth;
} hl_runlog_t;

/**
 * Called for each event of a log. Return false to stop, after writing a one-line
 * reason into @p why (HL_BUS_WHY_LEN bytes).
 */
typedef bool (*hl_runlog_event_fn)(void *user, const lcm_eventlog_event_t *ev, char *why);

/**
 * Checks the log at @p path with hl_log_check, then hands every event to @p fn in order.
 * @return 0, or 1 after printing "PROG: ..." (the check's reason, the open error, or
 *         "PATH: event N on CHANNEL: WHY" when @p fn stopped).
 */
int hl_runlog_each_event(const char *prog, const char *path, hl_runlog_event_fn fn,
                         void *user);

/** Whether the event is on exactly the channel @p name. */
bool hl_runlog_is_channel(const lcm_eventlog_event_t *ev, const char *name);

/**
 * Reads the SONAR scans and GROUND_TRUTH poses of the input log @p path into @p r
 * (r->prog set by the caller; r->stops allocated here, freed by hl_runlog_free).
 * @return 0, or 1 after printing why: the log is bad, a message does not decode, more
 *         than HL_RUNLOG_MAX_STOPS scans, out of memory, or no SONAR scan has a
 *         GROUND_TRUTH pose.
 */
int hl_runlog_load_input(hl_runlog_t *r, const char *path);

/**
 * Adds the POSE messages of the daemon's output log @p path to the scans of @p r.
 * @return 0, or 1 after printing why: the log is bad, a POSE does not decode, a second
 *         POSE for a scan, or a POSE for a scan the input lacks.
 */
int hl_runlog_load_output(hl_runlog_t *r, const char *path);

/**
 * Reads the one log of a live run (lcm-logger on the daemon and a simulated robot):
 * SONAR and POSE as above, and for each scan the last GROUND_TRUTH logged before it (the
 * simulated robot publishes its true pose with every packet, and stands still while it
 * sounds). With @p poses false the log's POSE messages are left out (a replay's output,
 * read with hl_runlog_load_output, gives them). Allocates r->stops like
 * hl_runlog_load_input.
 * @return 0, or 1 after printing why.
 */
int hl_runlog_load_live(hl_runlog_t *r, const char *path, bool poses);

/** Frees r->stops. Accepts a run that never loaded. */
void hl_runlog_free(hl_runlog_t *r);

#ifdef __cplusplus
}
#endif
#endif
