/* carmen_dump.c - an LCM log's houghloc input messages as text (--dump). */
#include "carmen_import.h"

#include <errno.h>
#include <lcm/eventlog.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/bus.h"
#include "houghloc/logcheck.h"

static bool is_channel(const lcm_eventlog_event_t *ev, const char *name)
{
    return (size_t)ev->channellen == strlen(name) && memcmp(ev->channel, name, ev->channellen) == 0;
}

static void print_scan(const hl_bus_scan_t *m, FILE *out)
{
    fprintf(out, "SONAR utime=%lld seq=%d odometry=%d,%d,%u readings=%u valid=%u\n",
            (long long)m->utime, m->seq, m->odometry.x_mm, m->odometry.y_mm,
            (unsigned)m->odometry.theta, m->scan.count, hl_scan_valid_count(&m->scan));
    for (uint32_t i = 0; i < m->scan.count; i++) {
        const hl_reading_t *r = &m->scan.readings[i];
        fprintf(out, "  reading %u bearing=%u range_mm=%d transducer=%d valid=%d\n", i,
                (unsigned)r->bearing, r->range_mm, r->transducer, r->valid ? 1 : 0);
    }
}

/* One event as text. @return false with the reason in @p why when it does not decode. */
static bool print_event(const lcm_eventlog_event_t *ev, hl_bus_scan_t *scan, FILE *out,
                        char *why)
{
    if (is_channel(ev, HL_CHANNEL_SONAR)) {
        if (hl_bus_decode_scan(ev->data, (size_t)ev->datalen, scan, why) != HL_OK)
            return false;
        print_scan(scan, out);
    } else if (is_channel(ev, HL_CHANNEL_ODOMETRY)) {
        hl_bus_odometry_t o;
        if (hl_bus_decode_odometry(ev->data, (size_t)ev->datalen, &o, why) != HL_OK)
            return false;
        fprintf(out, "ODOMETRY utime=%lld pose=%d,%d,%u velocity_mm_s=%d stopped=%d\n",
                (long long)o.utime, o.pose.x_mm, o.pose.y_mm, (unsigned)o.pose.theta,
                o.velocity_mm_s, o.stopped ? 1 : 0);
    } else if (is_channel(ev, HL_CHANNEL_GROUND_TRUTH)) {
        hl_bus_pose_t p;
        if (hl_bus_decode_pose(ev->data, (size_t)ev->datalen, &p, why) != HL_OK)
            return false;
        fprintf(out, "GROUND_TRUTH utime=%lld scan_seq=%d pose=%d,%d,%u\n", (long long)p.utime,
                p.scan_seq, p.pose.x_mm, p.pose.y_mm, (unsigned)p.pose.theta);
    } else {
        fprintf(out, "%.*s utime=%lld bytes=%d\n", (int)ev->channellen, ev->channel,
                (long long)ev->timestamp, (int)ev->datalen);
    }
    return true;
}

int carmen_dump(const char *path, FILE *out)
{
    char why[HL_LOG_WHY_LEN];
    if (hl_log_check(path, NULL, why) != HL_OK)
        return fprintf(stderr, PROG ": %s\n", why), CARMEN_EXIT_ERROR;
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    hl_bus_scan_t *scan = malloc(sizeof *scan);     /* ~12 KiB */
    if (!log || !scan) {
        fprintf(stderr, PROG ": %s: %s\n", path, log ? "out of memory" : strerror(errno));
        if (log)
            lcm_eventlog_destroy(log);
        free(scan);
        return CARMEN_EXIT_ERROR;
    }
    int rc = CARMEN_EXIT_OK;
    lcm_eventlog_event_t *ev;
    while (rc == CARMEN_EXIT_OK && (ev = lcm_eventlog_read_next_event(log)) != NULL) {
        char bwhy[HL_BUS_WHY_LEN] = "";
        if (!print_event(ev, scan, out, bwhy)) {
            fprintf(stderr, PROG ": %s: event %lld on %.*s: %s\n", path, (long long)ev->eventnum,
                    (int)ev->channellen, ev->channel, bwhy);
            rc = CARMEN_EXIT_ERROR;
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    free(scan);
    if (rc == CARMEN_EXIT_OK && (fflush(out) != 0 || ferror(out))) {
        fprintf(stderr, PROG ": write error: %s\n", strerror(errno));
        rc = CARMEN_EXIT_ERROR;
    }
    return rc;
}
