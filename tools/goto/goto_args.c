/* goto_args.c - houghloc-goto's command line: --help, options, X Y [HEADING]. */
#include "goto_args.h"

#include <string.h>


static const char usage_text[] =
    "Usage: " PROG " [options] X Y [HEADING]\n"
    "\n"
    "Sends the robot to (X, Y) through houghlocd and waits until it arrives. The daemon\n"
    "plans the way on its map and drives round what it knows; a destination with no way\n"
    "is refused (FAILED). Ctrl-C (SIGINT or SIGTERM) while waiting sends STOP: the robot\n"
    "stops, and the destination is given up.\n"
    "X and Y are metres in the map frame, within +-4194.304 m. HEADING is the heading\n"
    "to arrive with, in degrees counter-clockwise from the map's +x axis (any finite\n"
    "value; 370 is 10); without it the robot arrives with any heading. Negative numbers\n"
    "need no '--': " PROG " -1.5 2 -90.\n"
    "\n"
    "Options:\n"
    "  --lcm-url URL  the LCM network (default $LCM_DEFAULT_URL, else\n"
    "                 " REQ_DEFAULT_URL ")\n"
    "  --prefix P     the daemon's channel prefix (default none: DESTINATION, REPLY)\n"
    "  --key FILE     sign the request with the key in FILE (64 hexadecimal digits,\n"
    "                 mode 600), as a daemon configured with a key requires;\n"
    "                 unsigned otherwise\n"
    "  --timeout S    the longest silence, 0.1 to 3600 seconds (default 10): the wait\n"
    "                 for the first answer (a daemon that is starting, or whose robot\n"
    "                 link is not up yet, is asked again meanwhile), then, while the\n"
    "                 robot is on its way, for\n"
    "                 the next sign of progress in the daemon's STATUS (once a second:\n"
    "                 this destination under way, the robot moved, turned or sounded)\n"
    "  --deadline S   the longest whole wait, 0.1 to 86400 seconds (default none)\n"
    "  --no-wait      exit 0 as soon as the daemon accepts the destination (Ctrl-C then\n"
    "                 sends no STOP)\n"
    "  --help         this text\n"
    "  --version      the version\n"
    "\n"
    "Each answer of the daemon is one line, e.g. \"" PROG ": ACCEPTED: <message>\";\n"
    "ACCEPTED and ARRIVED go to standard output, everything else to standard error.\n"
    "\n"
    "Examples:\n"
    "  " PROG " 2.5 -1\n"
    "      go to (2.5 m, -1 m), arriving with any heading\n"
    "  " PROG " --key /etc/houghloc/key 3 4 90\n"
    "      go to (3 m, 4 m) and face +y, with a signed request\n"
    "  " PROG " --prefix robot1/ --no-wait 0 0\n"
    "      send robot1's daemon to the origin; exit once it accepts\n"
    "  " PROG " --deadline 300 -12 7.25 180\n"
    "      give up (exit 6) unless the robot arrives within 5 minutes\n"
    "\n"
    "Exit status:\n"
    "  0  the robot arrived (with --no-wait: the destination was accepted)\n"
    "  1  error: LCM could not start, the key file was refused, ...\n"
    "  2  bad usage\n"
    "  3  rejected: outside the geofence (REJECTED_FENCE), missing or wrong MAC\n"
    "     (REJECTED_AUTH), seq not above the last one (REJECTED_REPLAY), a field out\n"
    "     of range (REJECTED_INVALID)\n"
    "  4  no robot is connected to the daemon (NO_ROBOT) within --timeout\n"
    "  5  the daemon could not do it (FAILED)\n"
    "  6  no answer within --timeout, no sign of progress for --timeout once\n"
    "     under way, or no ARRIVED within --deadline\n"
    "  130, 143  interrupted by SIGINT or SIGTERM; STOP was sent\n";

static const char *const pos_names[3] = { "X", "Y", "HEADING" };

/* X, Y or HEADING. @return WAITING, or EXIT_USAGE after the message. */
static int add_positional(goto_options_t *o, const char *arg)
{
    if (o->npos == 3)
        return req_usage_error(PROG, "too many arguments at \"%s\" (expected X Y [HEADING])",
                               arg);
    int rc = req_parse_value(PROG, pos_names[o->npos], arg, o->npos < 2, &o->pos[o->npos]);
    if (rc == WAITING)
        o->npos++;
    return rc;
}

static int on_positional(void *user, const char *arg)
{
    return add_positional(user, arg);
}

static int on_option(void *user, const char *arg)
{
    goto_options_t *o = user;
    if (strcmp(arg, "--no-wait") != 0)
        return REQ_NOT_MINE;
    o->no_wait = true;
    return WAITING;
}

int goto_parse_args(int argc, char **argv, goto_options_t *o)
{
    const req_args_t args = { .prog = PROG, .usage = usage_text, .positional = on_positional,
                              .option = on_option, .user = o };
    int rc = req_walk_args(&args, argc, argv, &o->req);
    if (rc != WAITING)
        return rc;
    if (o->npos == 0)
        return req_usage_error(PROG, "missing X and Y");
    if (o->npos == 1)
        return req_usage_error(PROG, "missing Y");
    return WAITING;
}
