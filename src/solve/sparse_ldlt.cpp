/* sparse_ldlt.cpp - the block SPD solver of solve.h on Eigen's SimplicialLDLT.
 *
 * The matrix is kept as Eigen's compressed column storage of its upper triangle. Each
 * block's nine values map once, at the analysis, to their places in that storage (or to
 * none: the lower half of a diagonal block), so a call with the pattern analyzed before
 * only zeroes the values, adds the blocks in and factors: no search, no triplets. */
#include "houghloc-internal/solve.h"

#include <cmath>
#include <cstdint>
#include <algorithm>
#include <new>
#include <vector>

#include "ldlt_state.h"

namespace {

/* A pivot of D at most this share of its row's diagonal in A is taken for zero: all but
 * this much of the row was explained by the rows before it, so the matrix is singular to
 * within rounding (relative to the row, so that rows of millimetres and rows of radians
 * are judged alike). */
constexpr double kPivotShare = 1e-12;

constexpr int kNoValue = -1;

uint64_t block_key(const hl_solve_block_t &b)
{
    return (static_cast<uint64_t>(b.row) << 32) | b.col;
}

}  // namespace

bool hl_blocks_valid(const hl_sparse_ldlt *s, uint32_t n_block_rows,
                  const hl_solve_block_t *blocks, uint32_t n_blocks)
{
    if (!s || !blocks || n_block_rows == 0 || n_block_rows > s->max_block_rows ||
        n_blocks == 0 || n_blocks > s->max_blocks)
        return false;
    for (uint32_t k = 0; k < n_blocks; k++) {
        const hl_solve_block_t &b = blocks[k];
        if (b.row > b.col || b.col >= n_block_rows)
            return false;
        for (double v : b.v)
            if (!std::isfinite(v))
                return false;
    }
    return true;
}

namespace {

bool same_pattern(const hl_sparse_ldlt *s, uint32_t n_block_rows,
                  const hl_solve_block_t *blocks, uint32_t n_blocks)
{
    if (!s->analyzed || n_block_rows != s->pattern_rows || n_blocks != s->pattern_blocks)
        return false;
    for (uint32_t k = 0; k < n_blocks; k++)
        if (block_key(blocks[k]) != s->pattern[k])
            return false;
    return true;
}

/* Where entry (r, c) of the upper triangle lies in a's values (its column's rows are
 * sorted). */
int place_of(const SparseMatrix &a, int r, int c)
{
    const int *rows = a.innerIndexPtr();
    int lo = a.outerIndexPtr()[c], hi = a.outerIndexPtr()[c + 1];
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (rows[mid] < r)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

hl_solve_status_t analyze(hl_sparse_ldlt *s, uint32_t n_block_rows,
                          const hl_solve_block_t *blocks, uint32_t n_blocks)
{
    s->analyzed = false;
    s->factored = false;
    const int n = 3 * static_cast<int>(n_block_rows);
    s->triplets.clear();
    for (uint32_t k = 0; k < n_blocks; k++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                if (blocks[k].row != blocks[k].col || i <= j)
                    s->triplets.emplace_back(3 * static_cast<int>(blocks[k].row) + i,
                                             3 * static_cast<int>(blocks[k].col) + j, 1.0);
    /* The diagonal is always in the pattern, so that a row no block reaches is a zero
     * pivot (refused) rather than a column Eigen cannot order. */
    for (int i = 0; i < n; i++)
        s->triplets.emplace_back(i, i, 0.0);
    s->a.resize(n, n);
    s->a.setFromTriplets(s->triplets.begin(), s->triplets.end());
    s->a.makeCompressed();
    for (uint32_t k = 0; k < n_blocks; k++) {
        s->pattern[k] = block_key(blocks[k]);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                bool lower_of_diagonal = blocks[k].row == blocks[k].col && i > j;
                s->value_of[9 * k + 3 * i + j] =
                    lower_of_diagonal ? kNoValue
                                      : place_of(s->a, 3 * static_cast<int>(blocks[k].row) + i,
                                                 3 * static_cast<int>(blocks[k].col) + j);
            }
    }
    s->ldlt.analyzePattern(s->a);
    if (s->ldlt.info() != Eigen::Success)
        return HL_SOLVE_NO_MEMORY;
    s->pattern_rows = n_block_rows;
    s->pattern_blocks = n_blocks;
    s->analyzed = true;
    return HL_SOLVE_OK;
}

/* Whether every pivot is positive and more than kPivotShare of its row's diagonal. */
bool pivots_positive(const hl_sparse_ldlt *s)
{
    const auto &d = s->ldlt.vectorD();
    const auto &to_permuted = s->ldlt.permutationP().indices();
    const SparseMatrix &a = s->a;
    for (int i = 0; i < a.cols(); i++) {
        int end = a.outerIndexPtr()[i + 1];
        double a_ii = a.innerIndexPtr()[end - 1] == i ? a.valuePtr()[end - 1] : 0;
        double d_i = d[to_permuted[i]];
        if (!(a_ii > 0) || !(d_i > kPivotShare * a_ii) || !std::isfinite(d_i))
            return false;
    }
    return true;
}

hl_solve_status_t solve(hl_sparse_ldlt *s, uint32_t n_block_rows, const hl_solve_block_t *blocks,
                        uint32_t n_blocks, const double *rhs, double *x, bool *pattern_reused)
{
    const int n = 3 * static_cast<int>(n_block_rows);
    for (int i = 0; i < n; i++)
        if (!std::isfinite(rhs[i]))
            return HL_SOLVE_BAD_ARGUMENT;
    bool reused = same_pattern(s, n_block_rows, blocks, n_blocks);
    if (pattern_reused)
        *pattern_reused = reused;
    if (!reused) {
        hl_solve_status_t st = analyze(s, n_block_rows, blocks, n_blocks);
        if (st != HL_SOLVE_OK)
            return st;
    }
    double *values = s->a.valuePtr();
    std::fill(values, values + s->a.nonZeros(), 0.0);
    for (uint32_t k = 0; k < n_blocks; k++)
        for (int e = 0; e < 9; e++) {
            int place = s->value_of[9 * k + e];
            if (place != kNoValue)
                values[place] += blocks[k].v[e];
        }
    s->factored = false;
    s->ldlt.factorize(s->a);
    if (s->ldlt.info() != Eigen::Success || !pivots_positive(s))
        return HL_SOLVE_NOT_POSITIVE_DEFINITE;
    s->factored = true;
    s->factored_rows = n_block_rows;
    s->shift = 0;
    s->rhs.head(n) = Eigen::Map<const Eigen::VectorXd>(rhs, n);
    Eigen::Map<Eigen::VectorXd>(x, n) = s->ldlt.solve(s->rhs.head(n));
    return HL_SOLVE_OK;
}

}  // namespace

extern "C" {

hl_sparse_ldlt_t *hl_sparse_ldlt_create(uint32_t max_block_rows, uint32_t max_blocks)
{
    if (max_block_rows == 0 || max_blocks == 0 || max_block_rows > INT32_MAX / 3 ||
        max_blocks > INT32_MAX / 9)
        return nullptr;
    hl_sparse_ldlt *s = nullptr;
    try {
        s = new hl_sparse_ldlt;
        s->max_block_rows = max_block_rows;
        s->max_blocks = max_blocks;
        s->value_of.resize(9 * static_cast<size_t>(max_blocks));
        s->pattern.resize(max_blocks);
        s->triplets.reserve(9 * static_cast<size_t>(max_blocks) + 3 * max_block_rows);
        s->rhs.resize(3 * static_cast<Eigen::Index>(max_block_rows));
        s->a.resize(3 * max_block_rows, 3 * max_block_rows);
        s->a.reserve(9 * static_cast<Eigen::Index>(max_blocks) + 3 * max_block_rows);
        hl_pcg_reserve(s);
    } catch (...) {     /* std::bad_alloc: Eigen and the vectors throw nothing else */
        delete s;
        return nullptr;
    }
    return s;
}

void hl_sparse_ldlt_destroy(hl_sparse_ldlt_t *s)
{
    delete s;
}

size_t hl_sparse_ldlt_mem_bytes(uint32_t max_block_rows, uint32_t max_blocks)
{
    size_t entries = 9 * static_cast<size_t>(max_blocks) + 3 * static_cast<size_t>(max_block_rows);
    return sizeof(hl_sparse_ldlt) +
           entries * (sizeof(double) + sizeof(int) + sizeof(Eigen::Triplet<double, int>)) +
           9 * static_cast<size_t>(max_blocks) * sizeof(int) + max_blocks * sizeof(uint64_t) +
           (3 * static_cast<size_t>(max_block_rows) + 1) * (sizeof(double) + sizeof(int)) +
           static_cast<size_t>(max_block_rows) * (5 * 3 + 9 + 9) * sizeof(double);
}

hl_solve_status_t hl_sparse_ldlt_analyze(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                         const hl_solve_block_t *blocks, uint32_t n_blocks)
{
    if (!hl_blocks_valid(s, n_block_rows, blocks, n_blocks))
        return HL_SOLVE_BAD_ARGUMENT;
    try {
        return analyze(s, n_block_rows, blocks, n_blocks);
    } catch (...) {
        s->analyzed = false;
        s->factored = false;
        return HL_SOLVE_NO_MEMORY;
    }
}

hl_solve_status_t hl_sparse_ldlt_solve(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                       const hl_solve_block_t *blocks, uint32_t n_blocks,
                                       const double *rhs, double *x, bool *pattern_reused)
{
    if (!rhs || !x || !hl_blocks_valid(s, n_block_rows, blocks, n_blocks))
        return HL_SOLVE_BAD_ARGUMENT;
    try {
        return solve(s, n_block_rows, blocks, n_blocks, rhs, x, pattern_reused);
    } catch (...) {
        s->analyzed = false;
        s->factored = false;
        return HL_SOLVE_NO_MEMORY;
    }
}

const char *hl_solve_status_name(hl_solve_status_t status)
{
    switch (status) {
    case HL_SOLVE_OK:
        return "ok";
    case HL_SOLVE_BAD_ARGUMENT:
        return "bad argument";
    case HL_SOLVE_NOT_POSITIVE_DEFINITE:
        return "matrix not positive definite";
    case HL_SOLVE_NO_MEMORY:
        return "no memory";
    case HL_SOLVE_NOT_CONVERGED:
        return "not converged";
    }
    return "unknown status";
}

}  // extern "C"
