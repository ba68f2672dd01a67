/*
 * reloc_headings.h (private) - stage 1 of the global search (reloc.h): which heading
 * windows to search.
 */
#ifndef HOUGHLOC_CORE_RELOC_HEADINGS_H
#define HOUGHLOC_CORE_RELOC_HEADINGS_H

#include <stdint.h>

#include "houghloc-internal/reloc.h"

/**
 * Fills @p out with the centres of the @p max heading windows most worth a coarse search
 * for the first of @p scans (each taken at @p offset[k] in the first's frame), best
 * first; @return how many. The circle is tiled with windows as wide as one coarse search
 * (2 x coarse_half_steps x coarse_theta_step), so that searching them all covers every
 * heading. A window's worth is the highest value inside it of the circular correlation
 * of the scans' normal histogram (each turned by its offset's heading) and the map's,
 * smoothed by a triangle of half-width heading_smooth: the headings that turn the scans'
 * walls onto the map's.
 */
uint32_t hl_reloc_headings(const hl_reloc_params_t *p, const hl_vector_t *map, uint32_t n,
                           const hl_scan_t *const *scans, const hl_pose_t *offset,
                           uint32_t count, hl_bam_t *out, uint32_t max);

#endif
