/* robot_nav.c - the live robot's way to a destination: planned on its own map (plan.h),
 * published on PATH, and watched by the sonar's safety stop while a leg is driven
 * (safety.h, drive.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/safety.h"
#include "log.h"
#include "robot_internal.h"

/* The lobe the safety stop assumes for an echo: wider than a Polaroid transducer's
 * 11-degree half-width, since its side lobes also answer up close. */
#define SAFETY_HALF_BEAM_DEG 15

static bool inside_fence(void *ctx, hl_mm_t x_mm, hl_mm_t y_mm)
{
    return hl_fence_contains(hl_cycle_fence(ctx), x_mm, y_mm);
}

bool robot_nav_create(hl_robot_t *r)
{
    hl_plan_params_t p;
    hl_plan_params_default(&p);
    p.radius_mm = r->p.radius_mm;
    r->planner = hl_planner_create(&p);
    if (!r->planner)
        return false;
    hl_planner_set_allowed(r->planner, inside_fence, r->cycle);
    return true;
}

void robot_nav_destroy(hl_robot_t *r)
{
    hl_planner_destroy(r->planner);
    r->planner = NULL;
}

static void publish_path(hl_robot_t *r, int64_t seq, const hl_plan_path_t *way)
{
    hl_bus_path_t m = { .utime = r->epoch_us + r->robot_ms * 1000, .destination_seq = seq };
    if (way) {
        m.npoints = (int32_t)way->n;
        for (uint32_t i = 0; i < way->n && i < HL_BUS_PATH_MAX_POINTS; i++) {
            m.x_mm[i] = way->x_mm[i];
            m.y_mm[i] = way->y_mm[i];
        }
    }
    int len = hl_bus_encode_path(&m, r->buf, sizeof r->buf);
    if (len > 0)
        r->io.emit(r->io.ctx, HL_CH_PATH, r->buf, (size_t)len);
}

bool robot_nav_plan(hl_robot_t *r, int32_t goal_x, int32_t goal_y, char *why, size_t cap)
{
    hl_pose_t at = hl_cycle_estimate(r->cycle);
    const hl_map_t *map = hl_slam_map(hl_cycle_slam(r->cycle));
    hl_plan_path_t way;
    hl_plan_result_t res = hl_planner_plan(r->planner, hl_map_vectors(map), hl_map_count(map),
                                           at.x_mm, at.y_mm, goal_x, goal_y, &way);
    switch (res) {
    case HL_PLAN_OK:
        break;
    case HL_PLAN_GOAL_BLOCKED:
        snprintf(why, cap, "unreachable: the destination is %.2f m from an obstacle "
                 "(keep %.2f m) or outside the geofence",
                 hl_planner_goal_clearance(r->planner) / 1000.0, r->p.radius_mm / 1000.0);
        return false;
    case HL_PLAN_NO_PATH:
        snprintf(why, cap, "unreachable: no way on the map from (%.2f, %.2f) m", at.x_mm / 1000.0, at.y_mm / 1000.0);
        return false;
    default:
        snprintf(why, cap, "cannot plan: %s", hl_plan_result_name(res));
        return false;
    }
    if (way.n >= 2)
        hl_drive_set_via(&r->drive, way.x_mm[1], way.y_mm[1]);
    hl_log(HL_LOG_DEBUG, "destination %lld: planned %u points, %.2f m", (long long)r->dest_seq,
           way.n, way.length_mm / 1000.0);
    publish_path(r, r->dest_seq, &way);
    return true;
}

void robot_nav_end(hl_robot_t *r)
{
    hl_planner_clear_obstacles(r->planner);
    publish_path(r, -1, NULL);
}

int32_t robot_nav_ahead(hl_robot_t *r, const hl_arcos_sip_t *sip)
{
    hl_bam_t bearing[HL_ARCOS_SONAR_MAX];
    int32_t range[HL_ARCOS_SONAR_MAX];
    int32_t n = 0;
    for (int32_t i = 0; i < sip->sonar_count && i < (int32_t)HL_ARCOS_SONAR_MAX; i++) {
        int32_t t = sip->sonar[i].transducer, mm;
        if (t >= r->p.profile.transducers || !hl_calib_apply(&r->p.sounder.calib,
                                                             sip->sonar[i].range, &mm))
            continue;
        bearing[n] = r->p.profile.bearing[t];
        range[n++] = mm;
    }
    hl_safety_params_t sp = { .radius_mm = r->p.radius_mm,
                              .half_beam = (hl_bam_t)(SAFETY_HALF_BEAM_DEG * 65536 / 360) };
    int32_t which;
    int32_t ahead = hl_safety_ahead_mm(&sp, bearing, range, n, &which);
    if (ahead >= 0) {
        /* where the echo would lie on the transducer's axis, kept for robot_nav_blocked */
        hl_pose_t at = hl_cycle_estimate(r->cycle);
        double a = (at.theta + bearing[which]) * (6.283185307179586 / 65536.0);
        r->block_x = (hl_mm_t)lround(at.x_mm + ahead * cos(a));
        r->block_y = (hl_mm_t)lround(at.y_mm + ahead * sin(a));
    }
    return ahead < 0 ? 0 : ahead;
}

/* The front transducers for the safety stop: those within FRONT_DEG of ahead; the ones
 * within CORE_DEG of it fire twice as often. */
#define FRONT_DEG 50
#define CORE_DEG 25

static int32_t off_ahead_deg(hl_bam_t b)
{
    return abs((int32_t)(int16_t)b) * 360 / 65536;
}

/* The ahead order: the core, half the other front ones, the core again, the rest. */
static size_t ahead_order(const hl_robot_profile_t *pr, uint8_t *seq)
{
    uint8_t core[HL_ROBOT_MAX_TRANSDUCERS], rest[HL_ROBOT_MAX_TRANSDUCERS];
    size_t nc = 0, nr = 0, n = 0;
    for (int32_t t = 0; t < pr->transducers; t++) {
        int32_t off = off_ahead_deg(pr->bearing[t]);
        if (off <= CORE_DEG)
            core[nc++] = (uint8_t)(t + 1);      /* POLLING numbers them from 1 */
        else if (off <= FRONT_DEG)
            rest[nr++] = (uint8_t)(t + 1);
    }
    for (int pass = 0; pass < 2; pass++) {
        memcpy(seq + n, core, nc);
        n += nc;
        size_t from = pass ? nr / 2 : 0, to = pass ? nr : nr / 2;
        memcpy(seq + n, rest + from, to - from);
        n += to - from;
    }
    return n;
}

void robot_nav_polling(hl_robot_t *r, bool ahead, int64_t now_ms)
{
    if (r->polling_ahead == ahead)
        return;
    uint8_t seq[2 * HL_ROBOT_MAX_TRANSDUCERS];
    size_t n = ahead ? ahead_order(&r->p.profile, seq) : 0;
    if (ahead && n == 0)
        return;                     /* no transducer faces ahead: the ring as it is */
    if (!ahead)
        for (int32_t t = 0; t < r->p.profile.transducers; t++)
            seq[n++] = (uint8_t)(t + 1);
    if (!hl_rlink_send_str(&r->rlink, HL_ARCOS_POLLING, seq, n, now_ms)) {
        hl_log(HL_LOG_WARNING, "robot command POLLING not sent (link down or output full)");
        return;
    }
    hl_rlink_sent_at(&r->rlink, r->robot_ms);
    r->polling_ahead = ahead;
}

void robot_nav_blocked(hl_robot_t *r)
{
    if (hl_planner_add_obstacle(r->planner, r->block_x, r->block_y) != HL_OK)
        hl_log(HL_LOG_WARNING, "the safety stop's obstacle at (%.2f, %.2f) m is off the map",
               r->block_x / 1000.0, r->block_y / 1000.0);
}
