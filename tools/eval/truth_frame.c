/* truth_frame.c - GROUND_TRUTH in the daemon's map frame (truth_frame.h). */
#include "truth_frame.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc/fixed.h"

void hl_truth_frame_init(hl_truth_frame_t *f, hl_pose_t start)
{
    *f = (hl_truth_frame_t){ .start = start };
}

void hl_truth_frame_anchor(hl_truth_frame_t *f, hl_pose_t first)
{
    if (f->anchored)
        return;
    f->first = first;
    f->anchored = true;
}

/* Radians of a binary angle, from the signed degrees (exact to the unit). */
static double rad(hl_bam_t a)
{
    return hl_bam_to_sdeg(a) * (3.14159265358979323846 / 180.0);
}

bool hl_truth_frame_map(hl_truth_frame_t *f, hl_pose_t truth, hl_pose_t *out)
{
    hl_truth_frame_anchor(f, truth);
    /* In doubles, rounded once: composing in whole millimetres would round twice. */
    double c0 = cos(rad(f->first.theta)), s0 = sin(rad(f->first.theta));
    double dx = (double)truth.x_mm - f->first.x_mm, dy = (double)truth.y_mm - f->first.y_mm;
    double rx = c0 * dx + s0 * dy, ry = -s0 * dx + c0 * dy;    /* first^-1 (+) truth */
    double cs = cos(rad(f->start.theta)), ss = sin(rad(f->start.theta));
    double x = f->start.x_mm + cs * rx - ss * ry, y = f->start.y_mm + ss * rx + cs * ry;
    if (!(fabs(x) <= HL_COORD_MAX_MM && fabs(y) <= HL_COORD_MAX_MM))
        return false;
    *out = (hl_pose_t){ (hl_mm_t)lround(x), (hl_mm_t)lround(y),
                        (hl_bam_t)(f->start.theta + (truth.theta - f->first.theta)) };
    return true;
}

/* One decimal number of "X,Y,DEG" ending at @p stop; @return false if it is not one. */
static bool number(const char **s, char stop, double *out)
{
    if (isspace((unsigned char)**s))
        return false;
    char *end;
    errno = 0;
    *out = strtod(*s, &end);
    if (end == *s || *end != stop || !isfinite(*out) || errno)
        return false;
    *s = *end ? end + 1 : end;
    return true;
}

bool hl_truth_frame_parse_pose(const char *s, hl_pose_t *out, char *why)
{
    const char *p = s;
    double v[3];
    /* decimals only: strtod would also read hexadecimal */
    if (strpbrk(s, "xX") || !number(&p, ',', &v[0]) || !number(&p, ',', &v[1]) || !number(&p, '\0', &v[2])) {
        snprintf(why, HL_TRUTH_FRAME_WHY_LEN, "'%.60s' is not X,Y,DEG (metres, metres, "
                 "degrees)", s);
        return false;
    }
    for (int i = 0; i < 2; i++)
        if (fabs(round(v[i] * 1000.0)) > HL_COORD_MAX_MM) {
            snprintf(why, HL_TRUTH_FRAME_WHY_LEN, "'%.60s': %g m is outside +-%.3f m", s, v[i],
                     HL_COORD_MAX_MM / 1000.0);
            return false;
        }
    *out = (hl_pose_t){ (hl_mm_t)lround(v[0] * 1000.0), (hl_mm_t)lround(v[1] * 1000.0),
                        hl_bam_from_deg(fmod(v[2], 360.0)) };
    return true;
}
