/*
 * blur.h (private) - separable integer Gaussian blur of a 3-D vote raster.
 *
 * Kernels have integer taps summing to exactly 256 (Q8). The x pass reads the uint16
 * votes; the y and theta passes shift right by 8 with rounding, so the output is
 * votes x 256 and every intermediate stays below 65535 * 256 * 256 < 2^32
 * (houghloc/fixed.h). Outside the raster counts as zero.
 */
#ifndef HOUGHLOC_CORE_BLUR_H
#define HOUGHLOC_CORE_BLUR_H

#include <stdint.h>

#define HL_BLUR_MAX_RADIUS 24

typedef struct hl_kernel {
    int32_t radius;                          /* 0..HL_BLUR_MAX_RADIUS */
    uint32_t taps[2 * HL_BLUR_MAX_RADIUS + 1]; /* sum == 256 */
} hl_kernel_t;

/** Gaussian with @p sigma in cells (0 = identity); radius ceil(2.5 sigma), capped. */
void hl_kernel_gaussian(hl_kernel_t *k, double sigma_cells);

/**
 * Blurs votes [nt][ny][nx] using two scratch buffers of nx * ny * nt cells.
 * @return whichever of @p buf_a and @p buf_b holds the result (same layout).
 */
uint32_t *hl_blur3(const uint16_t *votes, int32_t nx, int32_t ny, int32_t nt,
                   const hl_kernel_t *kx, const hl_kernel_t *ky, const hl_kernel_t *kt,
                   uint32_t *buf_a, uint32_t *buf_b);

/** The widest box hl_blur3_box takes, and the scratch it needs for boxes of at most
 *  @p w x @p h cells and @p nt slices. */
#define HL_BLUR_BOX_MAX_W 64
#define HL_BLUR_BOX_SCRATCH(w, h, nt) \
    ((size_t)(w) * (size_t)(nt) * (2 * (size_t)(h) + 2 * HL_BLUR_MAX_RADIUS))

/**
 * hl_blur3's output on the cells x0 .. x0 + w - 1, y0 .. y0 + h - 1 of every slice of the
 * raster @p votes (the same integers: it reads the votes within the kernels' reach of
 * the box, zero outside the raster), written into @p out as a raster of its own,
 * [nt][h][w]. The box lies in the raster, 1 <= w <= HL_BLUR_BOX_MAX_W; @p scratch holds
 * HL_BLUR_BOX_SCRATCH(w, h, nt) cells.
 * @return the box's largest value.
 */
uint32_t hl_blur3_box(const uint16_t *votes, int32_t nx, int32_t ny, int32_t nt,
                      const hl_kernel_t *kx, const hl_kernel_t *ky, const hl_kernel_t *kt,
                      int32_t x0, int32_t y0, int32_t w, int32_t h, uint32_t *scratch,
                      uint32_t *out);

#endif
