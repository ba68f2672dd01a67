/* walls.c - which way a building's walls run, from folded normals (walls.h). */
#include "houghloc-internal/walls.h"

#include <math.h>

#include "houghloc/fixed.h"

#define PI 3.14159265358979323846

/* A map's normals are counted in this many bins of the folded angle (0.09 degrees of
 * the angle each) and the bins summed: a map of 15,000 vectors costs 15,000 increments
 * and 1,024 cosines, not 30,000 of them. */
#define MAP_BINS 1024

typedef struct fold {
    double c, s;
    uint32_t n;
} fold_t;

static hl_walls_t axis_of(const fold_t *f)
{
    if (f->n == 0)
        return (hl_walls_t){ 0, 0, 0 };
    return (hl_walls_t){ atan2(f->s, f->c) / 4, hypot(f->c, f->s) / f->n, f->n };
}

hl_walls_t hl_walls_of_scan(const hl_scan_t *scan)
{
    fold_t f = { 0, 0, 0 };
    for (uint32_t k = 0; k < scan->count; k++) {
        if (!scan->readings[k].valid)
            continue;
        double a = 4 * hl_bam_to_rad(hl_reading_normal(&scan->readings[k], 0));
        f.c += cos(a);
        f.s += sin(a);
        f.n++;
    }
    return axis_of(&f);
}

hl_walls_t hl_walls_of_vectors(const hl_vector_t *v, uint32_t count)
{
    uint32_t bins[MAP_BINS] = { 0 };
    for (uint32_t i = 0; i < count; i++)    /* four times the angle, in its 16-bit turn */
        bins[(uint16_t)(v[i].normal * 4u) / (65536 / MAP_BINS)]++;
    fold_t f = { 0, 0, count };
    for (uint32_t b = 0; b < MAP_BINS; b++) {
        if (bins[b] == 0)
            continue;
        double a = (b + 0.5) * (2 * PI / MAP_BINS);
        f.c += bins[b] * cos(a);
        f.s += bins[b] * sin(a);
    }
    return axis_of(&f);
}

double hl_walls_offset(const hl_scan_t *scan, double heading, double axis, double window,
                       uint32_t *inliers)
{
    double sum = 0;
    uint32_t n = 0;
    for (uint32_t k = 0; k < scan->count; k++) {
        if (!scan->readings[k].valid)
            continue;
        double normal = heading + hl_bam_to_rad(hl_reading_normal(&scan->readings[k], 0));
        double off = remainder(4 * (normal - axis), 2 * PI) / 4;
        if (fabs(off) <= window) {
            sum += off;
            n++;
        }
    }
    *inliers = n;
    return n ? sum / n : 0;
}
