/*
 * goto.c - houghloc-goto: sends the robot to a destination through houghlocd.
 *
 * One DESTINATION message (signed with --key), then the REPLY messages that carry its
 * seq: ACCEPTED, then ARRIVED or a refusal. While the robot is on its way, the daemon's
 * STATUS shows its progress, and each sign of it restarts the --timeout wait. A daemon
 * whose robot link is not up yet (NO_ROBOT), or that is not listening yet, is asked again
 * within --timeout; Ctrl-C (SIGINT, SIGTERM) sends STOP before exiting, so the robot does
 * not drive on unwatched. Sending and waiting are in request.c (shared with houghloc-ctl),
 * the command line in goto_args.c.
 */
#include <math.h>

#include "goto_args.h"
#include "houghloc/fixed.h"
#include "request.h"

int main(int argc, char **argv)
{
    goto_options_t o = { .req = REQ_OPTIONS_DEFAULT };
    int rc = goto_parse_args(argc, argv, &o);
    if (rc != WAITING)
        return rc;

    req_request_t r = { .kind = REQ_DESTINATION, .accepted_ends = o.no_wait,
                        .follow_progress = !o.no_wait, .wait_for_robot = true,
                        .stop_on_signal = !o.no_wait,
                        .accepted_text = "the robot is on its way" };
    r.msg.destination = (hl_bus_destination_t){
        .x_mm = (int32_t)lround(o.pos[0] * 1000.0),
        .y_mm = (int32_t)lround(o.pos[1] * 1000.0),
        .has_heading = o.npos == 3,
        .heading = o.npos == 3 ? hl_bam_from_deg(fmod(o.pos[2], 360.0)) : 0,
    };
    return req_run(PROG, &o.req, &r);
}
