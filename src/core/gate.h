/*
 * gate.h (private) - the localizer's normal gate as a range of heading slices, for the
 * vote loop of localize.c: under which slices of a search a map vector's normal agrees
 * with a reading's within the gate, found with two multiplications instead of a test
 * per slice.
 */
#ifndef HOUGHLOC_CORE_GATE_H
#define HOUGHLOC_CORE_GATE_H

#include <stdbool.h>
#include <stdint.h>

/*
 * The normal gate as slices: a normal d0 (BAM from the test normal of slice 0) passes
 * under slice it when |d0 - it * step| <= gate, that is for it in
 * ceil((d0 - gate) / step) .. floor((d0 + gate) / step). The divisions are done by
 * multiplication with the same exact reciprocal as the cell index, on operands made
 * non-negative by adding a multiple of the step.
 */
typedef struct gate {
    int32_t gate, nt;
    uint32_t step;          /* 0: one slice, heading known */
    uint32_t offset;        /* k * step >= 2^15 + gate */
    int32_t k;
    uint64_t recip;         /* floor(2^32 / step) + 1 */
} gate_t;

static inline gate_t gate_make(int32_t gate, int32_t step, int32_t nt)
{
    gate_t g = { .gate = gate, .nt = nt, .step = (uint32_t)step };
    if (step > 0) {
        g.k = (int32_t)((32768u + (uint32_t)gate) / g.step + 1);
        g.offset = (uint32_t)g.k * g.step;
        g.recip = (1ull << 32) / g.step + 1;
    }
    return g;
}

static inline bool gated_slices(const gate_t *g, int32_t d0, int32_t *lo, int32_t *hi)
{
    if (g->step == 0) {
        *lo = *hi = 0;
        return d0 <= g->gate && d0 >= -g->gate;
    }
    /* both below 2^18: the reciprocal is exact there */
    uint32_t a = (uint32_t)(d0 - g->gate + (int32_t)g->offset) + g->step - 1;
    uint32_t b = (uint32_t)(d0 + g->gate + (int32_t)g->offset);
    int32_t l = (int32_t)((a * g->recip) >> 32) - g->k;
    int32_t h = (int32_t)((b * g->recip) >> 32) - g->k;
    *lo = l > 0 ? l : 0;
    *hi = h < g->nt - 1 ? h : g->nt - 1;
    return *lo <= *hi;
}

#endif
