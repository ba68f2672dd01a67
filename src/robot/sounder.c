/* sounder.c - the rotating sounding of a live robot (see sounder.h). */
#include "houghloc/sounder.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A position counts as reached when the measured heading is this close to the command
 * (the base's own controller stops within about a degree), or, failing that, when the
 * base has been still for this many settle periods: the measurement absorbs the rest. */
#define HEAD_TOLERANCE_BAM 273   /* 1.5 deg */
#define STILL_PERIODS_ANYWAY 3

void hl_sounder_params_default(hl_sounder_params_t *p)
{
    /* Fixed for houghlocd (not keys: docs/design/expert-keys.md): the paper's sounding, 8
     * positions 2.8125 degrees apart filling the 22.5-degree gaps of a 16-transducer ring;
     * a base still for 0.3 s has stopped rocking; 8 s holds a turn, the settling and a
     * reading of every transducer with time to spare. */
    p->steps = 8;
    p->step = 512;                  /* 2.8125 deg: 22.5 / 8 */
    p->settle_ms = 300;
    p->step_timeout_ms = 8000;
    hl_calib_default(&p->calib);
}

const char *hl_sounder_params_error(const hl_sounder_params_t *p)
{
    if (!p)
        return "no sounding parameters";
    if (p->steps < 1 || p->steps > HL_SOUNDER_MAX_STEPS)
        return "sounding steps must be 1..32";
    if (p->steps > 1 && (p->step < 1 || p->step > 16384))
        return "sounding step must be more than 0 and at most 90 degrees";
    if (p->settle_ms < 0 || p->settle_ms > 60000)
        return "sounding settle time must be 0..60000 ms";
    if (p->step_timeout_ms < 100 || p->step_timeout_ms > 600000)
        return "sounding step timeout must be 100..600000 ms";
    return hl_calib_error(&p->calib);
}

hl_status_t hl_sounder_init(hl_sounder_t *s, const hl_sounder_params_t *p,
                            const hl_robot_profile_t *profile)
{
    if (!s || !profile || hl_sounder_params_error(p) || profile->transducers < 1 ||
        profile->transducers > HL_ROBOT_MAX_TRANSDUCERS)
        return HL_ERR_ARG;
    memset(s, 0, sizeof *s);
    s->p = *p;
    s->profile = *profile;
    return HL_OK;
}

static void begin_step(hl_sounder_t *s, int32_t step, int64_t now_ms)
{
    s->step = step;
    s->step_start_ms = now_ms;
    s->still = false;
    s->at_rest = false;
    s->missing = s->profile.transducers;
    memset(s->have[step], 0, sizeof s->have[step]);
}

void hl_sounder_start(hl_sounder_t *s)
{
    s->state = HL_SOUNDER_BUSY;
    s->why[0] = '\0';
    s->step = -1;                   /* the next packet stops the base and starts step 0 */
}

void hl_sounder_cancel(hl_sounder_t *s)
{
    s->state = HL_SOUNDER_IDLE;
}

static hl_sounder_cmd_t fail(hl_sounder_t *s, const char *what)
{
    snprintf(s->why, sizeof s->why, "sounding position %d of %d: %s", s->step + 1, s->p.steps,
             what);
    s->state = HL_SOUNDER_FAILED;
    return HL_SOUNDER_CMD_STOP;
}

/* The heading command for a position: the nearest whole degree, 0..359. */
static int32_t whole_degrees(hl_bam_t heading)
{
    return (int32_t)(((int64_t)heading * 360 + 32768) / 65536) % 360;
}

static hl_bam_t target_of(const hl_sounder_t *s, int32_t step)
{
    return (hl_bam_t)(s->start_heading + step * s->p.step);
}

/* Whether the base has come to rest at the current position. */
static bool settled(hl_sounder_t *s, const hl_sounder_sip_t *sip)
{
    if (sip->moving) {
        s->still = false;
        return false;
    }
    if (!s->still) {
        s->still = true;
        s->still_since_ms = sip->robot_ms;
    }
    int64_t still_ms = sip->robot_ms - s->still_since_ms;
    if (still_ms < s->p.settle_ms)
        return false;
    if (s->step <= 0 || !s->turning)
        return true;
    hl_bam_t aim = (hl_bam_t)((int64_t)whole_degrees(target_of(s, s->step)) * 65536 / 360);
    int32_t off = abs(hl_bam_diff(sip->odometry.theta, aim));
    return off <= HEAD_TOLERANCE_BAM ||
           still_ms >= (int64_t)STILL_PERIODS_ANYWAY * s->p.settle_ms + s->p.settle_ms;
}

static void collect(hl_sounder_t *s, const hl_sounder_sip_t *sip)
{
    int32_t k = s->step;
    for (int32_t i = 0; i < sip->readings && i < HL_ROBOT_MAX_TRANSDUCERS; i++) {
        int32_t t = sip->transducer[i];
        if (t >= s->profile.transducers || s->have[k][t])
            continue;
        s->have[k][t] = true;
        s->raw[k][t] = sip->raw[i];
        s->missing--;
    }
}

hl_sounder_cmd_t hl_sounder_on_sip(hl_sounder_t *s, const hl_sounder_sip_t *sip,
                                   int32_t *head_deg)
{
    if (!s || !sip || !head_deg || s->state != HL_SOUNDER_BUSY)
        return HL_SOUNDER_CMD_NONE;
    if (s->step < 0) {
        s->turning = false;
        begin_step(s, 0, sip->robot_ms);
        return HL_SOUNDER_CMD_STOP;
    }
    if (sip->robot_ms - s->step_start_ms > s->p.step_timeout_ms) {
        char what[64];
        if (s->still)
            snprintf(what, sizeof what, "%d transducers gave no reading in %d ms", s->missing,
                     s->p.step_timeout_ms);
        else
            snprintf(what, sizeof what, "the base did not come to rest in %d ms",
                     s->p.step_timeout_ms);
        return fail(s, what);
    }
    if (!settled(s, sip)) {
        if (s->at_rest)
            begin_step(s, s->step, s->step_start_ms);   /* moved while reading: again */
        return HL_SOUNDER_CMD_NONE;
    }
    if (!s->at_rest) {
        /* the first packet at rest gives this position's heading; its readings were
         * fired before the base settled */
        s->at_rest = true;
        s->step_heading[s->step] = sip->odometry.theta;
        if (s->step == 0)
            s->start_heading = sip->odometry.theta;
        return HL_SOUNDER_CMD_NONE;
    }
    collect(s, sip);
    if (s->missing > 0)
        return HL_SOUNDER_CMD_NONE;
    if (s->step + 1 == s->p.steps) {
        s->odometry = sip->odometry;
        s->done_ms = sip->robot_ms;
        s->state = HL_SOUNDER_DONE;
        return HL_SOUNDER_CMD_NONE;
    }
    begin_step(s, s->step + 1, sip->robot_ms);
    s->turning = true;
    *head_deg = whole_degrees(target_of(s, s->step));
    return HL_SOUNDER_CMD_HEAD;
}

static int by_bearing(const void *a, const void *b)
{
    const hl_reading_t *x = a, *y = b;
    if (x->bearing != y->bearing)
        return x->bearing < y->bearing ? -1 : 1;
    return (x->transducer > y->transducer) - (x->transducer < y->transducer);
}

hl_status_t hl_sounder_take(hl_sounder_t *s, hl_scan_t *scan, hl_pose_t *odometry)
{
    if (!s || !scan || !odometry)
        return HL_ERR_ARG;
    if (s->state != HL_SOUNDER_DONE)
        return HL_ERR_EMPTY;
    hl_scan_clear(scan);
    for (int32_t k = 0; k < s->p.steps; k++) {
        hl_bam_t turn = (hl_bam_t)(s->step_heading[k] - s->odometry.theta);
        for (int32_t t = 0; t < s->profile.transducers; t++) {
            int32_t mm = 0;
            bool ok = hl_calib_apply(&s->p.calib, s->raw[k][t], &mm);
            hl_scan_add(scan, (hl_bam_t)(s->profile.bearing[t] + turn), ok ? mm : 0,
                        (int8_t)t, ok);
        }
    }
    qsort(scan->readings, scan->count, sizeof scan->readings[0], by_bearing);
    *odometry = s->odometry;
    s->state = HL_SOUNDER_IDLE;
    return HL_OK;
}
