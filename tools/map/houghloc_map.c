/*
 * houghloc-map - exports a houghloc map as a picture and as a ROS map_server map.
 *
 *   houghloc-map [options] INPUT OUTBASE
 *
 * INPUT is a saved map file (.hlmap, recognized by its magic) or an LCM log, whose last
 * MAP message is taken. Writes OUTBASE.png (mapdraw.h), OUTBASE.pgm and OUTBASE.yaml
 * (mapgrid.h). Every log is checked with hl_log_check before liblcm reads it (runlog.h).
 */
#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "houghloc/bus.h"
#include "houghloc/version.h"
#include "mapdraw.h"
#include "mapgrid.h"
#include "houghloc/mapstore.h"
#include "runlog.h"
#include "truth_frame.h"

#define PROG "houghloc-map"
#define MAX_TRAJECTORIES 8
#define MAP_MAGIC "HLMAP\r\n\x1a"

static const char usage[] =
    "Usage: houghloc-map [options] INPUT OUTBASE\n"
    "Draws a houghloc map and exports it for ROS. INPUT is a map file (.hlmap) or an LCM\n"
    "log (its last MAP message is taken). Writes\n"
    "  OUTBASE.png   the vectors, each a short stroke along the surface it saw\n"
    "  OUTBASE.pgm   an occupancy grid, ROS map_server style: 0 occupied (each vector's\n"
    "                surface point), 254 free (each vector's beam, traced back to its\n"
    "                sensor), 205 unknown\n"
    "  OUTBASE.yaml  its map_server description (resolution, origin, thresholds)\n"
    "\n"
    "Options:\n"
    "  -r, --resolution M   grid cell side in metres (default 0.05)\n"
    "  -t, --trajectory LOG draw the POSE and GROUND_TRUTH paths of LOG over the picture\n"
    "                       (repeatable, up to 8 logs: the daemon's output and input);\n"
    "                       the truth is drawn in the map frame, its first pose laid on\n"
    "                       the daemon's start pose (--start)\n"
    "      --start X,Y,DEG  the daemon's start pose ([start]; default 0,0,0, its default)\n"
    "  -n, --normals        draw each vector's normal as a tick toward its sensor\n"
    "  -s, --size PX        longer side of the picture's map area (default 1200)\n"
    "  -h, --help           this text\n"
    "  -V, --version        the version\n"
    "Exit status: 0 written; 1 bad input or a file that cannot be written (one line on\n"
    "stderr); 2 bad usage.\n";

typedef struct vectors {
    hl_vector_t *v;
    size_t n;
} vectors_t;

/* ---- INPUT: a map file ------------------------------------------------------------- */

/* Whether the file starts like a map file (as much of the magic as it has). */
static bool looks_like_map_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    char head[8];
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    return got > 0 && memcmp(head, MAP_MAGIC, got) == 0;
}

static int load_map_file(const char *path, vectors_t *out)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return fprintf(stderr, PROG ": %s: %s\n", path, strerror(errno)), 1;
    /* Room for every vector the file's size allows; the loader checks the rest. */
    uint64_t room = (uint64_t)st.st_size / sizeof(hl_vector_t) + 1;
    room = room < HL_MAP_MAX_CAPACITY ? room : HL_MAP_MAX_CAPACITY;
    hl_mapfile_t m = { .max_vectors = (uint32_t)room };
    m.vectors = calloc((size_t)room, sizeof *m.vectors);
    if (!m.vectors)
        return fprintf(stderr, PROG ": out of memory\n"), 1;
    char why[HL_MAPSTORE_WHY_LEN];
    if (hl_mapstore_load(path, &m, why) != HL_OK) {
        free(m.vectors);
        return fprintf(stderr, PROG ": %s\n", why), 1;
    }
    out->v = m.vectors;
    out->n = m.count;
    return 0;
}

/* ---- INPUT: the last MAP message of a log ----------------------------------------- */

typedef struct last_map {
    uint8_t *data;
    size_t len;
} last_map_t;

static bool on_map(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    last_map_t *m = user;
    if (!hl_runlog_is_channel(ev, HL_CHANNEL_MAP))
        return true;
    uint8_t *d = realloc(m->data, (size_t)ev->datalen + 1);
    if (!d)
        return snprintf(why, HL_BUS_WHY_LEN, "out of memory"), false;
    memcpy(d, ev->data, (size_t)ev->datalen);
    m->data = d;
    m->len = (size_t)ev->datalen;
    return true;
}

static int load_map_message(const char *path, vectors_t *out)
{
    last_map_t m = { 0 };
    if (hl_runlog_each_event(PROG, path, on_map, &m) != 0) {
        free(m.data);
        return 1;
    }
    if (!m.data)
        return fprintf(stderr, PROG ": %s: no MAP message (and not a map file)\n", path), 1;
    size_t fixed = hl_bus_map_bytes(0), per_vector = hl_bus_map_bytes(1) - fixed;
    hl_bus_map_t map = { .max_vectors = m.len >= fixed ? (uint32_t)((m.len - fixed) / per_vector)
                                                       : 0 };
    map.vectors = calloc((size_t)map.max_vectors + 1, sizeof *map.vectors);
    char why[HL_BUS_WHY_LEN] = "";
    int rc = 0;
    if (!map.vectors) {
        fprintf(stderr, PROG ": out of memory\n");
        rc = 1;
    } else if (hl_bus_decode_map(m.data, m.len, &map, why) != HL_OK) {
        fprintf(stderr, PROG ": %s: the last MAP message: %s\n", path, why);
        rc = 1;
    }
    free(m.data);
    if (rc != 0) {
        free(map.vectors);
        return rc;
    }
    out->v = map.vectors;
    out->n = map.count;
    return 0;
}

/* ---- --trajectory: POSE and GROUND_TRUTH paths ------------------------------------- */

typedef struct poses {
    hl_pose_t *p;
    size_t n, cap;
} poses_t;

typedef struct trajectory {
    poses_t pose, truth;
    hl_truth_frame_t frame;     /* moves GROUND_TRUTH into the map frame */
} trajectory_t;

static bool push(poses_t *ps, hl_pose_t p)
{
    if (ps->n == ps->cap) {
        size_t cap = ps->cap ? 2 * ps->cap : 256;
        hl_pose_t *q = realloc(ps->p, cap * sizeof *q);
        if (!q)
            return false;
        ps->p = q;
        ps->cap = cap;
    }
    ps->p[ps->n++] = p;
    return true;
}

static bool on_trajectory(void *user, const lcm_eventlog_event_t *ev, char *why)
{
    trajectory_t *t = user;
    poses_t *into = hl_runlog_is_channel(ev, HL_CHANNEL_POSE)           ? &t->pose
                    : hl_runlog_is_channel(ev, HL_CHANNEL_GROUND_TRUTH) ? &t->truth
                                                                        : NULL;
    if (!into)
        return true;
    hl_bus_pose_t p;
    if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &p, why) != HL_OK)
        return false;
    if (into == &t->truth && !hl_truth_frame_map(&t->frame, p.pose, &p.pose))
        return snprintf(why, HL_BUS_WHY_LEN, "the true pose moved to the map frame lies "
                        "beyond +-%.3f m (check --start)", HL_COORD_MAX_MM / 1000.0), false;
    if (!push(into, p.pose))
        return snprintf(why, HL_BUS_WHY_LEN, "out of memory"), false;
    return true;
}

/* ---- main -------------------------------------------------------------------------- */

typedef struct options {
    double resolution_m;
    hl_mapdraw_opts_t draw;
    const char *trajectories[MAX_TRAJECTORIES];
    size_t ntrajectories;
    hl_pose_t start;            /* the daemon's start pose (--start) */
    const char *input, *outbase;
} options_t;

/* Bad usage: one line, exit status 2. */
__attribute__((format(printf, 1, 2))) static int bad_usage(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs(PROG ": ", stderr);
    vfprintf(stderr, fmt, ap);
    fputs(" (try --help)\n", stderr);
    va_end(ap);
    return 2;
}

static int parse(int argc, char **argv, options_t *o)
{
    static const struct option longopts[] = {
        { "resolution", required_argument, NULL, 'r' },
        { "trajectory", required_argument, NULL, 't' },
        { "normals", no_argument, NULL, 'n' },
        { "size", required_argument, NULL, 's' },
        { "start", required_argument, NULL, 'S' },
        { "help", no_argument, NULL, 'h' },
        { "version", no_argument, NULL, 'V' },
        { NULL, 0, NULL, 0 },
    };
    opterr = 0;     /* one line of our own instead of getopt's */
    int c;
    while ((c = getopt_long(argc, argv, ":r:t:ns:hV", longopts, NULL)) != -1) {
        char *end;
        switch (c) {
        case 'r':
            errno = 0;
            o->resolution_m = strtod(optarg, &end);
            /* plain decimals only: strtod would also skip spaces and read hexadecimal */
            if (!(isdigit((unsigned char)*optarg) || *optarg == '.') || strpbrk(optarg, "xX") ||
                end == optarg || *end || errno || !(o->resolution_m >= 0.001) ||
                !(o->resolution_m <= 100))
                return bad_usage("--resolution '%s' is not a cell size of 0.001..100 m", optarg);
            break;
        case 't':
            if (o->ntrajectories == MAX_TRAJECTORIES)
                return bad_usage("more than %d --trajectory logs", MAX_TRAJECTORIES);
            o->trajectories[o->ntrajectories++] = optarg;
            break;
        case 'n':
            o->draw.normals = true;
            break;
        case 'S': {
            char why[HL_TRUTH_FRAME_WHY_LEN];
            if (!hl_truth_frame_parse_pose(optarg, &o->start, why))
                return bad_usage("--start %s", why);
            break;
        }
        case 's': {
            errno = 0;
            long v = strtol(optarg, &end, 10);
            if (end == optarg || *end || errno || v < HL_MAPDRAW_MIN_PX || v > HL_MAPDRAW_MAX_PX)
                return bad_usage("--size '%s' is not %d..%d pixels", optarg, HL_MAPDRAW_MIN_PX,
                                 HL_MAPDRAW_MAX_PX);
            o->draw.size_px = (int)v;
            break;
        }
        case 'h':
            fputs(usage, stdout);
            return 0;
        case 'V':
            printf(PROG " %s\n", HL_VERSION);
            return 0;
        case ':':
            return bad_usage("%s needs a value", argv[optind - 1]);
        default:
            return bad_usage("unknown option '%s'", argv[optind - 1]);
        }
    }
    if (argc - optind != 2)
        return bad_usage("expected INPUT and OUTBASE");
    o->input = argv[optind];
    o->outbase = argv[optind + 1];
    return -1;
}

/* OUTBASE + suffix, or NULL (after saying so) when it does not fit. */
static char *out_name(const char *outbase, const char *suffix)
{
    size_t n = strlen(outbase) + strlen(suffix) + 1;
    char *s = malloc(n);
    if (s)
        snprintf(s, n, "%s%s", outbase, suffix);
    else
        fprintf(stderr, PROG ": out of memory\n");
    return s;
}

static int write_outputs(const options_t *o, const vectors_t *vs, const trajectory_t *t)
{
    hl_mapdraw_path_t paths[2 * MAX_TRAJECTORIES];
    size_t np = 0;
    for (size_t k = 0; k < o->ntrajectories; k++) {
        if (t[k].truth.n > 0)
            paths[np++] = (hl_mapdraw_path_t){ t[k].truth.p, t[k].truth.n, "ground truth",
                                               { 0.1, 0.6, 0.2 } };
        if (t[k].pose.n > 0)
            paths[np++] = (hl_mapdraw_path_t){ t[k].pose.p, t[k].pose.n, "POSE",
                                               { 0.15, 0.35, 0.9 } };
    }
    char *png = out_name(o->outbase, ".png"), *pgm = out_name(o->outbase, ".pgm");
    char *yaml = out_name(o->outbase, ".yaml");
    hl_mapgrid_t g = { 0 };
    char why[HL_MAPGRID_WHY_LEN + HL_MAPDRAW_WHY_LEN] = "";
    int rc = !png || !pgm || !yaml;
    if (rc == 0 && hl_mapgrid_build(vs->v, vs->n, o->resolution_m, &g, why) != HL_OK) {
        fprintf(stderr, PROG ": %s: %s\n", o->input, why);
        rc = 1;
    }
    if (rc == 0 && (hl_mapdraw_png(png, vs->v, vs->n, paths, np, &o->draw, why) != HL_OK ||
                    hl_mapgrid_write_pgm(&g, pgm, why) != HL_OK)) {
        fprintf(stderr, PROG ": %s\n", why);
        rc = 1;
    }
    if (rc == 0) {
        /* The YAML names the image relative to its own folder: the base name. */
        const char *slash = strrchr(pgm, '/');
        if (hl_mapgrid_write_yaml(&g, yaml, slash ? slash + 1 : pgm, why) != HL_OK) {
            fprintf(stderr, PROG ": %s\n", why);
            rc = 1;
        }
    }
    if (rc == 0)
        printf(PROG ": %zu vectors -> %s, %s (%u x %u cells of %g m), %s\n", vs->n, png, pgm,
               g.width, g.height, g.resolution_m, yaml);
    hl_mapgrid_free(&g);
    free(png);
    free(pgm);
    free(yaml);
    return rc;
}

int main(int argc, char **argv)
{
    options_t o = { .resolution_m = 0.05, .draw = { .size_px = 1200 } };
    int rc = parse(argc, argv, &o);
    if (rc >= 0)
        return rc;
    vectors_t vs = { 0 };
    rc = looks_like_map_file(o.input) ? load_map_file(o.input, &vs)
                                      : load_map_message(o.input, &vs);
    trajectory_t t[MAX_TRAJECTORIES] = { 0 };
    for (size_t k = 0; rc == 0 && k < o.ntrajectories; k++) {
        hl_truth_frame_init(&t[k].frame, o.start);
        rc = hl_runlog_each_event(PROG, o.trajectories[k], on_trajectory, &t[k]);
        if (rc == 0 && t[k].pose.n == 0 && t[k].truth.n == 0) {
            fprintf(stderr, PROG ": %s: no POSE or GROUND_TRUTH message\n", o.trajectories[k]);
            rc = 1;
        }
    }
    if (rc == 0)
        rc = write_outputs(&o, &vs, t);
    for (size_t k = 0; k < o.ntrajectories; k++) {
        free(t[k].pose.p);
        free(t[k].truth.p);
    }
    free(vs.v);
    return rc;
}
