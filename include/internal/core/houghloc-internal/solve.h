/*
 * solve.h - a sparse symmetric positive definite solver for systems made of 3 x 3 blocks
 * (the normal equations of a pose graph: one block per pose, one per edge between its two
 * poses), on Eigen's sparse Cholesky (SimplicialLDLT) behind a C interface. The layer
 * lives in src/solve (C++17); nothing of Eigen or C++ crosses this header, so the pure-C
 * core may call it through a function pointer without seeing either.
 *
 * The matrix is given as a list of 3 x 3 blocks of its UPPER block triangle: block (row,
 * col) with row <= col, values row-major. Of a diagonal block (row == col) only its upper
 * triangle is read (its lower is ignored, as it mirrors it); an off-diagonal block is read
 * whole and stands for itself and its transpose at (col, row). Blocks naming the same
 * (row, col) are summed, so a caller may hand in each edge's contribution as it comes.
 * Unknown block i is unknowns 3i, 3i + 1, 3i + 2.
 *
 * The symbolic analysis (the fill-reducing ordering and the factor's pattern) is kept
 * across calls: a call whose block list names the same (row, col) in the same order as
 * the one analyzed before only refills the values and factors again (each Gauss-Newton
 * step of one fit shares the pattern), and says so in *pattern_reused.
 *
 * Memory: create reserves the matrix, the block-to-value map, the pattern's copy and the
 * conjugate gradients' vectors for the largest system; Eigen's own work (the ordering, the factor, its permuted copy of the
 * matrix) is allocated by Eigen inside the calls (docs/results/pose-graph-solver.md).
 * No call throws; every failure is a status.
 */
#ifndef HOUGHLOC_SOLVE_H
#define HOUGHLOC_SOLVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_solve_status {
    HL_SOLVE_OK = 0,
    HL_SOLVE_BAD_ARGUMENT,              /* a NULL, a size beyond the limits, a block below
                                           the diagonal or past the last unknown block, a
                                           value not a number */
    HL_SOLVE_NOT_POSITIVE_DEFINITE,     /* a pivot not positive: singular or indefinite */
    HL_SOLVE_NO_MEMORY,
    HL_SOLVE_NOT_CONVERGED,             /* conjugate gradients: no factorization to
                                           precondition by, or not within the iterations */
} hl_solve_status_t;

/* One 3 x 3 block of the matrix, at block row `row` and block column `col`. */
typedef struct hl_solve_block {
    uint32_t row, col;
    double v[9];                        /* row-major */
} hl_solve_block_t;

typedef struct hl_sparse_ldlt hl_sparse_ldlt_t;

/** A solver for up to @p max_block_rows unknown blocks (3 unknowns each) and up to
 * @p max_blocks blocks in a list; NULL on no memory or a zero limit. */
hl_sparse_ldlt_t *hl_sparse_ldlt_create(uint32_t max_block_rows, uint32_t max_blocks);
void hl_sparse_ldlt_destroy(hl_sparse_ldlt_t *s);      /* accepts NULL */

/** What create reserves for those limits, in bytes (Eigen's own work in the calls, the
 * ordering and the factor, comes on top). */
size_t hl_sparse_ldlt_mem_bytes(uint32_t max_block_rows, uint32_t max_blocks);

/**
 * The symbolic analysis of the pattern of @p blocks (@p n_blocks of them, over
 * @p n_block_rows unknown blocks), kept for the solves that follow with the same pattern.
 * hl_sparse_ldlt_solve calls it itself when the pattern changes; a caller calls it
 * beforehand only to pay for it at a time of its choosing (or to time it).
 */
hl_solve_status_t hl_sparse_ldlt_analyze(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                         const hl_solve_block_t *blocks, uint32_t n_blocks);

/**
 * Solves A x = @p rhs for @p x (both 3 * @p n_block_rows long; they may be the same
 * array), A the symmetric matrix of @p blocks. *@p pattern_reused (if not NULL) is set
 * to whether the analysis of the call before served. On an error @p x is left as it was.
 */
hl_solve_status_t hl_sparse_ldlt_solve(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                       const hl_solve_block_t *blocks, uint32_t n_blocks,
                                       const double *rhs, double *x, bool *pattern_reused);

/**
 * Solves A x = @p rhs (as hl_sparse_ldlt_solve, any pattern) by conjugate gradients
 * preconditioned by the last factorization hl_sparse_ldlt_solve made, without factoring
 * A: for a system near the one factored (the next Gauss-Newton step of a fit, or the
 * next fit with a pose added or a match dropped), where the old factor is nearly A's
 * own and a few iterations do. The factored unknown block b stands for this system's
 * block b - shift (hl_sparse_ldlt_shift); this system's blocks the factor does not hold
 * (new ones past it) are preconditioned by the inverses of their diagonal blocks.
 * Stops once r^T M^-1 r, the residual r in the preconditioner M's inverse, has fallen to
 * @p tolerance^2 of its value at x = 0 (*@p iterations, if not NULL, says how many
 * were taken). No allocation: the workspace comes from create.
 * @return HL_SOLVE_OK; HL_SOLVE_NOT_CONVERGED when no factorization is held, it holds
 * no block of this system, or @p max_iterations did not do (then the caller factors A);
 * HL_SOLVE_BAD_ARGUMENT as hl_sparse_ldlt_solve. On an error @p x is left as it was.
 */
hl_solve_status_t hl_sparse_ldlt_pcg(hl_sparse_ldlt_t *s, uint32_t n_block_rows,
                                     const hl_solve_block_t *blocks, uint32_t n_blocks,
                                     const double *rhs, double *x, double tolerance,
                                     uint32_t max_iterations, uint32_t *iterations);

/** The unknowns were renumbered since the last factorization: block b is now block
 *  b - @p k (the first @p k dropped, as a record forgets its oldest pose), so that the
 *  factorization still preconditions the blocks it holds (hl_sparse_ldlt_pcg). */
void hl_sparse_ldlt_shift(hl_sparse_ldlt_t *s, uint32_t k);

/* The status as a few words, for an error line. */
const char *hl_solve_status_name(hl_solve_status_t status);

#ifdef __cplusplus
}
#endif

#endif
