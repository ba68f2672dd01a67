/* carmen_args.c - houghloc-import-carmen's command line. */
#include "carmen_args.h"

#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/version.h"

static const char usage_text[] =
    "Usage: " PROG " [options] IN OUT\n"
    "       " PROG " --dump LOG\n"
    "\n"
    "Converts a CARMEN log IN (plain or gzip) into an LCM event log OUT that houghlocd\n"
    "replays: one SONAR scan per FLASER line (seq 0, 1, 2, ... over the scans written,\n"
    "utime the CARMEN timestamp in microseconds), one ODOMETRY per FLASER line from its\n"
    "pose field, and with --truth one GROUND_TRUTH pose per scan. PARAM lines give the\n"
    "field of view (laser_front_laser_fov; 180 degrees without one) and the step\n"
    "between beams (laser_front_laser_resolution; without one the SICK's for the beam\n"
    "count, as CARMEN reads FLASER lines: 1 degree for 180 or 181 beams, 0.5 for 360\n"
    "or 361, the first beam at minus half the field of view; other counts spread\n"
    "evenly across it); comments and other line types are skipped; a malformed line\n"
    "stops the import with FILE:LINE.\n"
    "\n"
    "Options:\n"
    "  --input laser|sonar  laser: every beam a reading, at its bearing (default);\n"
    "                       sonar: a pseudo-sonar ring, a reading every 2.8125 degrees\n"
    "                       across the field of view, each the nearest return within\n"
    "                       a 22-degree cone around its bearing (64 for 180 degrees)\n"
    "  --select every|moved every: every FLASER line is a scan (default);\n"
    "                       moved: a scan only when the odometry has moved --move-m or\n"
    "                       turned --turn-deg since the last scan written (the first\n"
    "                       is always written), as a robot that stops to sound\n"
    "  --move-m M           distance for --select moved (default 0.5)\n"
    "  --turn-deg D         turn for --select moved (default 15)\n"
    "  --truth FILE         ground truth in TUM format (time x y z qx qy qz qw): every\n"
    "                       scan written must have a pose at exactly its timestamp\n"
    "  --fov-deg D          the laser's field of view, 0 < D <= 360 (overrides PARAM),\n"
    "                       the beams spread evenly across it\n"
    "  --no-return-m M      ranges of M metres or more are no return (overrides the\n"
    "                       default: 49.9 m, and the log's maximum range when it\n"
    "                       occurs more than once, the value some logs use for it)\n"
    "  --dump LOG           print an LCM log's SONAR, ODOMETRY and GROUND_TRUTH\n"
    "                       messages as text, one line each (readings indented)\n"
    "  --help               this text\n"
    "  --version            the version\n"
    "\n"
    "A summary goes to standard error: lines read, scans written and skipped, beams per\n"
    "scan, field of view, maximum range, no-return readings, and returns beyond 32.767 m\n"
    "(which a reading cannot hold: they are written as invalid readings, and counted).\n"
    "\n"
    "Examples:\n"
    "  " PROG " --truth intel-groundtruth.tum intel-raw.log.gz intel.lcmlog\n"
    "  " PROG " --input sonar --select moved intel-raw.log.gz intel-sonar.lcmlog\n"
    "  " PROG " --dump intel.lcmlog | head\n"
    "\n"
    "Exit status: 0 done, 1 bad input or I/O error (one line: FILE:LINE: reason), 2 bad\n"
    "usage.\n";

__attribute__((format(printf, 1, 2))) static int usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs(PROG ": ", stderr);
    vfprintf(stderr, fmt, ap);
    fputs(" (try --help)\n", stderr);
    va_end(ap);
    return CARMEN_EXIT_USAGE;
}

/* A finite number in (0, max]. */
static bool positive(const char *arg, double max, double *out)
{
    double v;
    if (!carmen_parse_number(arg, &v) || !(v > 0) || v > max)
        return false;
    *out = v;
    return true;
}

int carmen_parse_args(int argc, char **argv, carmen_options_t *o)
{
    *o = (carmen_options_t){ .input = CARMEN_INPUT_LASER, .select = CARMEN_SELECT_EVERY,
                             .move_m = CARMEN_DEFAULT_MOVE_M,
                             .turn_deg = CARMEN_DEFAULT_TURN_DEG };
    enum { O_INPUT = 256, O_SELECT, O_MOVE, O_TURN, O_TRUTH, O_FOV, O_NORET, O_DUMP, O_HELP,
           O_VERSION };
    static const struct option longopts[] = {
        { "input", required_argument, NULL, O_INPUT },
        { "select", required_argument, NULL, O_SELECT },
        { "move-m", required_argument, NULL, O_MOVE },
        { "turn-deg", required_argument, NULL, O_TURN },
        { "truth", required_argument, NULL, O_TRUTH },
        { "fov-deg", required_argument, NULL, O_FOV },
        { "no-return-m", required_argument, NULL, O_NORET },
        { "dump", required_argument, NULL, O_DUMP },
        { "help", no_argument, NULL, O_HELP },
        { "version", no_argument, NULL, O_VERSION },
        { NULL, 0, NULL, 0 },
    };
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case O_INPUT:
            if (strcmp(arg, "laser") == 0)
                o->input = CARMEN_INPUT_LASER;
            else if (strcmp(arg, "sonar") == 0)
                o->input = CARMEN_INPUT_SONAR;
            else
                return usage_error("--input '%s': expected laser or sonar", arg);
            break;
        case O_SELECT:
            if (strcmp(arg, "every") == 0)
                o->select = CARMEN_SELECT_EVERY;
            else if (strcmp(arg, "moved") == 0)
                o->select = CARMEN_SELECT_MOVED;
            else
                return usage_error("--select '%s': expected every or moved", arg);
            break;
        case O_MOVE:
            if (!positive(arg, 1e6, &o->move_m))
                return usage_error("--move-m '%s': expected metres above 0", arg);
            break;
        case O_TURN:
            if (!positive(arg, 360, &o->turn_deg))
                return usage_error("--turn-deg '%s': expected degrees in (0, 360]", arg);
            break;
        case O_TRUTH: o->truth = arg; break;
        case O_FOV:
            if (!positive(arg, 360, &o->fov_deg))
                return usage_error("--fov-deg '%s': expected degrees in (0, 360]", arg);
            break;
        case O_NORET:
            if (!positive(arg, 1e6, &o->no_return_m))
                return usage_error("--no-return-m '%s': expected metres above 0", arg);
            break;
        case O_DUMP: o->dump = arg; break;
        case O_HELP: fputs(usage_text, stdout); return CARMEN_EXIT_OK;
        case O_VERSION: printf("%s %s\n", PROG, HL_VERSION); return CARMEN_EXIT_OK;
        case ':': return usage_error("%s needs a value", argv[optind - 1]);
        default: return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    int npos = argc - optind;
    if (o->dump) {
        if (npos != 0)
            return usage_error("--dump takes one log and no other argument: '%s'", argv[optind]);
        return CARMEN_CONTINUE;
    }
    if (npos != 2)
        return usage_error("expected IN and OUT, got %s",
                           npos == 0 ? "none" : npos == 1 ? "one argument" : "more arguments");
    o->in = argv[optind];
    o->out = argv[optind + 1];
    return CARMEN_CONTINUE;
}
