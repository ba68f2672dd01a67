/*
 * fuzz_bus.h - shared by the LCM message targets (fuzz_bus_*.c): the input is one
 * message as it arrives on the bus (an lcm_recv_buf_t's data, or an event of a log).
 *
 * include/bus/houghloc/bus.h promises, for every codec: a refusal is HL_ERR_PARSE or
 * HL_ERR_RANGE with a one-line reason; whatever decodes re-encodes to the same bytes
 * (a scan's embedded odometry extras aside). The targets check exactly that.
 */
#ifndef HOUGHLOC_TESTS_FUZZ_BUS_H
#define HOUGHLOC_TESTS_FUZZ_BUS_H

#include <string.h>

#include "fuzz.h"
#include "houghloc/bus.h"

/** A refusal: the right status and a one-line reason. */
static inline void fuzz_bus_refused(hl_status_t st, const char *why)
{
    FUZZ_CHECK(st == HL_ERR_PARSE || st == HL_ERR_RANGE);
    FUZZ_CHECK(memchr(why, '\0', HL_BUS_WHY_LEN) != NULL);
    FUZZ_CHECK(why[0] != '\0' && strchr(why, '\n') == NULL);
}

/** A position bus.h allows: |x|, |y| <= HL_COORD_MAX_MM. */
static inline bool fuzz_bus_xy_ok(int32_t x, int32_t y)
{
    return x >= -HL_COORD_MAX_MM && x <= HL_COORD_MAX_MM && y >= -HL_COORD_MAX_MM &&
           y <= HL_COORD_MAX_MM;
}

/** A one-line text bus.h allows: a NUL within HL_BUS_TEXT_MAX, no control character. */
static inline bool fuzz_bus_text_ok(const char *s)
{
    const char *nul = memchr(s, '\0', HL_BUS_TEXT_MAX);
    if (!nul)
        return false;
    for (const char *p = s; p < nul; p++)
        if ((unsigned char)*p < 0x20 || *p == 0x7f)
            return false;
    return true;
}

/** The re-encoding @p n of @p out is the input again. */
static inline void fuzz_bus_same(int n, const uint8_t *out, const uint8_t *data, size_t size)
{
    FUZZ_CHECK(n >= 0 && (size_t)n == size);
    FUZZ_CHECK(memcmp(out, data, size) == 0);
}

#endif
