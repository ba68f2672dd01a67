/*
 * floordiv.h (private) - floor(v / d) of a map coordinate by a multiply, for the place
 * index that divides every vector added by the same square (mapsq.c): a loop closure's
 * redraw adds tens of thousands of vectors a scan.
 *
 * Granlund and Montgomery's method: for n below 2^N and l = ceil(log2 d),
 * magic = ceil(2^(N + l) / d) gives floor(n / d) = n * magic >> (N + l) exactly. A
 * coordinate v (within +-HL_COORD_MAX_MM) is first offset by a multiple of d above
 * HL_COORD_MAX_MM, which keeps n below 2^24 for d up to 2^22 and the product below 2^50.
 * tests/core/test_map.c checks it against division at every square's edges.
 */
#ifndef HOUGHLOC_CORE_FLOORDIV_H
#define HOUGHLOC_CORE_FLOORDIV_H

#include <stdbool.h>
#include <stdint.h>

#include "houghloc/fixed.h"

typedef struct hl_floordiv {
    int32_t d;
    uint32_t offset;        /* a multiple of d, at least HL_COORD_MAX_MM */
    uint64_t magic;
    uint32_t shift;
} hl_floordiv_t;

/** Prepares division by @p d. @return false unless 1 <= d <= HL_COORD_MAX_MM. */
static inline bool hl_floordiv_init(hl_floordiv_t *f, int32_t d)
{
    if (d < 1 || d > HL_COORD_MAX_MM)
        return false;
    uint32_t l = 0;
    while ((1u << l) < (uint32_t)d)
        l++;
    f->d = d;
    f->shift = 24 + l;
    f->magic = ((1ull << f->shift) + (uint64_t)d - 1) / (uint64_t)d;
    f->offset = (uint32_t)d * (((uint32_t)HL_COORD_MAX_MM + (uint32_t)d - 1) / (uint32_t)d);
    return true;
}

/** floor(v / d) + offset / d, in 0 .. 2^24 - 1: the cell of @p v counted from a fixed
 *  cell below every coordinate (|v| <= HL_COORD_MAX_MM). */
static inline uint32_t hl_floordiv_from_base(const hl_floordiv_t *f, int32_t v)
{
    return (uint32_t)((uint64_t)((uint32_t)v + f->offset) * f->magic >> f->shift);
}

/** floor(v / d) (|v| <= HL_COORD_MAX_MM). */
static inline int32_t hl_floordiv(const hl_floordiv_t *f, int32_t v)
{
    return (int32_t)hl_floordiv_from_base(f, v) - (int32_t)(f->offset / (uint32_t)f->d);
}

#endif
