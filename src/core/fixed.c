/* fixed.c - binary-angle trigonometry and conversions (formats: houghloc/fixed.h). */
#include "houghloc/fixed.h"

#include <math.h>

/* First-quadrant sine, Q14, generated at build time (tools/build/gen_trig_table.c). */
extern const int16_t hl_sin_quadrant[16385];

int16_t hl_sin(hl_bam_t a)
{
    uint32_t quadrant = a >> 14;
    uint32_t i = a & 0x3FFFu;
    switch (quadrant) {
    case 0: return hl_sin_quadrant[i];
    case 1: return hl_sin_quadrant[16384 - i];
    case 2: return (int16_t)-hl_sin_quadrant[i];
    default: return (int16_t)-hl_sin_quadrant[16384 - i];
    }
}

int16_t hl_cos(hl_bam_t a)
{
    return hl_sin((hl_bam_t)(a + 16384u));
}

/* Rounds r * t / 2^14 to nearest, ties away from zero, so results are symmetric. */
static int32_t mul_q14(int32_t r, int32_t t)
{
    int32_t p = r * t;  /* |p| <= 32767 * 16384 < 2^29 */
    return p >= 0 ? (p + (1 << 13)) >> 14 : -((-p + (1 << 13)) >> 14);
}

void hl_polar_to_xy(int32_t range_mm, hl_bam_t angle, int32_t *x_mm, int32_t *y_mm)
{
    if (range_mm < 0)
        range_mm = 0;
    if (range_mm > HL_RANGE_MAX_MM)
        range_mm = HL_RANGE_MAX_MM;
    *x_mm = mul_q14(range_mm, hl_cos(angle));
    *y_mm = mul_q14(range_mm, hl_sin(angle));
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
