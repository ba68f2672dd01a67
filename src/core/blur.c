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

/*
 * Speed (docs/results/performance.md). Each output cell is a sum of tap * input products in
 * uint32 arithmetic, which is exact modulo 2^32 in any order or grouping (and the sums
 * stay below 2^32, blur.h): so the passes below give the integers of the plain
 * one-tap-at-a-time loops. They sum a block of LANES neighbouring output cells in
 * registers, all taps before one store (instead of adding each tap into memory); add the
 * two inputs of a mirrored tap pair before multiplying; and treat the rows (y pass) or
 * slices (theta pass) that the whole kernel covers as one long run.
 */
#define LANES 16
#define LINE_MAX 2048   /* longest x row blurred through the padded line */

/* out[q] = sum_k taps[k] * src[q + k * stride] for q in q0 .. q0 + LANES - 1, then
 * rounded >> 8 when `shift`. Written for the compiler to keep the block in registers. */
static inline void taps_block(const uint32_t *restrict src, uint32_t *restrict out, int64_t q0,
                              int64_t stride, const uint32_t *restrict taps, int32_t ntaps,
                              int shift)
{
    uint32_t acc[LANES] = { 0 };
    for (int32_t k = 0; k < ntaps; k++) {
        const uint32_t *s = src + q0 + k * stride;
        uint32_t t = taps[k];
        for (int l = 0; l < LANES; l++)
            acc[l] += t * s[l];
    }
    for (int l = 0; l < LANES; l++)
        out[q0 + l] = shift ? (acc[l] + 128u) >> 8 : acc[l];
}

/* The same for a kernel of 2r + 1 taps that mirror around the centre: the two inputs of
 * a tap pair are added first and multiplied once, which is the same sum modulo 2^32. */
static inline void taps_block_sym(const uint32_t *restrict src, uint32_t *restrict out,
                                  int64_t q0, int64_t stride, const uint32_t *restrict taps,
                                  int32_t r, int shift)
{
    uint32_t acc[LANES];
    const uint32_t *mid = src + q0 + r * stride;
    for (int l = 0; l < LANES; l++)
        acc[l] = taps[r] * mid[l];
    for (int32_t k = 0; k < r; k++) {
        const uint32_t *a = src + q0 + k * stride, *b = src + q0 + (2 * r - k) * stride;
        uint32_t t = taps[k];
        for (int l = 0; l < LANES; l++)
            acc[l] += t * (a[l] + b[l]);
    }
    for (int l = 0; l < LANES; l++)
        out[q0 + l] = shift ? (acc[l] + 128u) >> 8 : acc[l];
}

/* out[q] = sum_k taps[k] * src[q + k * stride] for q in [0, n), then rounded >> 8 when
 * `shift`; src must be readable from q to q + (ntaps - 1) * stride. `sym`: ntaps is odd
 * and the taps mirror around the centre. A run that does not end on a whole block ends
 * with a block that overlaps the one before: out and src are distinct, so its first
 * cells are computed again to the same values. */
HL_VECTOR_KERNEL
static void taps_run(const uint32_t *restrict src, uint32_t *restrict out, int64_t n,
                     int64_t stride, const uint32_t *restrict taps, int32_t ntaps, int sym,
                     int shift)
{
    int64_t q = 0;
    if (n >= LANES) {
        int64_t last = n - LANES;   /* the start of the last block */
        if (sym) {
            for (;; q += LANES) {
                q = q < last ? q : last;
                taps_block_sym(src, out, q, stride, taps, ntaps / 2, shift);
                if (q == last)
                    return;
            }
        }
        for (;; q += LANES) {
            q = q < last ? q : last;
            taps_block(src, out, q, stride, taps, ntaps, shift);
            if (q == last)
                return;
        }
    }
    for (; q < n; q++) {
        uint32_t acc = 0;
        for (int32_t k = 0; k < ntaps; k++)
            acc += taps[k] * src[q + k * stride];
        out[q] = shift ? (acc + 128u) >> 8 : acc;
    }
}

/* Whether a kernel's taps mirror around the centre (hl_kernel_gaussian's always do). */
static int symmetric(const hl_kernel_t *k)
{
    for (int32_t j = 0; j < k->radius; j++)
        if (k->taps[j] != k->taps[2 * k->radius - j])
            return 0;
    return 1;
}

/* out[i] = sum_j k[j] * in[i + j - r], zero outside [0, n). Loops over taps outside
 * so the inner loop is a plain multiply-add over a contiguous run (vectorizable). Used
 * for rows longer than LINE_MAX. */
HL_VECTOR_KERNEL
static void row_u16_long(const uint16_t *restrict in, uint32_t *restrict out, int32_t n,
                         const hl_kernel_t *k)
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

/* The x pass over `rows` rows of n cells: each row is copied between r zeros on either
 * side, then blurred as one run. */
static void x_pass(const uint16_t *in, uint32_t *out, int32_t n, int64_t rows,
                   const hl_kernel_t *k)
{
    int32_t r = k->radius;
    if (n > LINE_MAX) {
        for (int64_t row = 0; row < rows; row++)
            row_u16_long(in + row * n, out + row * n, n, k);
        return;
    }
    uint32_t line[LINE_MAX + 2 * HL_BLUR_MAX_RADIUS];
    int sym = symmetric(k);
    for (int32_t i = 0; i < r; i++)
        line[i] = line[r + n + i] = 0;
    for (int64_t row = 0; row < rows; row++) {
        const uint16_t *src = in + row * n;
        for (int32_t i = 0; i < n; i++)
            line[r + i] = src[i];
        taps_run(line, out + row * n, n, 1, k->taps, 2 * r + 1, sym, 0);
    }
}

/* Blurs `count` blocks of `len` lines spaced `stride` cells apart (a line is `stride`
 * contiguous cells; block b starts at b * len * stride): out line i = rounded
 * (sum_j k[j] * in line i + j) >> 8, zero outside [0, len). The lines the whole kernel
 * covers are one run; the r lines at either end have their own, shorter, kernels. */
static void axis_pass(const uint32_t *in, uint32_t *out, int32_t len, int64_t stride,
                      int64_t count, const hl_kernel_t *k)
{
    int32_t r = k->radius;
    int sym = symmetric(k);
    for (int64_t b = 0; b < count; b++) {
        const uint32_t *src = in + b * len * stride;
        uint32_t *dst = out + b * len * stride;
        for (int32_t i = 0; i < len;) {
            int32_t jlo = i - r < 0 ? -i : -r;
            int32_t jhi = i + r >= len ? len - 1 - i : r;
            int full = jlo == -r && jhi == r;
            int32_t lines = full ? len - r - i : 1; /* lines i .. len - r - 1 take every tap */
            taps_run(src + (i + jlo) * stride, dst + i * stride, lines * stride, stride,
                     k->taps + (jlo + r), jhi - jlo + 1, sym && full, 1);
            i += lines;
        }
    }
}

uint32_t *hl_blur3(const uint16_t *votes, int32_t nx, int32_t ny, int32_t nt,
                   const hl_kernel_t *kx, const hl_kernel_t *ky, const hl_kernel_t *kt,
                   uint32_t *buf_a, uint32_t *buf_b)
{
    int64_t plane = (int64_t)nx * ny;
    x_pass(votes, buf_a, nx, (int64_t)ny * nt, kx);
    /* y: lines of nx cells, one block per slice. */
    axis_pass(buf_a, buf_b, ny, nx, nt, ky);
    if (nt == 1 || kt->radius == 0)
        return buf_b;
    /* theta: lines of whole slices, one block. */
    axis_pass(buf_b, buf_a, nt, plane, 1, kt);
    return buf_a;
}

/* The largest of n values (vectorized). */
HL_VECTOR_KERNEL
static uint32_t max_of(const uint32_t *restrict v, int64_t n)
{
    uint32_t m = 0;
    for (int64_t i = 0; i < n; i++)
        m = v[i] > m ? v[i] : m;
    return m;
}

/*
 * The box's passes run in the order and with the roundings of hl_blur3's, on the box's
 * own small buffers: the x pass over its rows and ry rows either side (rows outside the
 * raster, and columns, are zero: what hl_blur3's edges' shorter kernels leave out), the
 * y pass over the box's rows (every tap, the missing rows being zero), the theta pass
 * through every slice (axis_pass, as hl_blur3's). Each output cell is the same sum of
 * the same products, hence the same integer.
 */
uint32_t hl_blur3_box(const uint16_t *votes, int32_t nx, int32_t ny, int32_t nt,
                      const hl_kernel_t *kx, const hl_kernel_t *ky, const hl_kernel_t *kt,
                      int32_t x0, int32_t y0, int32_t w, int32_t h, uint32_t *scratch,
                      uint32_t *out)
{
    int32_t rx = kx->radius, ry = ky->radius;
    int32_t rows = h + 2 * ry;  /* the x pass's rows: y0 - ry .. y0 + h + ry - 1 */
    size_t in_plane = (size_t)w * rows, plane = (size_t)w * h;
    uint32_t *a = scratch, *b = a + in_plane * nt;
    /* without a theta pass the y pass writes the result */
    int theta = nt > 1 && kt->radius > 0;
    uint32_t *yout = theta ? b : out;
    uint32_t line[HL_BLUR_BOX_MAX_W + 2 * HL_BLUR_MAX_RADIUS];
    int symx = symmetric(kx), symy = symmetric(ky);
    /* the line holds x0 - rx .. x0 + w + rx - 1; the raster's part is [jlo, jhi) */
    int32_t len = w + 2 * rx;
    int32_t jlo = x0 - rx < 0 ? rx - x0 : 0;
    int32_t jhi = x0 + w + rx > nx ? nx - (x0 - rx) : len;
    for (int32_t j = 0; j < jlo; j++)
        line[j] = 0;
    for (int32_t j = jhi; j < len; j++)
        line[j] = 0;
    for (int32_t it = 0; it < nt; it++) {
        for (int32_t i = 0; i < rows; i++) {
            int32_t y = y0 - ry + i;
            uint32_t *row = a + it * in_plane + (size_t)i * w;
            if (y < 0 || y >= ny) {
                memset(row, 0, (size_t)w * sizeof *row);
                continue;
            }
            const uint16_t *src = votes + ((size_t)it * ny + y) * nx;
            for (int32_t j = jlo; j < jhi; j++)
                line[j] = src[x0 - rx + j];
            taps_run(line, row, w, 1, kx->taps, 2 * rx + 1, symx, 0);
        }
        taps_run(a + it * in_plane, yout + it * plane, (int64_t)plane, w, ky->taps,
                 2 * ry + 1, symy, 1);
    }
    if (theta)
        axis_pass(b, out, nt, (int64_t)plane, 1, kt);
    return max_of(out, (int64_t)plane * nt);
}
