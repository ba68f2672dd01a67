/* rng.c - PCG32 (XSH RR variant), after O'Neill, "PCG: A Family of Simple Fast
 * Space-Efficient Statistically Good Algorithms for Random Number Generation" (2014). */
#include "houghloc-internal/rng.h"

void hl_rng_seed(hl_rng_t *rng, uint64_t seed)
{
    rng->state = 0;
    rng->inc = (seed << 1u) | 1u;
    (void)hl_rng_next(rng);
    rng->state += 0x853c49e6748fea9bULL ^ seed;
    (void)hl_rng_next(rng);
}

uint32_t hl_rng_next(hl_rng_t *rng)
{
    uint64_t old = rng->state;
    rng->state = old * 6364136223846793005ULL + rng->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

uint32_t hl_rng_below(hl_rng_t *rng, uint32_t bound)
{
    /* Reject the low values that would make the modulo biased. */
    uint32_t threshold = (0u - bound) % bound;
    for (;;) {
        uint32_t r = hl_rng_next(rng);
        if (r >= threshold)
            return r % bound;
    }
}
