/* Tests for src/solve/sparse_ldlt.cpp and src/solve/pcg.cpp
 * (include/internal/core/houghloc-internal/solve.h): a small SPD block system against its
 * dense solution, blocks of one place summed, the pattern's analysis reused with new
 * values (and the same answer as a fresh solver), a singular and an indefinite system
 * refused, bad arguments refused; conjugate gradients on the last factorization solving
 * another system (other values; the unknowns renumbered and one added), and refusing
 * without a factorization or within too few iterations. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "houghloc-internal/solve.h"

#define ROWS 4                  /* unknown blocks */
#define N (3 * ROWS)            /* unknowns */
#define MAX_BLOCKS 16

/* A dense SPD matrix with the block pattern of a chain 0-1-2-3 and a loop 0-3: B^T B + I
 * over those blocks, B a fixed pseudo-random matrix masked to the pattern. */
static bool in_pattern(int bi, int bj)
{
    int lo = bi < bj ? bi : bj, hi = bi < bj ? bj : bi;
    return hi - lo <= 1 || (lo == 0 && hi == 3);
}

static void dense_spd(double a[N][N], double seed)
{
    double b[N][N];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            b[i][j] = in_pattern(i / 3, j / 3) && (i / 3 == j / 3 || i / 3 < j / 3)
                          ? sin(seed + 1.7 * i + 0.9 * j * j) : 0;
    /* a = b^T b + 2 I has the pattern's blocks (and B upper block triangular keeps the
     * fill inside the chain and the loop, as a pose graph's normal equations would). */
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double s = i == j ? 2 : 0;
            for (int k = 0; k < N; k++)
                s += b[k][i] * b[k][j];
            a[i][j] = in_pattern(i / 3, j / 3) ? s : 0;
        }
    /* Masking can only leave a matrix SPD when it is diagonally dominant: make it so. */
    for (int i = 0; i < N; i++) {
        double off = 0;
        for (int j = 0; j < N; j++)
            off += i == j ? 0 : fabs(a[i][j]);
        a[i][i] = off + 1 + 0.1 * i;
    }
}

/* The upper block triangle of a as blocks; the diagonal block of row 1 split in two
 * halves (they must be summed). Returns the count. */
static uint32_t to_blocks(double a[N][N], hl_solve_block_t *out)
{
    uint32_t n = 0;
    for (int bi = 0; bi < ROWS; bi++)
        for (int bj = bi; bj < ROWS; bj++) {
            if (!in_pattern(bi, bj))
                continue;
            hl_solve_block_t b = { (uint32_t)bi, (uint32_t)bj, { 0 } };
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    b.v[3 * i + j] = a[3 * bi + i][3 * bj + j];
            if (bi == 1 && bj == 1) {
                for (int e = 0; e < 9; e++)
                    b.v[e] /= 2;
                out[n++] = b;
            }
            out[n++] = b;
        }
    return n;
}

/* x = a^-1 rhs by Gaussian elimination with partial pivoting. */
static void dense_solve(double a_in[N][N], const double *rhs, double *x)
{
    double a[N][N + 1];
    for (int i = 0; i < N; i++) {
        memcpy(a[i], a_in[i], sizeof a_in[i]);
        a[i][N] = rhs[i];
    }
    for (int c = 0; c < N; c++) {
        int p = c;
        for (int r = c + 1; r < N; r++)
            if (fabs(a[r][c]) > fabs(a[p][c]))
                p = r;
        for (int k = 0; k <= N; k++) {
            double t = a[c][k];
            a[c][k] = a[p][k];
            a[p][k] = t;
        }
        for (int r = c + 1; r < N; r++) {
            double f = a[r][c] / a[c][c];
            for (int k = c; k <= N; k++)
                a[r][k] -= f * a[c][k];
        }
    }
    for (int r = N - 1; r >= 0; r--) {
        double s = a[r][N];
        for (int k = r + 1; k < N; k++)
            s -= a[r][k] * x[k];
        x[r] = s / a[r][r];
    }
}

static void fill_rhs(double *rhs)
{
    for (int i = 0; i < N; i++)
        rhs[i] = cos(0.3 * i) * (i + 1);
}

static void test_matches_dense_solution(void **state)
{
    (void)state;
    double a[N][N], rhs[N], want[N], got[N];
    hl_solve_block_t blocks[MAX_BLOCKS];
    dense_spd(a, 0.5);
    fill_rhs(rhs);
    dense_solve(a, rhs, want);
    uint32_t n_blocks = to_blocks(a, blocks);
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(ROWS, MAX_BLOCKS);
    assert_non_null(s);
    bool reused = true;
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, n_blocks, rhs, got, &reused),
                     HL_SOLVE_OK);
    assert_false(reused);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-10 * (1 + fabs(want[i])));
    /* The right-hand side may be the answer's array. */
    memcpy(got, rhs, sizeof got);
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, n_blocks, got, got, NULL),
                     HL_SOLVE_OK);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-10 * (1 + fabs(want[i])));
    hl_sparse_ldlt_destroy(s);
}

static void test_pattern_reused_same_answer(void **state)
{
    (void)state;
    double a[N][N], rhs[N], want[N], got[N], fresh[N];
    hl_solve_block_t blocks[MAX_BLOCKS];
    fill_rhs(rhs);
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(ROWS, MAX_BLOCKS);
    hl_sparse_ldlt_t *other = hl_sparse_ldlt_create(ROWS, MAX_BLOCKS);
    assert_non_null(s);
    assert_non_null(other);
    dense_spd(a, 0.5);
    uint32_t n_blocks = to_blocks(a, blocks);
    assert_int_equal(hl_sparse_ldlt_analyze(s, ROWS, blocks, n_blocks), HL_SOLVE_OK);
    /* New values, the same pattern: the analysis serves, the answer is the new one's. */
    dense_spd(a, 2.25);
    dense_solve(a, rhs, want);
    n_blocks = to_blocks(a, blocks);
    bool reused = false;
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, n_blocks, rhs, got, &reused),
                     HL_SOLVE_OK);
    assert_true(reused);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-10 * (1 + fabs(want[i])));
    assert_int_equal(hl_sparse_ldlt_solve(other, ROWS, blocks, n_blocks, rhs, fresh, &reused),
                     HL_SOLVE_OK);
    assert_false(reused);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - fresh[i]) <= 1e-12 * (1 + fabs(fresh[i])));
    /* One block fewer (the loop's, which comes before the last row's diagonal): a new
     * pattern, analyzed again, and still the right answer for what is left. */
    uint32_t loop = 0;
    while (!(blocks[loop].row == 0 && blocks[loop].col == 3))
        loop++;
    memmove(&blocks[loop], &blocks[loop + 1], (n_blocks - loop - 1) * sizeof blocks[0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            a[i][9 + j] = a[9 + j][i] = 0;
    dense_solve(a, rhs, want);
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, n_blocks - 1, rhs, got, &reused),
                     HL_SOLVE_OK);
    assert_false(reused);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-10 * (1 + fabs(want[i])));
    hl_sparse_ldlt_destroy(s);
    hl_sparse_ldlt_destroy(other);
}

static void test_singular_and_indefinite_refused(void **state)
{
    (void)state;
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(2, 4);
    assert_non_null(s);
    double rhs[6] = { 1, 2, 3, 4, 5, 6 }, x[6] = { 7, 7, 7, 7, 7, 7 };
    /* Block row 1 reached by no block: a zero row. */
    hl_solve_block_t lonely[1] = { { 0, 0, { 4, 1, 0, 1, 4, 0, 0, 0, 4 } } };
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, lonely, 1, rhs, x, NULL),
                     HL_SOLVE_NOT_POSITIVE_DEFINITE);
    assert_true(x[0] == 7 && x[5] == 7);        /* left as it was */
    /* Rank deficient: two identical rows across the blocks ([I I; I I]). */
    hl_solve_block_t twins[3] = {
        { 0, 0, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
        { 0, 1, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
        { 1, 1, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
    };
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, twins, 3, rhs, x, NULL),
                     HL_SOLVE_NOT_POSITIVE_DEFINITE);
    /* Indefinite: a negative eigenvalue, which LDL^T itself would carry through. */
    hl_solve_block_t negative[2] = {
        { 0, 0, { 2, 0, 0, 0, -1, 0, 0, 0, 2 } },
        { 1, 1, { 2, 0, 0, 0, 2, 0, 0, 0, 2 } },
    };
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, negative, 2, rhs, x, NULL),
                     HL_SOLVE_NOT_POSITIVE_DEFINITE);
    assert_true(x[0] == 7 && x[5] == 7);
    /* And after the refusals a good system still solves. */
    negative[0].v[4] = 2;
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, negative, 2, rhs, x, NULL), HL_SOLVE_OK);
    assert_true(fabs(x[4] - 2.5) < 1e-12 && fabs(x[5] - 3) < 1e-12);
    hl_sparse_ldlt_destroy(s);
}

static void test_bad_arguments_refused(void **state)
{
    (void)state;
    assert_null(hl_sparse_ldlt_create(0, 4));
    assert_null(hl_sparse_ldlt_create(4, 0));
    hl_sparse_ldlt_destroy(NULL);
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(2, 2);
    assert_non_null(s);
    double rhs[6] = { 1, 1, 1, 1, 1, 1 }, x[6];
    hl_solve_block_t ok[2] = {
        { 0, 0, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
        { 1, 1, { 1, 0, 0, 0, 1, 0, 0, 0, 1 } },
    };
    hl_solve_block_t b[3];
    memcpy(b, ok, sizeof ok);
    assert_int_equal(hl_sparse_ldlt_solve(NULL, 2, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, NULL, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, NULL, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, NULL, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 0, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 3, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 0, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    b[2] = ok[0];
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 3, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    b[1].row = 1;
    b[1].col = 0;               /* below the diagonal */
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    b[1].col = 2;               /* past the last block row */
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    b[1] = ok[1];
    b[1].v[4] = NAN;
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    assert_int_equal(hl_sparse_ldlt_analyze(s, 2, b, 2), HL_SOLVE_BAD_ARGUMENT);
    b[1] = ok[1];
    rhs[3] = INFINITY;
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, x, NULL), HL_SOLVE_BAD_ARGUMENT);
    rhs[3] = 1;
    assert_int_equal(hl_sparse_ldlt_solve(s, 2, b, 2, rhs, x, NULL), HL_SOLVE_OK);
    assert_true(fabs(x[3] - 1) < 1e-15);
    assert_string_equal(hl_solve_status_name(HL_SOLVE_NOT_POSITIVE_DEFINITE),
                        "matrix not positive definite");
    hl_sparse_ldlt_destroy(s);
}

/* The factorization of one matrix preconditions conjugate gradients on another of the
 * same pattern: the other's answer, in fewer iterations than unknowns. */
static void test_pcg_on_the_last_factorization(void **state)
{
    (void)state;
    double a[N][N], rhs[N], want[N], got[N];
    hl_solve_block_t blocks[MAX_BLOCKS];
    fill_rhs(rhs);
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(ROWS, MAX_BLOCKS);
    assert_non_null(s);
    dense_spd(a, 0.5);
    uint32_t n_blocks = to_blocks(a, blocks);
    uint32_t iterations = 99;
    /* Nothing factored yet: refused, x untouched. */
    got[0] = 7;
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 50,
                                        &iterations), HL_SOLVE_NOT_CONVERGED);
    assert_true(got[0] == 7);
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, n_blocks, rhs, got, NULL),
                     HL_SOLVE_OK);
    /* The same matrix: one iteration. */
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 50,
                                        &iterations), HL_SOLVE_OK);
    assert_int_equal(iterations, 1);
    dense_spd(a, 0.6);
    dense_solve(a, rhs, want);
    n_blocks = to_blocks(a, blocks);
    /* Too few iterations for another matrix: refused, x untouched. */
    got[0] = 7;
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 1,
                                        &iterations), HL_SOLVE_NOT_CONVERGED);
    assert_true(got[0] == 7);
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 50,
                                        &iterations), HL_SOLVE_OK);
    assert_true(iterations > 1 && iterations < N);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-8 * (1 + fabs(want[i])));
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, NULL, 1e-10, 50, NULL),
                     HL_SOLVE_BAD_ARGUMENT);
    hl_sparse_ldlt_destroy(s);
}

/* The unknowns renumbered after the factorization (the first block gone, the others one
 * down, a new last block): with the shift told, conjugate gradients still find the new
 * system's answer. */
static void test_pcg_after_a_shift(void **state)
{
    (void)state;
    double a[N][N], b[N][N], rhs[N], want[N], got[N];
    hl_solve_block_t blocks[MAX_BLOCKS];
    fill_rhs(rhs);
    hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(ROWS, MAX_BLOCKS);
    assert_non_null(s);
    dense_spd(a, 0.5);
    assert_int_equal(hl_sparse_ldlt_solve(s, ROWS, blocks, to_blocks(a, blocks), rhs, got, NULL),
                     HL_SOLVE_OK);
    /* b: a's blocks 1..3 as 0..2, and a new block 3 tied to block 2. */
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            b[i][j] = i < N - 3 && j < N - 3 ? a[i + 3][j + 3] : 0;
    for (int i = 0; i < 3; i++) {
        b[N - 3 + i][N - 3 + i] = 5;
        b[N - 6 + i][N - 3 + i] = b[N - 3 + i][N - 6 + i] = -1;
        b[N - 6 + i][N - 6 + i] += 1;
    }
    dense_solve(b, rhs, want);
    uint32_t n_blocks = 0;
    for (uint32_t bi = 0; bi < ROWS; bi++)
        for (uint32_t bj = bi; bj < ROWS; bj++) {
            hl_solve_block_t blk = { bi, bj, { 0 } };
            double sum = 0;
            for (int e = 0; e < 9; e++)
                sum += fabs(blk.v[e] = b[3 * bi + e / 3][3 * bj + e % 3]);
            if (sum > 0)
                blocks[n_blocks++] = blk;
        }
    hl_sparse_ldlt_shift(s, 1);
    uint32_t iterations = 0;
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 50,
                                        &iterations), HL_SOLVE_OK);
    assert_true(iterations > 1 && iterations < N);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-8 * (1 + fabs(want[i])));
    /* Shifted past everything it held: nothing to precondition by. */
    hl_sparse_ldlt_shift(s, ROWS);
    assert_int_equal(hl_sparse_ldlt_pcg(s, ROWS, blocks, n_blocks, rhs, got, 1e-10, 50, NULL),
                     HL_SOLVE_NOT_CONVERGED);
    hl_sparse_ldlt_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matches_dense_solution),
        cmocka_unit_test(test_pattern_reused_same_answer),
        cmocka_unit_test(test_singular_and_indefinite_refused),
        cmocka_unit_test(test_bad_arguments_refused),
        cmocka_unit_test(test_pcg_on_the_last_factorization),
        cmocka_unit_test(test_pcg_after_a_shift),
    };
    return cmocka_run_group_tests_name("sparse_ldlt", tests, NULL, NULL);
}
