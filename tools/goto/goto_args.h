/* goto_args.h - houghloc-goto's command line and exit codes (private to tools/goto). */
#ifndef HOUGHLOC_TOOLS_GOTO_ARGS_H
#define HOUGHLOC_TOOLS_GOTO_ARGS_H

#include <stdbool.h>

#define PROG "houghloc-goto"
#include "houghloc/version.h"
#define GOTO_VERSION HL_VERSION
#define DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0"

/* The exit codes, as --help lists them. */
enum {
    EXIT_ARRIVED = 0,   /* ARRIVED, or ACCEPTED with --no-wait; also --help, --version */
    EXIT_ERROR = 1,     /* LCM cannot start, key file refused, ... */
    EXIT_USAGE = 2,
    EXIT_REJECTED = 3,  /* REJECTED_FENCE, _AUTH, _REPLAY, _INVALID */
    EXIT_NO_ROBOT = 4,
    EXIT_FAILED = 5,
    EXIT_TIMEOUT = 6,
    WAITING = -1,       /* not an exit code: go on */
};

typedef struct goto_options {
    const char *url;        /* NULL: $LCM_DEFAULT_URL, else DEFAULT_URL */
    const char *prefix;     /* channel prefix, already checked by hl_bus_channel */
    const char *key_file;   /* NULL: unsigned */
    double timeout_s;       /* 0.1 .. 3600 */
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

/** Prints "houghloc-goto: <message>; try houghloc-goto --help" on stderr.
 *  @return EXIT_USAGE. */
__attribute__((format(printf, 1, 2))) int goto_usage_error(const char *fmt, ...);

#endif
