/*
 * count.h - counters that never wrap.
 *
 * A counter that grows for as long as the daemon (or its map file) lives - scans, dropped
 * messages, map changes - is 64-bit and stops at HL_COUNT_MAX, the largest value an LCM
 * int64_t carries, rather than wrap: a wrapped counter would go out negative (which every
 * codec refuses, silencing STATUS or MAP for good) or run backwards (which readers would
 * take for an older map). At a million increments a second HL_COUNT_MAX is 292,000 years
 * away, so the limit is only ever met by a corrupted or crafted value; it then stays put.
 */
#ifndef HOUGHLOC_COUNT_H
#define HOUGHLOC_COUNT_H

#include <stdint.h>

#define HL_COUNT_MAX INT64_MAX

/** @p n plus one, or HL_COUNT_MAX when @p n is at (or above) it. */
static inline uint64_t hl_count_next(uint64_t n)
{
    return n < (uint64_t)HL_COUNT_MAX ? n + 1 : (uint64_t)HL_COUNT_MAX;
}

/** Adds @p k (>= 0) to the counter @p n, stopping at HL_COUNT_MAX. */
static inline void hl_count_add(int64_t *n, int64_t k)
{
    *n = k > HL_COUNT_MAX - *n ? HL_COUNT_MAX : *n + k;
}

#endif
