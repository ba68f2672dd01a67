/*
 * counter_edge.c - hl-counter-edge: the tool of the Counters trial
 * (tools/lab/trials/counters.sh), which runs houghlocd on a map whose version is just
 * below 2^31 or 2^32.
 *
 *   hl-counter-edge set MAPFILE VERSION   gives a real map file (one houghlocd saved)
 *                                          another map version, 0..2^63 - 1, and saves it
 *                                          (format version 2) in place
 *   hl-counter-edge scan LOG EDGE         reads the MAP and STATUS messages of houghlocd's
 *                                          output LOG and prints one line about their
 *                                          versions against EDGE
 *
 * scan's line:
 *   maps=N maps_past=N map_first=V map_last=V map_rising=yes|no statuses=N
 *   statuses_past=N status_last=V undecodable=N
 * where *_past count the messages whose version is at least EDGE, map_rising says whether
 * each MAP's version was above the one before, status_last is the last STATUS's
 * map_version (-1 when none) and undecodable counts MAP and STATUS messages the codecs
 * refuse. Exit status: 0 done; 1 a file that cannot be read or written; 2 bad usage.
 */
#include <errno.h>
#include <inttypes.h>
#include <lcm/eventlog.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/mapstore.h"

#define PROG "hl-counter-edge"

static const char usage[] =
    "Usage: hl-counter-edge set MAPFILE VERSION\n"
    "       hl-counter-edge scan LOG EDGE\n"
    "set gives the map file MAPFILE the map version VERSION (0..2^63 - 1) and saves it.\n"
    "scan prints one line about the MAP and STATUS versions of houghlocd's output LOG:\n"
    "  maps=N maps_past=N map_first=V map_last=V map_rising=yes|no statuses=N\n"
    "  statuses_past=N status_last=V undecodable=N\n"
    "(*_past: messages whose version is at least EDGE).\n";

/* A whole decimal number in 0..HL_COUNT_MAX. */
static bool parse_count(const char *s, int64_t *out)
{
    if (!s[0] || s[0] < '0' || s[0] > '9')
        return false;
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (errno != 0 || *end != '\0' || v < 0)
        return false;
    *out = (int64_t)v;
    return true;
}

static int cmd_set(const char *path, int64_t version)
{
    char why[HL_MAPSTORE_WHY_LEN];
    hl_mapfile_t m = { .max_vectors = HL_MAP_MAX_CAPACITY };
    m.vectors = calloc(HL_MAP_MAX_CAPACITY, sizeof *m.vectors);
    if (!m.vectors)
        return fprintf(stderr, PROG ": out of memory\n"), 1;
    int rc = 0;
    if (hl_mapstore_load(path, &m, why) != HL_OK) {
        fprintf(stderr, PROG ": %s\n", why);
        rc = 1;
    } else {
        uint64_t was = m.state.map_version;
        m.state.map_version = (uint64_t)version;
        if (hl_mapstore_save(path, &m, why) != HL_OK) {
            fprintf(stderr, PROG ": %s\n", why);
            rc = 1;
        } else {
            printf("%s: map version %" PRIu64 " -> %" PRId64 "\n", path, was, version);
        }
    }
    free(m.vectors);
    return rc;
}

typedef struct tally {
    int64_t edge;
    long maps, maps_past, statuses, statuses_past, undecodable;
    int64_t map_first, map_last, status_last;
    bool rising;
} tally_t;

static void on_map(tally_t *t, const lcm_eventlog_event_t *ev, hl_vector_t *storage)
{
    hl_bus_map_t m = { .vectors = storage, .max_vectors = HL_MAP_MAX_CAPACITY };
    if (hl_bus_decode_map(ev->data, (size_t)ev->datalen, &m, NULL) != HL_OK) {
        t->undecodable++;
        return;
    }
    if (t->maps == 0)
        t->map_first = m.version;
    else if (m.version <= t->map_last)
        t->rising = false;
    t->map_last = m.version;
    t->maps++;
    t->maps_past += m.version >= t->edge;
}

static void on_status(tally_t *t, const lcm_eventlog_event_t *ev)
{
    hl_bus_status_t s;
    if (hl_bus_decode_status(ev->data, (size_t)ev->datalen, &s, NULL) != HL_OK) {
        t->undecodable++;
        return;
    }
    t->status_last = s.map_version;
    t->statuses++;
    t->statuses_past += s.map_version >= t->edge;
}

static int cmd_scan(const char *path, int64_t edge)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    if (!log)
        return fprintf(stderr, PROG ": %s: cannot read: %s\n", path, strerror(errno)), 1;
    hl_vector_t *storage = malloc(HL_MAP_MAX_CAPACITY * sizeof *storage);
    if (!storage) {
        lcm_eventlog_destroy(log);
        return fprintf(stderr, PROG ": out of memory\n"), 1;
    }
    tally_t t = { .edge = edge, .map_first = -1, .map_last = -1, .status_last = -1,
                  .rising = true };
    lcm_eventlog_event_t *ev;
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
        if (strcmp(ev->channel, HL_CHANNEL_MAP) == 0)
            on_map(&t, ev, storage);
        else if (strcmp(ev->channel, HL_CHANNEL_STATUS) == 0)
            on_status(&t, ev);
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    free(storage);
    printf("maps=%ld maps_past=%ld map_first=%" PRId64 " map_last=%" PRId64
           " map_rising=%s statuses=%ld statuses_past=%ld status_last=%" PRId64
           " undecodable=%ld\n",
           t.maps, t.maps_past, t.map_first, t.map_last, t.rising ? "yes" : "no",
           t.statuses, t.statuses_past, t.status_last, t.undecodable);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return fputs(usage, stdout), 0;
    int64_t n;
    if (argc != 4 || (strcmp(argv[1], "set") != 0 && strcmp(argv[1], "scan") != 0))
        return fprintf(stderr, PROG ": expected set MAPFILE VERSION or scan LOG EDGE; try "
                       PROG " --help\n"), 2;
    if (!parse_count(argv[3], &n))
        return fprintf(stderr, PROG ": '%s' is not a number in 0..2^63 - 1\n", argv[3]), 2;
    return strcmp(argv[1], "set") == 0 ? cmd_set(argv[2], n) : cmd_scan(argv[2], n);
}
