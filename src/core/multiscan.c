/* multiscan.c - a sounding assembled by motion (multiscan.h). */
#include "houghloc-internal/multiscan.h"

#include <math.h>
#include <stdlib.h>

#define RAD_PER_BAM (2 * 3.14159265358979323846 / 65536)

typedef struct entry {
    hl_pose_t odometry, pose;
    double path_mm, turn_rad;   /* the travel and turning before it, since the clear */
    bool draw;
} entry_t;

struct hl_multiscan {
    uint32_t max_scans, first, n;   /* a ring of n entries from first */
    hl_mm_t span_mm;
    hl_bam_t span_turn;
    bool have_last;
    hl_pose_t last_odometry;        /* the newest pushed */
    double path_mm, turn_rad;       /* ... its travel and turning */
    entry_t entries[HL_MULTISCAN_MAX_SCANS];
    hl_scan_t *scans;               /* [max_scans], parallel to entries */
};

hl_multiscan_t *hl_multiscan_create(uint32_t max_scans, hl_mm_t span_mm, hl_bam_t span_turn)
{
    if (max_scans < 1 || max_scans > HL_MULTISCAN_MAX_SCANS || span_mm < 0)
        return NULL;
    hl_multiscan_t *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    m->scans = calloc(max_scans, sizeof *m->scans);
    if (!m->scans) {
        free(m);
        return NULL;
    }
    m->max_scans = max_scans;
    m->span_mm = span_mm;
    m->span_turn = span_turn;
    return m;
}

void hl_multiscan_destroy(hl_multiscan_t *m)
{
    if (!m)
        return;
    free(m->scans);
    free(m);
}

void hl_multiscan_clear(hl_multiscan_t *m)
{
    m->first = m->n = 0;
    m->have_last = false;
    m->path_mm = m->turn_rad = 0;
}

uint32_t hl_multiscan_count(const hl_multiscan_t *m)
{
    return m->n;
}

static uint32_t slot(const hl_multiscan_t *m, uint32_t k)     /* k-th oldest */
{
    return (m->first + k) % m->max_scans;
}

/* The travel and turning from the newest pushed to @p odometry. */
static void since_last(const hl_multiscan_t *m, hl_pose_t odometry, double *mm, double *rad)
{
    *mm = *rad = 0;
    if (!m->have_last)
        return;
    hl_pose_t d = hl_pose_between(m->last_odometry, odometry);
    *mm = hypot(d.x_mm, d.y_mm);
    *rad = fabs((int16_t)(uint16_t)d.theta * RAD_PER_BAM);
}

/* Reading @p r of a scan taken at @p at (a pose in the newest scan's frame), moved into
 * that frame; false when its surface faces away from the newest pose. */
static bool move_reading(const hl_reading_t *r, hl_pose_t at, hl_reading_t *out)
{
    double b = hl_bam_to_rad(r->bearing), t = hl_bam_to_rad(at.theta);
    double px = r->range_mm * cos(b), py = r->range_mm * sin(b);
    double x = at.x_mm + cos(t) * px - sin(t) * py;
    double y = at.y_mm + sin(t) * px + cos(t) * py;
    double range = hypot(x, y);
    if (range > HL_RANGE_MAX_MM)
        return false;
    *out = *r;
    out->range_mm = (int32_t)lround(range);
    out->bearing = hl_bam_from_rad(atan2(y, x));
    int32_t tilt = hl_bam_diff(hl_reading_normal(r, at.theta),
                               (hl_bam_t)(out->bearing + HL_BAM_HALF_TURN));
    if (tilt <= -(int32_t)HL_BAM_QUARTER_TURN || tilt >= (int32_t)HL_BAM_QUARTER_TURN)
        return false;
    out->tilt = (int16_t)tilt;
    return true;
}

uint32_t hl_multiscan_assemble(const hl_multiscan_t *m, const hl_scan_t *newest,
                               hl_pose_t odometry, hl_scan_t *out)
{
    *out = *newest;
    uint32_t taken = 0;
    for (uint32_t k = m->n; k-- > 0 && out->count < HL_SCAN_MAX_READINGS; taken++) {
        const entry_t *e = &m->entries[slot(m, k)];
        const hl_scan_t *scan = &m->scans[slot(m, k)];
        hl_pose_t at = hl_pose_between(odometry, e->odometry);
        for (uint32_t i = 0; i < scan->count && out->count < HL_SCAN_MAX_READINGS; i++) {
            if (scan->readings[i].valid &&
                move_reading(&scan->readings[i], at, &out->readings[out->count]))
                out->count++;
        }
    }
    return taken;
}

bool hl_multiscan_pop_due(hl_multiscan_t *m, hl_pose_t odometry, const hl_scan_t **scan,
                          hl_pose_t *scan_odometry, hl_pose_t *pose, bool *draw)
{
    if (m->n == 0)
        return false;
    const entry_t *e = &m->entries[m->first];
    double mm, rad;
    since_last(m, odometry, &mm, &rad);
    bool full = m->n == m->max_scans;
    bool far = m->path_mm + mm - e->path_mm > m->span_mm ||
               m->turn_rad + rad - e->turn_rad > m->span_turn * RAD_PER_BAM;
    if (!full && !far)
        return false;
    *scan = &m->scans[m->first];
    *scan_odometry = e->odometry;
    *pose = e->pose;
    *draw = e->draw;
    m->first = slot(m, 1);
    m->n--;
    return true;
}

void hl_multiscan_push(hl_multiscan_t *m, const hl_scan_t *scan, hl_pose_t odometry,
                       hl_pose_t pose, bool draw)
{
    double mm, rad;
    since_last(m, odometry, &mm, &rad);
    m->path_mm += mm;
    m->turn_rad += rad;
    m->last_odometry = odometry;
    m->have_last = true;
    if (m->n == m->max_scans) {     /* the oldest goes undrawn: pop_due was not called */
        m->first = slot(m, 1);
        m->n--;
    }
    uint32_t at = slot(m, m->n++);
    m->entries[at] = (entry_t){ .odometry = odometry, .pose = pose, .path_mm = m->path_mm,
                                .turn_rad = m->turn_rad, .draw = draw };
    m->scans[at] = *scan;
}
