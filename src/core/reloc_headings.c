/*
 * reloc_headings.c - the global search's first stage (reloc.h): the heading windows most
 * worth a coarse search, from the correlation of the scans' and the map's normals.
 */
#include "reloc_headings.h"

#define BINS 256                /* heading histogram bins: 256 BAM each, 1.4 deg */
#define BIN_SHIFT 8
#define MAX_WINDOWS 1024        /* heading windows tiling the circle */

/* reloc_headings.h says what; the windows are ranked by an insertion sort, stable. */
uint32_t hl_reloc_headings(const hl_reloc_params_t *p, const hl_vector_t *map, uint32_t n,
                           const hl_scan_t *const *scans, const hl_pose_t *offset,
                           uint32_t count, hl_bam_t *out, uint32_t max)
{
    uint32_t hs[BINS] = { 0 }, hm[BINS] = { 0 };
    for (uint32_t k = 0; k < count; k++) {
        const hl_scan_t *scan = scans[k];
        for (uint32_t i = 0; i < scan->count; i++)
            if (scan->readings[i].valid)
                hs[hl_reading_normal(&scan->readings[i], offset[k].theta) >> BIN_SHIFT]++;
    }
    for (uint32_t j = 0; j < n; j++)
        hm[map[j].normal >> BIN_SHIFT]++;
    uint64_t corr[BINS], smooth[BINS];
    for (uint32_t h = 0; h < BINS; h++) {
        uint64_t s = 0;
        for (uint32_t b = 0; b < BINS; b++)
            s += (uint64_t)hs[b] * hm[(b + h) & (BINS - 1)];
        corr[h] = s;
    }
    int32_t w = p->heading_smooth >> BIN_SHIFT;
    for (int32_t h = 0; h < BINS; h++) {
        uint64_t s = (uint64_t)(w + 1) * corr[h];
        for (int32_t k = 1; k <= w; k++)
            s += (uint64_t)(w + 1 - k) * (corr[(h + k) & (BINS - 1)] + corr[(h - k) & (BINS - 1)]);
        smooth[h] = s;
    }
    uint32_t span = 2u * p->coarse_half_steps * p->coarse_theta_step;
    uint32_t nwin = span ? (65536u + span - 1) / span : 1;
    nwin = nwin > MAX_WINDOWS ? MAX_WINDOWS : nwin;
    uint64_t worth[MAX_WINDOWS];
    uint32_t order[MAX_WINDOWS];
    for (uint32_t k = 0; k < nwin; k++) {
        /* bins whose centre lies within the window [centre - half, centre + half) */
        int64_t lo = (int64_t)k * 65536 / nwin - 32768 / nwin, hi = lo + 65536 / nwin;
        uint64_t best = 0;
        for (int64_t a = lo; a < hi; a += 1 << BIN_SHIFT)
            if (smooth[((uint32_t)a >> BIN_SHIFT) & (BINS - 1)] > best)
                best = smooth[((uint32_t)a >> BIN_SHIFT) & (BINS - 1)];
        worth[k] = best;
        order[k] = k;
    }
    for (uint32_t i = 1; i < nwin; i++)        /* insertion sort, descending, stable */
        for (uint32_t j = i; j > 0 && worth[order[j]] > worth[order[j - 1]]; j--) {
            uint32_t t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    uint32_t m = max < nwin ? max : nwin;
    for (uint32_t i = 0; i < m; i++)
        out[i] = (hl_bam_t)((uint64_t)order[i] * 65536 / nwin);
    return m;
}
