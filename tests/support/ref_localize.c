/* ref_localize.c - floating-point reference localizer (see ref_localize.h). */
#include "ref_localize.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

struct ref_localizer {
    hl_loc_params_t p;
    double *votes, *tmp, *blur;     /* max_cells each */
};

ref_localizer_t *ref_create(const hl_loc_params_t *p)
{
    ref_localizer_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->p = *p;
    r->votes = calloc(p->max_cells, sizeof(double));
    r->tmp = calloc(p->max_cells, sizeof(double));
    r->blur = calloc(p->max_cells, sizeof(double));
    if (!r->votes || !r->tmp || !r->blur) {
        ref_destroy(r);
        return NULL;
    }
    return r;
}

void ref_destroy(ref_localizer_t *r)
{
    if (!r)
        return;
    free(r->votes);
    free(r->tmp);
    free(r->blur);
    free(r);
}

size_t ref_mem_bytes(const ref_localizer_t *r)
{
    return sizeof *r + 3 * (size_t)r->p.max_cells * sizeof(double);
}

static double wrap(double a)
{
    return a - 2 * PI * floor((a + PI) / (2 * PI));
}

/* The localizer's blur is defined as an integer Gaussian whose taps sum to 256
 * (src/core/blur.c); the reference uses the same weights in double, so the two differ
 * only by fixed-point arithmetic, not by kernel design. */
static int kernel(double sigma, double *k)
{
    if (!(sigma > 0.05)) {
        k[0] = 1;
        return 0;
    }
    int r = (int)ceil(2.5 * sigma);
    if (r > 24)
        r = 24;
    double w[49], total = 0, sum = 0;
    for (int i = -r; i <= r; i++)
        total += w[i + r] = exp(-0.5 * i * i / (sigma * sigma));
    for (int i = 0; i <= 2 * r; i++)
        sum += k[i] = round(256.0 * w[i] / total);
    k[r] += 256.0 - sum;
    for (int i = 0; i <= 2 * r; i++)
        k[i] /= 256.0;
    return r;
}

/* One axis of a separable blur: n cells along the axis, `stride` apart, `outer` blocks. */
static void blur_axis(const double *in, double *out, int n, long stride, long outer,
                      long outer_stride, const double *k, int r)
{
    for (long o = 0; o < outer; o++)
        for (long p = 0; p < stride; p++)
            for (int i = 0; i < n; i++) {
                double s = 0;
                for (int j = -r; j <= r; j++)
                    if (i + j >= 0 && i + j < n)
                        s += k[j + r] * in[o * outer_stride + (i + j) * stride + p];
                out[o * outer_stride + i * stride + p] = s;
            }
}

static double at(const double *g, int nx, int ny, int ix, int iy, int it)
{
    return g[((long)it * ny + iy) * nx + ix];
}

static double vertex(double l, double c, double r)
{
    double den = l - 2 * c + r;
    return den < 0 ? 0.5 * (l - r) / den : 0;
}

int ref_run(ref_localizer_t *r, const hl_vector_t *map, unsigned n, const hl_scan_t *scan,
            const hl_loc_query_t *q, ref_result_t *out)
{
    const hl_loc_params_t *p = &r->p;
    memset(out, 0, sizeof *out);
    if (n == 0)
        return -1;
    int cell = p->cell_mm, nx, ny, x0, y0;
    if (q->window_mm > 0) {
        nx = ny = (int)((2L * q->window_mm + cell - 1) / cell);
        x0 = q->predicted.x_mm - nx * cell / 2;
        y0 = q->predicted.y_mm - ny * cell / 2;
    } else {
        int x1 = map[0].x_mm, y1 = map[0].y_mm;
        x0 = x1;
        y0 = y1;
        for (unsigned i = 1; i < n; i++) {
            x0 = fmin(x0, map[i].x_mm);
            x1 = fmax(x1, map[i].x_mm);
            y0 = fmin(y0, map[i].y_mm);
            y1 = fmax(y1, map[i].y_mm);
        }
        nx = (x1 - x0) / cell + 1;
        ny = (y1 - y0) / cell + 1;
    }
    int half = q->search_theta ? p->theta_half_steps : 0, nt = 2 * half + 1;
    double step = q->search_theta ? p->theta_step : 0;     /* BAM */
    double theta0 = (double)q->predicted.theta - half * step;
    long cells = (long)nx * ny * nt;
    if (cells > (long)p->max_cells)
        return -1;
    memset(r->votes, 0, cells * sizeof(double));

    double gate = p->normal_gate * 2 * PI / 65536.0;
    for (int it = 0; it < nt; it++) {
        double heading = (theta0 + it * step) * 2 * PI / 65536.0;
        for (unsigned i = 0; i < scan->count; i++) {
            const hl_reading_t *rd = &scan->readings[i];
            if (!rd->valid)
                continue;
            double a = heading + rd->bearing * 2 * PI / 65536.0;
            double tx = rd->range_mm * cos(a), ty = rd->range_mm * sin(a);
            double tn = a + PI;
            for (unsigned k = 0; k < n; k++) {
                double mn = map[k].normal * 2 * PI / 65536.0;
                if (fabs(wrap(mn - tn)) > gate)
                    continue;
                int ix = (int)floor((map[k].x_mm - tx - x0) / cell);
                int iy = (int)floor((map[k].y_mm - ty - y0) / cell);
                if (ix < 0 || ix >= nx || iy < 0 || iy >= ny)
                    continue;
                r->votes[((long)it * ny + iy) * nx + ix] += 1;
                out->votes++;
            }
        }
    }
    if (out->votes == 0)
        return -1;

    double kx[49], kt[49];
    int rx = kernel((double)p->blur_sigma_mm / cell, kx);
    int rt = kernel(p->theta_step ? (double)p->blur_sigma_theta / p->theta_step : 0, kt);
    blur_axis(r->votes, r->tmp, nx, 1, (long)ny * nt, nx, kx, rx);
    blur_axis(r->tmp, r->blur, ny, nx, nt, (long)nx * ny, kx, rx);
    if (nt > 1 && rt > 0) {
        blur_axis(r->blur, r->tmp, nt, (long)nx * ny, 1, 0, kt, rt);
        memcpy(r->blur, r->tmp, cells * sizeof(double));
    }

    double best = 0;
    for (int it = 0; it < nt; it++)
        for (int iy = 0; iy < ny; iy++)
            for (int ix = 0; ix < nx; ix++)
                if (at(r->blur, nx, ny, ix, iy, it) > best) {
                    best = at(r->blur, nx, ny, ix, iy, it);
                    out->ix = ix;
                    out->iy = iy;
                    out->it = it;
                }
    double sep2 = (double)p->peak_separation_mm * p->peak_separation_mm, second = 0;
    for (int it = 0; it < nt; it++)
        for (int iy = 0; iy < ny; iy++)
            for (int ix = 0; ix < nx; ix++) {
                double dx = (ix - out->ix) * (double)cell, dy = (iy - out->iy) * (double)cell;
                if (dx * dx + dy * dy >= fmax(sep2, 1) && at(r->blur, nx, ny, ix, iy, it) > second)
                    second = at(r->blur, nx, ny, ix, iy, it);
            }
    out->peak = best * 256;
    out->second = second * 256;

    int ix = out->ix, iy = out->iy, it = out->it;
    double c = best;
    double ox = (ix > 0 && ix < nx - 1)
        ? vertex(at(r->blur, nx, ny, ix - 1, iy, it), c, at(r->blur, nx, ny, ix + 1, iy, it)) : 0;
    double oy = (iy > 0 && iy < ny - 1)
        ? vertex(at(r->blur, nx, ny, ix, iy - 1, it), c, at(r->blur, nx, ny, ix, iy + 1, it)) : 0;
    double ot = (it > 0 && it < nt - 1)
        ? vertex(at(r->blur, nx, ny, ix, iy, it - 1), c, at(r->blur, nx, ny, ix, iy, it + 1)) : 0;
    out->x_mm = x0 + (ix + 0.5) * cell + ox * cell;
    out->y_mm = y0 + (iy + 0.5) * cell + oy * cell;
    out->theta_bam = theta0 + it * step + ot * step;
    return 0;
}
