/* ldlt_state.h (the solve layer's own) - what a hl_sparse_ldlt_t holds, shared by the
 * factorization (sparse_ldlt.cpp) and the conjugate gradients it preconditions
 * (pcg.cpp). C++ only: Eigen's types cross no other header. */
#ifndef HOUGHLOC_SOLVE_LDLT_STATE_H
#define HOUGHLOC_SOLVE_LDLT_STATE_H

#include <cstdint>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "houghloc-internal/solve.h"

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper>;

struct hl_sparse_ldlt {
    uint32_t max_block_rows = 0, max_blocks = 0;
    SparseMatrix a;                             /* upper triangle */
    Ldlt ldlt;
    std::vector<int> value_of;                  /* [9 * max_blocks] place in a's values */
    std::vector<uint64_t> pattern;              /* [max_blocks] (row, col) analyzed */
    std::vector<Eigen::Triplet<double, int>> triplets;  /* [9 * max_blocks] */
    Eigen::VectorXd rhs;                        /* [3 * max_block_rows] so rhs may be x */
    uint32_t pattern_rows = 0, pattern_blocks = 0;
    bool analyzed = false;
    /* The factorization the conjugate gradients are preconditioned by (pcg.cpp): */
    bool factored = false;                      /* ldlt holds a good one */
    uint32_t factored_rows = 0;                 /* ... of this many unknown blocks */
    uint32_t shift = 0;                         /* ... its block b is block b - shift now */
    /* [3 * max_block_rows] each: the iteration's vectors, and one in the factor's order */
    Eigen::VectorXd x, r, z, p, ap, in_factor;
    std::vector<double> jacobi;                 /* [9 * max_block_rows] inverse diagonal
                                                   blocks of the rows the factor misses */
};

/* Whether the arguments name a system of @p s's limits: blocks of the upper block
 * triangle within @p n_block_rows, every value a number (solve.h's HL_SOLVE_BAD_ARGUMENT). */
bool hl_blocks_valid(const hl_sparse_ldlt *s, uint32_t n_block_rows,
                     const hl_solve_block_t *blocks, uint32_t n_blocks);

/* Sizes the conjugate gradients' workspace for the largest system (create). Throws
 * std::bad_alloc. */
void hl_pcg_reserve(hl_sparse_ldlt *s);

#endif
