/*
 * calib.h - raw sonar value -> millimetres, and the validity filter (paper, section 4).
 *
 * The paper fitted a linear function from (known distance, raw reading) pairs and
 * dropped two kinds of garbage: low raw values (echoes from the robot's own cables,
 * below 200) and the no-echo sentinel 16384.
 *
 *   mm = (raw * gain_q16 + 2^15) >> 16 + offset_mm
 *
 * gain_q16 is the slope in Q16 (65536 = 1 mm per raw unit); raw is 0..65535, so
 * raw * gain_q16 < 2^16 * 2^20 = 2^36: computed in int64.
 */
#ifndef HOUGHLOC_CALIB_H
#define HOUGHLOC_CALIB_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_calib {
    int32_t gain_q16;       /* mm per raw unit, Q16; 1..2^20 (default 65536) */
    int32_t offset_mm;      /* -10000..10000 (default 0) */
    uint16_t min_raw;       /* raw values below this are cable echoes (default 200) */
    uint16_t sentinel_raw;  /* raw values >= this mean "no echo" (default 16384) */
    int32_t max_range_mm;   /* calibrated ranges above this are invalid (default 10000) */
} hl_calib_t;

void hl_calib_default(hl_calib_t *c);
/** A one-line description of what is wrong, or NULL. */
const char *hl_calib_error(const hl_calib_t *c);

/**
 * Converts one raw reading.
 * @param[out] range_mm  calibrated range (clamped to 0..HL_RANGE_MAX_MM).
 * @return true if the reading is valid (not garbage, not sentinel, within max range).
 */
bool hl_calib_apply(const hl_calib_t *c, uint16_t raw, int32_t *range_mm);

/** The raw value a surface at @p range_mm would give (inverse, for simulators). */
uint16_t hl_calib_raw_for(const hl_calib_t *c, int32_t range_mm);

#ifdef __cplusplus
}
#endif
#endif
