/* calib.c - linear sonar calibration and the garbage filter (paper, section 4). */
#include "houghloc/calib.h"

#include <stddef.h>

#include "houghloc/fixed.h"

void hl_calib_default(hl_calib_t *c)
{
    c->gain_q16 = 65536;
    c->offset_mm = 0;
    /* Fixed for houghlocd (docs/design/expert-keys.md): raw values below 200 are the
     * board's own cable echoes, 16384 and up its no-echo value, and nothing a sonar
     * reports past 10 m is a wall (the paper's filter, section 4). */
    c->min_raw = 200;
    c->sentinel_raw = 16384;
    c->max_range_mm = 10000;
}

const char *hl_calib_error(const hl_calib_t *c)
{
    if (c->gain_q16 < 1 || c->gain_q16 > (1 << 20))
        return "calibration gain must be in (0, 16] mm per raw unit";
    if (c->offset_mm < -10000 || c->offset_mm > 10000)
        return "calibration offset must be within +-10000 mm";
    if (c->min_raw >= c->sentinel_raw)
        return "calibration min_raw must be below sentinel_raw";
    if (c->max_range_mm < 1 || c->max_range_mm > HL_RANGE_MAX_MM)
        return "calibration max_range_mm must be in 1..32767";
    return NULL;
}

bool hl_calib_apply(const hl_calib_t *c, uint16_t raw, int32_t *range_mm)
{
    int64_t mm = (((int64_t)raw * c->gain_q16 + (1 << 15)) >> 16) + c->offset_mm;
    if (mm < 0)
        mm = 0;
    if (mm > HL_RANGE_MAX_MM)
        mm = HL_RANGE_MAX_MM;
    *range_mm = (int32_t)mm;
    return raw >= c->min_raw && raw < c->sentinel_raw && mm <= c->max_range_mm;
}

uint16_t hl_calib_raw_for(const hl_calib_t *c, int32_t range_mm)
{
    int64_t raw = (((int64_t)(range_mm - c->offset_mm) << 16) + c->gain_q16 / 2) / c->gain_q16;
    if (raw < 0)
        raw = 0;
    if (raw > UINT16_MAX)
        raw = UINT16_MAX;
    return (uint16_t)raw;
}
