/*
 * ctl.c - houghloc-ctl: sends one COMMAND to houghlocd (set-pose, save, relocalize, stop) and
 * waits for the REPLY that carries its seq.
 *
 * Sending and waiting are in request.c (shared with houghloc-goto), the command line in
 * ctl_args.c. ACCEPTED is the end of a command: SET_POSE is done when accepted, SAVE is
 * answered only once the map file is written.
 */
#include <math.h>

#include "ctl_args.h"
#include "houghloc/fixed.h"
#include "request.h"

int main(int argc, char **argv)
{
    ctl_options_t o = { .req = REQ_OPTIONS_DEFAULT };
    int rc = ctl_parse_args(argc, argv, &o);
    if (rc != WAITING)
        return rc;

    req_request_t r = { .kind = REQ_COMMAND, .accepted_ends = true,
                        .accepted_text = o.accepted_text };
    /* Every kind carries a pose, checked by the daemon: zeros unless SET_POSE. */
    r.msg.command = (hl_bus_command_t){ .kind = o.kind };
    if (o.kind == HL_BUS_COMMAND_SET_POSE)
        r.msg.command.pose = (hl_pose_t){
            .x_mm = (int32_t)lround(o.args[0] * 1000.0),
            .y_mm = (int32_t)lround(o.args[1] * 1000.0),
            .theta = hl_bam_from_deg(fmod(o.args[2], 360.0)),
        };
    return req_run(CTL_PROG, &o.req, &r);
}
