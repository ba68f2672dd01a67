/* ctl_args.c - houghloc-ctl's command line: --help, options, COMMAND [ARGS]. */
#include "ctl_args.h"

#include <string.h>


static const char usage_text[] =
    "Usage: " CTL_PROG " [options] COMMAND [ARGS]\n"
    "\n"
    "Sends one command to houghlocd and waits for its answer.\n"
    "\n"
    "Commands:\n"
    "  set-pose X Y HEADING\n"
    "      the robot is at (X, Y), facing HEADING (an operator placed it by hand):\n"
    "      the daemon moves its estimate there and keeps the map. X and Y are\n"
    "      metres in the map frame, within +-4194.304 m; HEADING is degrees\n"
    "      counter-clockwise from the map's +x axis (any finite value; 370 is 10).\n"
    "      Negative numbers need no '--': " CTL_PROG " set-pose -1.5 2 -90.\n"
    "  save\n"
    "      save the map file now; answered once the file is written\n"
    "  relocalize\n"
    "      forget the pose: the daemon is LOST, and its next scans search the whole\n"
    "      map until one finds the robot and the next confirms it (STATUS shows\n"
    "      LOST until then; a robot stands still and sounds three times)\n"
    "  stop\n"
    "      stop the robot at once and give up its destination (and a sounding); it\n"
    "      stays still until the next destination. Never refused: no --key needed\n"
    "\n"
    "Options:\n"
    "  --lcm-url URL  the LCM network (default $LCM_DEFAULT_URL, else\n"
    "                 " REQ_DEFAULT_URL ")\n"
    "  --prefix P     the daemon's channel prefix (default none: COMMAND, REPLY)\n"
    "  --key FILE     sign the request with the key in FILE (64 hexadecimal digits,\n"
    "                 mode 600), as a daemon configured with a key requires;\n"
    "                 unsigned otherwise\n"
    "  --timeout S    seconds to wait for the answer, 0.1 to 3600 (default 10)\n"
    "  --help         this text\n"
    "  --version      the version\n"
    "\n"
    "The daemon's answer is one line, e.g. \"" CTL_PROG ": ACCEPTED: map saved\";\n"
    "ACCEPTED goes to standard output, everything else to standard error.\n"
    "\n"
    "Examples:\n"
    "  " CTL_PROG " set-pose 2.5 -1 90\n"
    "      the robot stands at (2.5 m, -1 m), facing +y\n"
    "  " CTL_PROG " --key /etc/houghloc/key save\n"
    "      save the map now, with a signed request\n"
    "  " CTL_PROG " --prefix robot1/ set-pose 0 0 0\n"
    "      robot1 is back at the origin of its map, facing +x\n"
    "  " CTL_PROG " --timeout 30 relocalize\n"
    "      ask the daemon to find the robot on the whole map\n"
    "  " CTL_PROG " stop\n"
    "      stop the robot now\n"
    "\n"
    "Exit status:\n"
    "  0  done: the daemon accepted the command (save: the map file is written)\n"
    "  1  error: LCM could not start, the key file was refused, ...\n"
    "  2  bad usage\n"
    "  3  rejected: missing or wrong MAC (REJECTED_AUTH), seq not above the last one\n"
    "     (REJECTED_REPLAY), a field out of range (REJECTED_INVALID)\n"
    "  4  no robot is connected to the daemon (NO_ROBOT)\n"
    "  5  the daemon could not do it (FAILED): a save that failed\n"
    "  6  no answer within the timeout\n";

typedef struct command {
    const char *name;
    int8_t kind;
    int nargs;
    const char *accepted_text;  /* for an ACCEPTED that comes without a message */
} command_t;

static const command_t commands[] = {
    { "set-pose", HL_BUS_COMMAND_SET_POSE, 3, "pose set; map kept" },
    { "save", HL_BUS_COMMAND_SAVE, 0, "map saved" },
    { "relocalize", HL_BUS_COMMAND_RELOCALIZE, 0, "relocalizing" },
    { "stop", HL_BUS_COMMAND_STOP, 0, "stopped" },
};
#define NCOMMANDS ((int)(sizeof commands / sizeof commands[0]))
#define COMMAND_LIST "set-pose, save, relocalize or stop"

static const char *const arg_names[3] = { "X", "Y", "HEADING" };
static const char *const missing[3] = { "X, Y and HEADING", "Y and HEADING", "HEADING" };

/* The command word, then its arguments. @return WAITING, or EXIT_USAGE after the message. */
static int add_positional(ctl_options_t *o, const command_t **cmd, const char *arg)
{
    if (!*cmd) {
        for (int k = 0; k < NCOMMANDS; k++)
            if (strcmp(arg, commands[k].name) == 0)
                *cmd = &commands[k];
        if (!*cmd)
            return req_usage_error(CTL_PROG, "unknown command \"%s\" (expected " COMMAND_LIST
                                             ")", arg);
        o->kind = (*cmd)->kind;
        o->accepted_text = (*cmd)->accepted_text;
        return WAITING;
    }
    if (o->nargs == (*cmd)->nargs) {
        if ((*cmd)->nargs == 0)
            return req_usage_error(CTL_PROG, "too many arguments at \"%s\" (%s takes none)",
                                   arg, (*cmd)->name);
        return req_usage_error(CTL_PROG, "too many arguments at \"%s\" (expected %s X Y "
                                         "HEADING)", arg, (*cmd)->name);
    }
    int rc = req_parse_value(CTL_PROG, arg_names[o->nargs], arg, o->nargs < 2,
                             &o->args[o->nargs]);
    if (rc == WAITING)
        o->nargs++;
    return rc;
}

typedef struct walk {
    ctl_options_t *o;
    const command_t *cmd;
} walk_t;

static int on_positional(void *user, const char *arg)
{
    walk_t *w = user;
    return add_positional(w->o, &w->cmd, arg);
}

/* houghloc-goto's --deadline bounds a trip; a command's one answer has --timeout. */
static int on_option(void *user, const char *arg)
{
    (void)user;
    if (strncmp(arg, "--deadline", 10) == 0 && (arg[10] == '\0' || arg[10] == '='))
        return req_usage_error(CTL_PROG, "unknown option \"%s\" (a command's answer is "
                               "bounded by --timeout)", arg);
    return REQ_NOT_MINE;
}

int ctl_parse_args(int argc, char **argv, ctl_options_t *o)
{
    walk_t w = { o, NULL };
    const req_args_t args = { .prog = CTL_PROG, .usage = usage_text,
                              .positional = on_positional, .option = on_option, .user = &w };
    int rc = req_walk_args(&args, argc, argv, &o->req);
    if (rc != WAITING)
        return rc;
    const command_t *cmd = w.cmd;
    if (!cmd)
        return req_usage_error(CTL_PROG, "missing COMMAND (" COMMAND_LIST ")");
    if (o->nargs < cmd->nargs)
        return req_usage_error(CTL_PROG, "%s: missing %s", cmd->name, missing[o->nargs]);
    return WAITING;
}
