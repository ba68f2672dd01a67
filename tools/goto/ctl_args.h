/* ctl_args.h - houghloc-ctl's command line (private to tools/goto; the exit codes and the
 * options it shares with houghloc-goto are in request.h). */
#ifndef HOUGHLOC_TOOLS_CTL_ARGS_H
#define HOUGHLOC_TOOLS_CTL_ARGS_H

#include <stdint.h>

#include "request.h"

#define CTL_PROG "houghloc-ctl"

typedef struct ctl_options {
    req_options_t req;      /* --lcm-url, --prefix, --key, --timeout */
    int8_t kind;            /* HL_BUS_COMMAND_* once parsed */
    const char *accepted_text;  /* what ACCEPTED means for this command */
    int nargs;              /* the command's arguments read so far */
    double args[3];         /* set-pose: X, Y in metres (within +-HL_COORD_MAX_MM once
                               rounded to the millimetre), HEADING in degrees (finite) */
} ctl_options_t;

/**
 * Parses the command line into @p o (which holds the defaults on entry).
 * @return WAITING when the program should go on; otherwise the exit code, after --help
 *         or --version printed on stdout, or a usage error printed on stderr as one line.
 */
int ctl_parse_args(int argc, char **argv, ctl_options_t *o);

#endif
