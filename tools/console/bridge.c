/* bridge.c - houghlocd's messages as JSON for the console's page (bridge.h). */
#include "bridge.h"

#include "houghloc/fixed.h"
#include "houghloc/slam.h"

static const char *const state_names[] = {
    [HL_BUS_STATE_STARTING] = "STARTING", [HL_BUS_STATE_SOUNDING] = "SOUNDING",
    [HL_BUS_STATE_LOCALIZING] = "LOCALIZING", [HL_BUS_STATE_MOVING] = "MOVING",
    [HL_BUS_STATE_IDLE] = "IDLE", [HL_BUS_STATE_FAULT] = "FAULT",
    [HL_BUS_STATE_STOPPING] = "STOPPING", [HL_BUS_STATE_LOST] = "LOST",
};

static const char *const pose_names[] = {
    [HL_BUS_POSE_ACCEPTED] = "ACCEPTED", [HL_BUS_POSE_REJECTED_WILD] = "REJECTED_WILD",
    [HL_BUS_POSE_ODOMETRY_ONLY] = "ODOMETRY_ONLY", [HL_BUS_POSE_RELOCALIZED] = "RELOCALIZED",
    [HL_BUS_POSE_LOST] = "LOST",
};

const char *bridge_state_name(int8_t state)
{
    int n = (int)(sizeof state_names / sizeof state_names[0]);
    return state >= 0 && state < n ? state_names[state] : "UNKNOWN";
}

const char *bridge_pose_status_name(int8_t status)
{
    int n = (int)(sizeof pose_names / sizeof pose_names[0]);
    return status >= 0 && status < n ? pose_names[status] : "UNKNOWN";
}

/* ,"key": */
static void key(jbuf_t *b, const char *k, bool first)
{
    if (!first)
        jbuf_putc(b, ',');
    jbuf_str(b, k);
    jbuf_putc(b, ':');
}

/* A number. The counters and the map version (64-bit on the bus) go out as numbers too:
 * JavaScript holds them exactly below 2^53, 285 years of a million a second. */
static void int_field(jbuf_t *b, const char *k, int64_t v)
{
    key(b, k, false);
    jbuf_int(b, v);
}

/* A seq as a decimal string: JavaScript numbers hold integers exactly only to 2^53. */
static void seq_field(jbuf_t *b, const char *k, int64_t seq)
{
    key(b, k, false);
    jbuf_putc(b, '"');
    jbuf_int(b, seq);
    jbuf_putc(b, '"');
}

/* "x_mm":..,"y_mm":..,"heading_deg":.. (with a leading comma) */
static void pose_fields(jbuf_t *b, hl_pose_t p)
{
    int_field(b, "x_mm", p.x_mm);
    int_field(b, "y_mm", p.y_mm);
    key(b, "heading_deg", false);
    jbuf_num(b, hl_bam_to_deg(p.theta), 2);
}

void bridge_map(jbuf_t *b, const hl_bus_map_t *m)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, m->utime);
    int_field(b, "version", m->version);
    int_field(b, "capacity", m->capacity);
    int_field(b, "count", m->count);
    uint32_t stride = m->count / BRIDGE_MAP_MAX_VECTORS + (m->count % BRIDGE_MAP_MAX_VECTORS != 0);
    if (stride > 1)
        int_field(b, "stride", stride);
    else
        stride = 1;
    key(b, "v", false);
    jbuf_putc(b, '[');
    for (uint64_t i = 0; i < m->count && !b->failed; i += stride) {
        const hl_vector_t *v = &m->vectors[i];
        if (i)
            jbuf_putc(b, ',');
        jbuf_int(b, v->x_mm);
        jbuf_putc(b, ',');
        jbuf_int(b, v->y_mm);
        jbuf_putc(b, ',');
        jbuf_int(b, v->normal);
        jbuf_putc(b, ',');
        jbuf_int(b, v->range_mm);
    }
    jbuf_puts(b, "]}");
}

void bridge_pose(jbuf_t *b, const hl_bus_pose_t *p)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, p->utime);
    int_field(b, "scan_seq", p->scan_seq);
    pose_fields(b, p->pose);
    key(b, "status", false);
    jbuf_str(b, bridge_pose_status_name(p->status));
    key(b, "confidence", false);
    jbuf_num(b, p->confidence, 4);
    int_field(b, "peak", p->peak);
    int_field(b, "second_peak", p->second_peak);
    int_field(b, "votes", p->votes);
    key(b, "search_score", false);
    jbuf_num(b, p->search_score, 4);
    key(b, "runner_up", false);
    jbuf_putc(b, '{');
    key(b, "x_mm", true);
    jbuf_int(b, p->runner_up.x_mm);
    int_field(b, "y_mm", p->runner_up.y_mm);
    key(b, "heading_deg", false);
    jbuf_num(b, hl_bam_to_deg(p->runner_up.theta), 2);
    jbuf_putc(b, '}');
    key(b, "runner_up_score", false);
    jbuf_num(b, p->runner_up_score, 4);
    jbuf_putc(b, '}');
}

void bridge_status(jbuf_t *b, const hl_bus_status_t *s)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, s->utime);
    key(b, "state", false);
    jbuf_str(b, bridge_state_name(s->state));
    if (s->destination_seq < 0) {
        key(b, "destination_seq", false);
        jbuf_puts(b, "null");
    } else {
        seq_field(b, "destination_seq", s->destination_seq);
    }
    int_field(b, "scans", s->scans);
    int_field(b, "accepted", s->accepted);
    int_field(b, "rejected_wild", s->rejected_wild);
    int_field(b, "odometry_only", s->odometry_only);
    int_field(b, "relocalized", s->relocalized);
    int_field(b, "lost", s->lost);
    int_field(b, "bad_packets", s->bad_packets);
    int_field(b, "bad_messages", s->bad_messages);
    int_field(b, "rejected_requests", s->rejected_requests);
    int_field(b, "map_vectors", s->map_vectors);
    int_field(b, "map_version", s->map_version);
    int_field(b, "saves", s->saves);
    pose_fields(b, s->pose);
    int_field(b, "compute_median_us", s->compute_median_us);
    int_field(b, "compute_p99_us", s->compute_p99_us);
    int_field(b, "compute_samples", s->compute_samples);
    key(b, "last_error", false);
    jbuf_str(b, s->last_error);
    jbuf_putc(b, '}');
}

void bridge_reply(jbuf_t *b, const hl_bus_reply_t *r, bool mine)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, r->utime);
    seq_field(b, "seq", r->seq);
    key(b, "result", false);
    jbuf_str(b, hl_bus_reply_name(r->result));
    key(b, "message", false);
    jbuf_str(b, r->message);
    key(b, "mine", false);
    jbuf_puts(b, mine ? "true" : "false");
    jbuf_putc(b, '}');
}

void bridge_sent(jbuf_t *b, const hl_bus_destination_t *d, bool is_signed)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, d->utime);
    seq_field(b, "seq", d->seq);
    int_field(b, "x_mm", d->x_mm);
    int_field(b, "y_mm", d->y_mm);
    key(b, "heading_deg", false);
    if (d->has_heading)
        jbuf_num(b, hl_bam_to_deg(d->heading), 2);
    else
        jbuf_puts(b, "null");
    key(b, "signed", false);
    jbuf_puts(b, is_signed ? "true" : "false");
    jbuf_putc(b, '}');
}

void bridge_path(jbuf_t *b, const hl_bus_path_t *p)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, p->utime);
    if (p->destination_seq < 0) {
        key(b, "seq", false);
        jbuf_puts(b, "null");
    } else {
        seq_field(b, "seq", p->destination_seq);
    }
    key(b, "points", false);
    jbuf_putc(b, '[');
    int32_t n = p->npoints < 0 ? 0 : p->npoints;
    if (n > HL_BUS_PATH_MAX_POINTS)
        n = HL_BUS_PATH_MAX_POINTS;
    for (int32_t i = 0; i < n; i++) {
        if (i)
            jbuf_putc(b, ',');
        jbuf_int(b, p->x_mm[i]);
        jbuf_putc(b, ',');
        jbuf_int(b, p->y_mm[i]);
    }
    jbuf_puts(b, "]}");
}

void bridge_stop(jbuf_t *b, const hl_bus_command_t *c, bool is_signed)
{
    jbuf_putc(b, '{');
    key(b, "utime", true);
    jbuf_int(b, c->utime);
    seq_field(b, "seq", c->seq);
    key(b, "signed", false);
    jbuf_puts(b, is_signed ? "true" : "false");
    jbuf_putc(b, '}');
}
