/*
 * bench_solve - what one Gauss-Newton step's solve of loop closure's normal equations costs
 * on Eigen's sparse Cholesky (include/internal/core/houghloc-internal/solve.h) against Eigen's preconditioned
 * conjugate gradients, on the synthetic corridor graph of bench_posegraph.c
 * (docs/results/pose-graph-solver.md).
 *
 *   hl-bench-solve [--stops N] [--runs R]
 *
 * The graph is bench_posegraph.c's, made the same way (its generator copied below, on the
 * core's hl_pg_between / hl_pg_compose and the same seed): N stops (default 256, 2..4096)
 * back and forth along a 28 m corridor, a step between consecutive stops and up to 8
 * matches a stop, 5 % of them wrong. The normal equations are those of the first
 * Gauss-Newton step from the stops chained by their steps, every edge weighed the same
 * (the daemon's sigmas, no kernel), pose 0 held (left out: N - 1 unknown blocks). The
 * second system, for the reused pattern, is the same graph linearized at the true poses:
 * other values, the same blocks. Each time is the median of R runs (default 5). Prints
 * one line a method:
 *
 *   bench solve stops=N unknowns=N blocks=N method=M analyze_ms=X factor_solve_ms=X residual=X iterations=N
 *
 *   ldlt        a fresh solver: hl_sparse_ldlt_analyze (analyze_ms), then the first
 *               hl_sparse_ldlt_solve (values in, factor, solve)
 *   ldlt-reuse  hl_sparse_ldlt_solve of the second system, the analysis kept (analyze_ms 0)
 *   cg-ichol    Eigen's ConjugateGradient, IncompleteCholesky preconditioner: compute
 *               (analyze_ms) and solve, to a relative residual of 1e-6
 *   cg-jacobi   the same with the diagonal (Jacobi) preconditioner
 *
 * The conjugate gradients' times leave out putting the blocks into Eigen's matrix; the
 * solver's factor_solve_ms includes putting the values in. residual: |A x - b| / |b|.
 * Exit status: 0 done, 1 no memory or a solve failed, 2 bad usage (one line naming it).
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "houghloc-internal/solve.h"
#include "timing.h"

#include "corridor.h"
extern "C" {
#include "houghloc-internal/closure.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kMaxStops = HL_CLOSURE_MAX_STOPS;
constexpr double kSigmaMm = HL_CLOSURE_SIGMA_MM, kSigmaRad = HL_CLOSURE_SIGMA_DEG * kPi / 180;
constexpr double kWrongPct = 5;     /* hl-bench-posegraph's default */

struct Graph {
    std::vector<hl_pg_pose_t> truth, chained;
    std::vector<hl_pg_edge_t> edges;
};

/* hl-bench-posegraph's corridor tour, edge for edge (corridor.h). */
Graph corridor(uint32_t n)
{
    Graph g;
    g.truth.resize(n);
    g.chained.resize(n);
    g.edges.resize(sr_corridor_max_edges(n));
    g.edges.resize(sr_corridor(n, kWrongPct, g.truth.data(), g.chained.data(), g.edges.data()));
    return g;
}

using Mat3 = Eigen::Matrix3d;

/* The normal equations at @p poses (posegraph.c's error and Jacobians), pose 0 held: the
 * diagonal blocks first (pose i is block i - 1), then one block per edge between two free
 * poses, in the edges' order; rhs = -J^T W r. */
void normal_equations(const Graph &g, const std::vector<hl_pg_pose_t> &poses,
                      std::vector<hl_solve_block_t> &blocks, std::vector<double> &rhs)
{
    const uint32_t n = static_cast<uint32_t>(poses.size()), rows = n - 1;
    const Eigen::Vector3d w(1 / (kSigmaMm * kSigmaMm), 1 / (kSigmaMm * kSigmaMm),
                            1 / (kSigmaRad * kSigmaRad));
    std::vector<Mat3> diag(rows, Mat3::Zero());
    std::vector<hl_solve_block_t> between;
    rhs.assign(3 * rows, 0.0);
    for (const hl_pg_edge_t &e : g.edges) {
        const hl_pg_pose_t a = poses[e.from], b = poses[e.to];
        double c = std::cos(a.theta), s = std::sin(a.theta), dx = b.x - a.x, dy = b.y - a.y;
        Eigen::Vector3d r(c * dx + s * dy - e.rel.x, -s * dx + c * dy - e.rel.y,
                          std::remainder(b.theta - a.theta - e.rel.theta, 2 * kPi));
        Mat3 ja, jb;
        ja << -c, -s, -s * dx + c * dy, s, -c, -c * dx - s * dy, 0, 0, -1;
        jb << c, s, 0, -s, c, 0, 0, 0, 1;
        const auto W = w.asDiagonal();
        if (e.from > 0) {
            diag[e.from - 1] += ja.transpose() * W * ja;
            Eigen::Map<Eigen::Vector3d>(&rhs[3 * (e.from - 1)]) -= ja.transpose() * W * r;
        }
        if (e.to > 0) {
            diag[e.to - 1] += jb.transpose() * W * jb;
            Eigen::Map<Eigen::Vector3d>(&rhs[3 * (e.to - 1)]) -= jb.transpose() * W * r;
        }
        if (e.from > 0 && e.to > 0) {
            Mat3 ab = ja.transpose() * W * jb;
            uint32_t i = e.from - 1, j = e.to - 1;
            if (i > j) {
                std::swap(i, j);
                ab.transposeInPlace();
            }
            hl_solve_block_t blk{ i, j, {} };
            Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(blk.v) = ab;
            between.push_back(blk);
        }
    }
    blocks.clear();
    for (uint32_t i = 0; i < rows; i++) {
        hl_solve_block_t blk{ i, i, {} };
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(blk.v) = diag[i];
        blocks.push_back(blk);
    }
    blocks.insert(blocks.end(), between.begin(), between.end());
}

/* The whole symmetric matrix of the blocks, for the conjugate gradients and residuals. */
Eigen::SparseMatrix<double> full_matrix(uint32_t rows, const std::vector<hl_solve_block_t> &blocks)
{
    std::vector<Eigen::Triplet<double>> t;
    for (const hl_solve_block_t &b : blocks)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                int r = 3 * static_cast<int>(b.row) + i, c = 3 * static_cast<int>(b.col) + j;
                if (b.row == b.col) {
                    t.emplace_back(r, c, b.v[3 * std::min(i, j) + std::max(i, j)]);
                } else {
                    t.emplace_back(r, c, b.v[3 * i + j]);
                    t.emplace_back(c, r, b.v[3 * i + j]);
                }
            }
    Eigen::SparseMatrix<double> a(3 * rows, 3 * rows);
    a.setFromTriplets(t.begin(), t.end());
    return a;
}

double residual(const Eigen::SparseMatrix<double> &a, const std::vector<double> &rhs,
                const std::vector<double> &x)
{
    Eigen::Map<const Eigen::VectorXd> b(rhs.data(), rhs.size()), xv(x.data(), x.size());
    return (a * xv - b).norm() / b.norm();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

void print(uint32_t stops, uint32_t rows, size_t blocks, const char *method, double analyze_ms,
           double factor_solve_ms, double res, long iterations)
{
    std::printf("bench solve stops=%u unknowns=%u blocks=%zu method=%s analyze_ms=%.2f "
                "factor_solve_ms=%.2f residual=%.1e iterations=%ld\n",
                stops, 3 * rows, blocks, method, analyze_ms, factor_solve_ms, res, iterations);
}

template <typename Cg>
void time_cg(const char *method, uint32_t stops, uint32_t rows, const std::vector<hl_solve_block_t> &blocks,
             const std::vector<double> &rhs, int runs)
{
    Eigen::SparseMatrix<double> a = full_matrix(rows, blocks);
    Eigen::Map<const Eigen::VectorXd> b(rhs.data(), rhs.size());
    std::vector<double> compute_ms, solve_ms, x(rhs.size());
    long iterations = 0;
    for (int run = 0; run < runs; run++) {
        Cg cg;
        cg.setTolerance(1e-6);
        double t0 = now_us();
        cg.compute(a);
        double t1 = now_us();
        Eigen::Map<Eigen::VectorXd>(x.data(), x.size()) = cg.solve(b);
        double t2 = now_us();
        compute_ms.push_back((t1 - t0) / 1e3);
        solve_ms.push_back((t2 - t1) / 1e3);
        iterations = cg.iterations();
    }
    print(stops, rows, blocks.size(), method, median(compute_ms), median(solve_ms),
          residual(a, rhs, x), iterations);
}

int bad(const char *what, const char *value)
{
    std::fprintf(stderr, "hl-bench-solve: %s, not '%s' (--help)\n", what, value);
    return 2;
}

}  // namespace

int main(int argc, char **argv)
{
    long stops = 256, runs = 5;
    for (int i = 1; i < argc; i++) {
        char *end = nullptr;
        if (std::strcmp(argv[i], "--help") == 0) {
            std::printf("usage: hl-bench-solve [--stops N] [--runs R]\n"
                        "Times one Gauss-Newton step's solve of the corridor graph of N stops\n"
                        "(2..%u, default 256) each way, the median of R runs (1..100, default 5):\n"
                        "  bench solve stops=N unknowns=N blocks=N method=M analyze_ms=X "
                        "factor_solve_ms=X residual=X iterations=N\n", kMaxStops);
            return 0;
        } else if (std::strcmp(argv[i], "--stops") == 0 && i + 1 < argc) {
            stops = std::strtol(argv[++i], &end, 10);
            if (*end || end == argv[i] || stops < 2 || stops > static_cast<long>(kMaxStops))
                return bad("--stops wants 2..4096", argv[i]);
        } else if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
            runs = std::strtol(argv[++i], &end, 10);
            if (*end || end == argv[i] || runs < 1 || runs > 100)
                return bad("--runs wants 1..100", argv[i]);
        } else {
            return bad("an unknown option or one without its value", argv[i]);
        }
    }
    const uint32_t n = static_cast<uint32_t>(stops), rows = n - 1;
    Graph g = corridor(n);
    std::vector<hl_solve_block_t> blocks, blocks_truth;
    std::vector<double> rhs, rhs_truth, x(3 * rows);
    normal_equations(g, g.chained, blocks, rhs);
    normal_equations(g, g.truth, blocks_truth, rhs_truth);
    const uint32_t n_blocks = static_cast<uint32_t>(blocks.size());

    std::vector<double> analyze_ms, first_ms, reuse_ms;
    for (int run = 0; run < runs; run++) {
        hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(rows, n_blocks);
        if (!s) {
            std::fprintf(stderr, "hl-bench-solve: no memory for %u unknown blocks\n", rows);
            return 1;
        }
        bool reused = false, reused_again = false;
        double t0 = now_us();
        hl_solve_status_t st = hl_sparse_ldlt_analyze(s, rows, blocks.data(), n_blocks);
        double t1 = now_us();
        if (st == HL_SOLVE_OK)
            st = hl_sparse_ldlt_solve(s, rows, blocks.data(), n_blocks, rhs.data(), x.data(), &reused);
        double t2 = now_us();
        if (st == HL_SOLVE_OK)
            st = hl_sparse_ldlt_solve(s, rows, blocks_truth.data(), n_blocks, rhs_truth.data(),
                                      x.data(), &reused_again);
        double t3 = now_us();
        hl_sparse_ldlt_destroy(s);
        if (st != HL_SOLVE_OK || !reused || !reused_again) {
            std::fprintf(stderr, "hl-bench-solve: the sparse solve failed (%s%s)\n",
                         hl_solve_status_name(st), st == HL_SOLVE_OK ? ", pattern not reused" : "");
            return 1;
        }
        analyze_ms.push_back((t1 - t0) / 1e3);
        first_ms.push_back((t2 - t1) / 1e3);
        reuse_ms.push_back((t3 - t2) / 1e3);
    }
    double reuse_residual = residual(full_matrix(rows, blocks_truth), rhs_truth, x);
    {
        hl_sparse_ldlt_t *s = hl_sparse_ldlt_create(rows, n_blocks);
        if (!s || hl_sparse_ldlt_solve(s, rows, blocks.data(), n_blocks, rhs.data(), x.data(),
                                       nullptr) != HL_SOLVE_OK) {
            std::fprintf(stderr, "hl-bench-solve: the sparse solve failed\n");
            hl_sparse_ldlt_destroy(s);
            return 1;
        }
        hl_sparse_ldlt_destroy(s);
    }
    print(n, rows, blocks.size(), "ldlt", median(analyze_ms), median(first_ms),
          residual(full_matrix(rows, blocks), rhs, x), 0);
    print(n, rows, blocks.size(), "ldlt-reuse", 0, median(reuse_ms), reuse_residual, 0);
    time_cg<Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                                     Eigen::IncompleteCholesky<double>>>(
        "cg-ichol", n, rows, blocks, rhs, static_cast<int>(runs));
    time_cg<Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                                     Eigen::DiagonalPreconditioner<double>>>(
        "cg-jacobi", n, rows, blocks, rhs, static_cast<int>(runs));
    return 0;
}
