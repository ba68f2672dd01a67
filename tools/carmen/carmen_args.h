/* carmen_args.h - houghloc-import-carmen's command line (private to tools/carmen). */
#ifndef HOUGHLOC_TOOLS_CARMEN_ARGS_H
#define HOUGHLOC_TOOLS_CARMEN_ARGS_H

#include <stdbool.h>

#include "carmen_scan.h"

#define PROG "houghloc-import-carmen"

/* Exit codes. */
#define CARMEN_EXIT_OK 0
#define CARMEN_EXIT_ERROR 1     /* bad input, I/O error */
#define CARMEN_EXIT_USAGE 2
#define CARMEN_CONTINUE (-1)    /* parse_args: go on */

/* Defaults of --select moved: about the hop of the paper's space-filling tour
 * (2-foot floor tiles), and a turn that moves the ring by a few sonar cones. */
#define CARMEN_DEFAULT_MOVE_M 0.5
#define CARMEN_DEFAULT_TURN_DEG 15.0

typedef enum carmen_select {
    CARMEN_SELECT_EVERY = 0,
    CARMEN_SELECT_MOVED,
} carmen_select_t;

typedef struct carmen_options {
    carmen_input_t input;
    carmen_select_t select;
    double move_m;          /* > 0 and finite */
    double turn_deg;        /* > 0 and finite */
    const char *truth;      /* --truth FILE, or NULL */
    double fov_deg;         /* --fov-deg, 0 when not given; else 0 < fov <= 360 */
    double no_return_m;     /* --no-return-m, 0 when not given; else > 0 */
    const char *dump;       /* --dump LOG: print LOG and exit; NULL otherwise */
    const char *in, *out;   /* positional IN OUT (NULL with --dump) */
} carmen_options_t;

/**
 * Parses the command line into @p o (defaults are set here).
 * @return CARMEN_CONTINUE when the program should go on; otherwise the exit code, after
 *         --help or --version printed on stdout, or a usage error printed on stderr as
 *         one line.
 */
int carmen_parse_args(int argc, char **argv, carmen_options_t *o);

#endif
