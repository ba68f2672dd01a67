/* fixed.c - binary-angle trigonometry and conversions (formats: houghloc/fixed.h). */
#include "houghloc-internal/fixed.h"

#include <math.h>

/* First-quadrant sine, Q30, generated at build time (tools/build/gen_trig_table.c). */
extern const int32_t hl_sin_quadrant_q30[16385];

/* Sine in Q30, by symmetry from the first quadrant. */
static int32_t sin_q30(hl_bam_t a)
{
    uint32_t i = a & 0x3FFFu;
    switch (a >> 14) {
    case 0: return hl_sin_quadrant_q30[i];
    case 1: return hl_sin_quadrant_q30[16384 - i];
    case 2: return -hl_sin_quadrant_q30[i];
    default: return -hl_sin_quadrant_q30[16384 - i];
    }
}

/* v / 2^shift rounded to nearest, ties away from zero, so results are symmetric. */
static int64_t round_shift(int64_t v, int shift)
{
    int64_t half = (int64_t)1 << (shift - 1);
    return v >= 0 ? (v + half) >> shift : -((-v + half) >> shift);
}

int16_t hl_sin(hl_bam_t a)
{
    return (int16_t)round_shift(sin_q30(a), 30 - HL_TRIG_SHIFT);
}

int16_t hl_cos(hl_bam_t a)
{
    return hl_sin((hl_bam_t)(a + 16384u));
}

static int32_t clamp_range(int32_t range_mm)
{
    return range_mm < 0 ? 0 : (range_mm > HL_RANGE_MAX_MM ? HL_RANGE_MAX_MM : range_mm);
}

void hl_polar_to_xy(int32_t range_mm, hl_bam_t angle, int32_t *x_mm, int32_t *y_mm)
{
    int32_t r = clamp_range(range_mm);
    *x_mm = (int32_t)round_shift((int64_t)r * hl_cos(angle), HL_TRIG_SHIFT);
    *y_mm = (int32_t)round_shift((int64_t)r * hl_sin(angle), HL_TRIG_SHIFT);
}

void hl_polar_to_xy_q8(int32_t range_mm, hl_bam_t angle, int32_t *x_q8, int32_t *y_q8)
{
    int32_t r = clamp_range(range_mm);
    *x_q8 = (int32_t)round_shift((int64_t)r * sin_q30((hl_bam_t)(angle + 16384u)), 22);
    *y_q8 = (int32_t)round_shift((int64_t)r * sin_q30(angle), 22);
}

hl_bam_t hl_bam_from_deg(double deg)
{
    double turns = deg / 360.0;
    turns -= floor(turns);
    return (hl_bam_t)((long)llround(turns * 65536.0) & 0xFFFF);
}

hl_bam_t hl_bam_from_rad(double rad)
{
    return hl_bam_from_deg(rad * (180.0 / 3.14159265358979323846));
}

double hl_bam_to_deg(hl_bam_t a)
{
    return a * (360.0 / 65536.0);
}

double hl_bam_to_rad(hl_bam_t a)
{
    return a * (2.0 * 3.14159265358979323846 / 65536.0);
}

double hl_bam_to_sdeg(hl_bam_t a)
{
    return (int16_t)a * (360.0 / 65536.0);
}
