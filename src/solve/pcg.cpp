/* pcg.cpp - conjugate gradients preconditioned by the last sparse LDL^T factorization
 * (solve.h, hl_sparse_ldlt_pcg).
 *
 * A Gauss-Newton fit's next step, or the next fit with a pose added, a few matches added
 * or dropped and the kernel's weights moved a little, has normal equations close to the
 * ones factored last: M = P^T L D L^T P differs from A by a few edges' terms, and
 * conjugate gradients on M^-1 A converge in a few iterations (at most one more than the
 * rank of A - M, in exact arithmetic). Each iteration costs one product with A (its
 * blocks, as given) and two triangular solves with L, no factorization.
 *
 * The factor's unknown block b stands for this system's block b - shift; a vector goes
 * into the factor's order with zeros at the blocks this system no longer has (so the
 * preconditioner is the principal part of M^-1 over the blocks both hold: symmetric
 * positive definite, as conjugate gradients need), and rows past the factor's get the
 * inverse of their own diagonal block. */
#include <algorithm>
#include <cmath>
#include <cstring>

#include "ldlt_state.h"

namespace {

/* y = A v, A the symmetric matrix of the blocks (upper block triangle; of a diagonal
 * block its upper triangle, mirrored). */
void multiply(const hl_solve_block_t *blocks, uint32_t n_blocks, const double *v, double *y,
              int n)
{
    std::memset(y, 0, static_cast<size_t>(n) * sizeof *y);
    for (uint32_t k = 0; k < n_blocks; k++) {
        const hl_solve_block_t &b = blocks[k];
        const double *vr = &v[3 * b.row], *vc = &v[3 * b.col];
        double *yr = &y[3 * b.row], *yc = &y[3 * b.col];
        const double *m = b.v;
        if (b.row == b.col) {
            yr[0] += m[0] * vr[0] + m[1] * vr[1] + m[2] * vr[2];
            yr[1] += m[1] * vr[0] + m[4] * vr[1] + m[5] * vr[2];
            yr[2] += m[2] * vr[0] + m[5] * vr[1] + m[8] * vr[2];
        } else {
            for (int i = 0; i < 3; i++) {
                yr[i] += m[3 * i] * vc[0] + m[3 * i + 1] * vc[1] + m[3 * i + 2] * vc[2];
                yc[i] += m[i] * vr[0] + m[3 + i] * vr[1] + m[6 + i] * vr[2];
            }
        }
    }
}

/* The inverse of the symmetric 3 x 3 matrix whose upper triangle @p u holds (summed over
 * the blocks), row-major into @p inv; false when it is not positive definite. */
bool invert_sym3(const double u[9], double inv[9])
{
    double a = u[0], b = u[1], c = u[2], d = u[4], e = u[5], f = u[8];
    double c0 = d * f - e * e, c1 = c * e - b * f, c2 = b * e - c * d;
    double det = a * c0 + b * c1 + c * c2;
    if (!(a > 0) || !(a * d - b * b > 0) || !(det > 0))
        return false;
    double inv_det = 1 / det;
    inv[0] = c0 * inv_det;
    inv[1] = inv[3] = c1 * inv_det;
    inv[2] = inv[6] = c2 * inv_det;
    inv[4] = (a * f - c * c) * inv_det;
    inv[5] = inv[7] = (b * c - a * e) * inv_det;
    inv[8] = (a * d - b * b) * inv_det;
    return true;
}

/* The inverses of the diagonal blocks of rows from..n_block_rows - 1. */
bool block_jacobi(hl_sparse_ldlt *s, uint32_t from, uint32_t n_block_rows,
                  const hl_solve_block_t *blocks, uint32_t n_blocks)
{
    if (from >= n_block_rows)
        return true;
    double *sum = s->in_factor.data();      /* free until the iterations start */
    std::memset(sum, 0, 9 * static_cast<size_t>(n_block_rows - from) * sizeof *sum);
    for (uint32_t k = 0; k < n_blocks; k++)
        if (blocks[k].row == blocks[k].col && blocks[k].row >= from)
            for (int e = 0; e < 9; e++)
                sum[9 * (blocks[k].row - from) + e] += blocks[k].v[e];
    for (uint32_t b = from; b < n_block_rows; b++)
        if (!invert_sym3(&sum[9 * (b - from)], &s->jacobi[9 * (b - from)]))
            return false;
    return true;
}

/* z = M^-1 r (header). */
void precondition(hl_sparse_ldlt *s, uint32_t n_block_rows, uint32_t held, const double *r,
                  double *z)
{
    const int m = 3 * static_cast<int>(s->factored_rows), lo = 3 * static_cast<int>(s->shift);
    const int *to_permuted = s->ldlt.permutationP().indices().data();
    double *t = s->in_factor.data();
    for (int i = 0; i < m; i++)
        t[to_permuted[i]] = i >= lo ? r[i - lo] : 0;
    Eigen::Map<Eigen::VectorXd> tm(t, m);
    s->ldlt.matrixL().solveInPlace(tm);
    tm.array() /= s->ldlt.vectorD().array();
    s->ldlt.matrixU().solveInPlace(tm);
    for (int i = lo; i < m; i++)
        z[i - lo] = t[to_permuted[i]];
    for (uint32_t b = held; b < n_block_rows; b++) {
        const double *inv = &s->jacobi[9 * (b - held)], *rb = &r[3 * b];
        for (int i = 0; i < 3; i++)
            z[3 * b + i] = inv[3 * i] * rb[0] + inv[3 * i + 1] * rb[1] + inv[3 * i + 2] * rb[2];
    }
}

double dot(const double *a, const double *b, int n)
{
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += a[i] * b[i];
    return sum;
}

}  // namespace

void hl_pcg_reserve(hl_sparse_ldlt *s)
{
    const Eigen::Index n = 3 * static_cast<Eigen::Index>(s->max_block_rows);
    for (Eigen::VectorXd *v : { &s->x, &s->r, &s->z, &s->p, &s->ap })
        v->resize(n);
    s->in_factor.resize(3 * n);     /* a vector of the factor's, or the diagonal blocks' sums */
    s->jacobi.resize(9 * static_cast<size_t>(s->max_block_rows));
}

extern "C" {

hl_solve_status_t hl_sparse_ldlt_pcg(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                     const hl_solve_block_t *blocks, uint32_t n_blocks,
                                     const double *rhs, double *x, double tolerance,
                                     uint32_t max_iterations, uint32_t *iterations)
{
    if (iterations)
        *iterations = 0;
    if (!rhs || !x || !hl_blocks_valid(s, n_block_rows, blocks, n_blocks))
        return HL_SOLVE_BAD_ARGUMENT;
    const int n = 3 * static_cast<int>(n_block_rows);
    for (int i = 0; i < n; i++)
        if (!std::isfinite(rhs[i]))
            return HL_SOLVE_BAD_ARGUMENT;
    if (!s->factored || s->shift >= s->factored_rows)
        return HL_SOLVE_NOT_CONVERGED;
    /* This system's blocks the factor holds: 0 .. held - 1. */
    uint32_t held = std::min(n_block_rows, s->factored_rows - s->shift);
    if (!block_jacobi(s, held, n_block_rows, blocks, n_blocks))
        return HL_SOLVE_NOT_CONVERGED;
    double *xk = s->x.data(), *r = s->r.data(), *z = s->z.data(), *p = s->p.data(),
           *ap = s->ap.data();
    std::memset(xk, 0, static_cast<size_t>(n) * sizeof *xk);
    std::memcpy(r, rhs, static_cast<size_t>(n) * sizeof *r);
    precondition(s, n_block_rows, held, r, z);
    std::memcpy(p, z, static_cast<size_t>(n) * sizeof *p);
    double rz = dot(r, z, n);
    const double enough = tolerance * tolerance * rz;
    uint32_t it = 0;
    while (rz > enough) {
        if (it == max_iterations)
            return HL_SOLVE_NOT_CONVERGED;
        it++;
        if (iterations)
            *iterations = it;
        multiply(blocks, n_blocks, p, ap, n);
        double pap = dot(p, ap, n);
        if (!(pap > 0) || !std::isfinite(pap))
            return HL_SOLVE_NOT_CONVERGED;
        double alpha = rz / pap;
        for (int i = 0; i < n; i++) {
            xk[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        precondition(s, n_block_rows, held, r, z);
        double rz_next = dot(r, z, n);
        double beta = rz_next / rz;
        rz = rz_next;
        for (int i = 0; i < n; i++)
            p[i] = z[i] + beta * p[i];
    }
    std::memcpy(x, xk, static_cast<size_t>(n) * sizeof *x);
    return HL_SOLVE_OK;
}

void hl_sparse_ldlt_shift(hl_sparse_ldlt_t *s, uint32_t k)
{
    if (s)
        s->shift = s->shift + k < s->shift ? UINT32_MAX : s->shift + k;
}

}  // extern "C"
