/* blur.c - separable integer Gaussian (formats and bounds: blur.h). */
#include "blur.h"
#include "simd.h"

#include <math.h>
#include <string.h>

void hl_kernel_gaussian(hl_kernel_t *k, double sigma_cells)
{
    memset(k, 0, sizeof *k);
    if (!(sigma_cells > 0.05)) {
        k->radius = 0;
        k->taps[0] = 256;
        return;
    }
    int32_t r = (int32_t)ceil(2.5 * sigma_cells);
    if (r > HL_BLUR_MAX_RADIUS)
        r = HL_BLUR_MAX_RADIUS;
    k->radius = r;
    double w[2 * HL_BLUR_MAX_RADIUS + 1], total = 0;
    for (int32_t i = -r; i <= r; i++) {
        w[i + r] = exp(-0.5 * (i * i) / (sigma_cells * sigma_cells));
        total += w[i + r];
    }
    uint32_t sum = 0;
    for (int32_t i = 0; i <= 2 * r; i++) {
        k->taps[i] = (uint32_t)lround(256.0 * w[i] / total);
        sum += k->taps[i];
    }
    /* Rounding may leave the sum a little off 256; the centre tap absorbs it so that
     * the overflow bound in blur.h holds exactly. */
    k->taps[r] = k->taps[r] + 256u - sum;
}

/* out[i] = sum_j k[j] * in[i + j - r], zero outside [0, n). Loops over taps outside
 * so the inner loop is a plain multiply-add over a contiguous run (vectorizable). */
HL_VECTOR_KERNEL
static void row_u16(const uint16_t *restrict in, uint32_t *restrict out, int32_t n, const hl_kernel_t *k)
{
    int32_t r = k->radius;
    memset(out, 0, (size_t)n * sizeof *out);
    for (int32_t j = -r; j <= r; j++) {
        uint32_t t = k->taps[j + r];
        int32_t lo = j < 0 ? -j : 0;
        int32_t hi = j > 0 ? n - j : n;
        for (int32_t i = lo; i < hi; i++)
            out[i] += t * in[i + j];
    }
}

/* Blurs `count` planes of `len` cells spaced `stride` apart along one axis:
 * out[p] = (sum_j k[j] * in[p + (j)*stride] + 128) >> 8 for p in plane q. */
HL_VECTOR_KERNEL
static void axis_u32(const uint32_t *restrict in, uint32_t *restrict out, int32_t n, int64_t stride,
                     int64_t outer, int64_t outer_stride, const hl_kernel_t *k)
{
    int32_t r = k->radius;
    for (int64_t o = 0; o < outer; o++) {
        const uint32_t *src = in + o * outer_stride;
        uint32_t *dst = out + o * outer_stride;
        for (int32_t i = 0; i < n; i++) {
            uint32_t *d = dst + i * stride;
            memset(d, 0, (size_t)stride * sizeof *d);
            int32_t jlo = i - r < 0 ? -i : -r;
            int32_t jhi = i + r >= n ? n - 1 - i : r;
            for (int32_t j = jlo; j <= jhi; j++) {
                uint32_t t = k->taps[j + r];
                const uint32_t *s = src + (i + j) * stride;
                for (int64_t p = 0; p < stride; p++)
                    d[p] += t * s[p];
            }
            for (int64_t p = 0; p < stride; p++)
                d[p] = (d[p] + 128u) >> 8;
        }
    }
}

uint32_t *hl_blur3(const uint16_t *votes, int32_t nx, int32_t ny, int32_t nt,
                   const hl_kernel_t *kx, const hl_kernel_t *ky, const hl_kernel_t *kt,
                   uint32_t *buf_a, uint32_t *buf_b)
{
    int64_t plane = (int64_t)nx * ny;
    for (int64_t row = 0; row < (int64_t)ny * nt; row++)
        row_u16(votes + row * nx, buf_a + row * nx, nx, kx);
    /* y: lines of nx cells, stride nx, one block per slice. */
    axis_u32(buf_a, buf_b, ny, nx, nt, plane, ky);
    if (nt == 1 || kt->radius == 0)
        return buf_b;
    /* theta: whole slices of nx * ny cells. */
    axis_u32(buf_b, buf_a, nt, plane, 1, 0, kt);
    return buf_a;
}
