/* timing.h - what the benchmarks share: a monotonic clock in microseconds and sorting of
 * timings (header-only; the benchmarks are separate programs). */
#ifndef HOUGHLOC_BENCH_TIMING_H
#define HOUGHLOC_BENCH_TIMING_H

#include <stdlib.h>
#include <time.h>

static inline double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e6 + ts.tv_nsec / 1e3;
}

static inline int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#endif
