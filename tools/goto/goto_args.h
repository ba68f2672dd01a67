/* goto_args.h - houghloc-goto's command line (private to tools/goto; the exit codes and
 * the options it shares with houghloc-ctl are in request.h). */
#ifndef HOUGHLOC_TOOLS_GOTO_ARGS_H
#define HOUGHLOC_TOOLS_GOTO_ARGS_H

#include <stdbool.h>

#include "request.h"

#define PROG "houghloc-goto"

typedef struct goto_options {
    req_options_t req;      /* --lcm-url, --prefix, --key, --timeout */
    bool no_wait;
    int npos;               /* 2 or 3 once parsed */
    double pos[3];          /* X, Y in metres (within +-HL_COORD_MAX_MM once rounded to
                               the millimetre), HEADING in degrees (finite) */
} goto_options_t;

/**
 * Parses the command line into @p o (which holds the defaults on entry).
 * @return WAITING when the program should go on; otherwise the exit code, after --help
 *         or --version printed on stdout, or a usage error printed on stderr as one line.
 */
int goto_parse_args(int argc, char **argv, goto_options_t *o);

#endif
