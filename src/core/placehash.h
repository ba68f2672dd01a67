/*
 * placehash.h (private) - a map place's number hashed into a power-of-two table of
 * chains: what the place indexes share (mapsq.c, the squares of the density bound and
 * the crowding cull; mapdisc.c, the round places). At least twice as many buckets as
 * slots keeps the chains short.
 */
#ifndef HOUGHLOC_CORE_PLACEHASH_H
#define HOUGHLOC_CORE_PLACEHASH_H

#include <stdint.h>

/** The buckets for @p capacity slots: the power of two at least twice it. */
static inline uint32_t hl_place_buckets(uint32_t capacity)
{
    uint32_t buckets = 1;
    while (buckets < 2 * capacity)
        buckets <<= 1;
    return buckets;
}

/** The bucket of @p place among mask + 1 (Fibonacci hashing: the high bits of a multiply
 *  by 2^64 over the golden ratio, which spreads neighbouring squares apart). */
static inline uint32_t hl_place_bucket(uint64_t place, uint32_t mask)
{
    return (uint32_t)((place * 0x9E3779B97F4A7C15u) >> 32) & mask;
}

#endif
