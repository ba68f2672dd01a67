/* posegraph.c - a 2-D pose graph by Gauss-Newton and a sparse Cholesky (posegraph.h). */
#include "houghloc-internal/posegraph.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/solve.h"

#define GN_STEPS 10             /* Gauss-Newton steps at most ... */
#define GN_STEPS_AFTER_DROP 3   /* ... and after matches are dropped, from the fit before */
/* ... until no pose moves more than this share of one edge's sigma in x, y and heading
 * (0.1 mm and 0.003 degrees at the daemon's): the last steps about halve each, so the
 * fit stops within about one more such step of where more steps would take it, far
 * below a map's 50 mm squares. The rule it replaced (0.01 mm, 1e-7 rad) took 13 steps
 * a refit of 4,096 stops, not 3 (docs/results/pose-graph-solver.md). */
#define GN_DONE_SHARE 0.002
#define MAX_DROPS 8             /* outliers dropped a fit at most */
/* A step is solved by conjugate gradients preconditioned by the last factorization (no
 * new one) while the poses have moved less than this since it was made ... */
#define PCG_MOVED_MM 100.0
#define PCG_MOVED_RAD 0.02
#define PCG_ITERATIONS 20       /* ... and the gradients converge within this many */
#define PCG_TOLERANCE 1e-4      /* ... to this share of the residual (solve.h) */

typedef struct { double v[9]; } mat3_t;     /* row-major */

typedef struct edge_terms {
    double r[3];        /* the edge's error at the current poses */
    mat3_t a, b;        /* its Jacobians in the `from` and `to` poses */
} edge_terms_t;

/* Each Gauss-Newton step's normal equations H dx = -g go to the solve layer as 3 x 3
 * blocks of H's upper triangle, pose 0 left out (held): first each pose's own block (block
 * row i - 1 for pose i), then one block per edge between two poses that move, in the
 * edges' order. The list's pattern is the same at every step of one fit, so the solver's
 * ordering and symbolic factor serve them all. */
struct hl_posegraph {
    uint32_t max_poses, max_edges;
    hl_sparse_ldlt_t *ldlt;
    hl_solve_block_t *blocks;       /* [max_poses + max_edges] */
    double match_weight;            /* hl_posegraph_weigh_matches; 1 from create */
    double *g, *dx;                 /* [3 * max_poses] each */
    double *cs;                     /* [2 * max_poses]: each pose's cosine and sine */
    double *chi2;                   /* [max_edges]: each loop edge's error (drop_outliers) */
    bool factored;                  /* the solver holds a factorization ... */
    double moved_mm, moved_rad;     /* ... and the poses moved this much since (the sum of
                                       the steps' largest moves) */
    hl_pg_work_t stats;
};

size_t hl_posegraph_mem_bytes(uint32_t max_poses, uint32_t max_edges)
{
    return sizeof(hl_posegraph_t) +
           ((size_t)max_poses + max_edges) * sizeof(hl_solve_block_t) +
           (size_t)max_poses * 4 * 2 * sizeof(double) + (size_t)max_edges * sizeof(double) +
           hl_sparse_ldlt_mem_bytes(max_poses, max_poses + max_edges);
}

hl_posegraph_t *hl_posegraph_create(uint32_t max_poses, uint32_t max_edges)
{
    if (max_poses < 2)
        return NULL;
    hl_posegraph_t *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->max_poses = max_poses;
    g->max_edges = max_edges;
    g->match_weight = 1;
    g->ldlt = hl_sparse_ldlt_create(max_poses - 1, max_poses + max_edges);
    g->blocks = calloc((size_t)max_poses + max_edges, sizeof *g->blocks);
    g->g = calloc(3 * (size_t)max_poses, sizeof *g->g);
    g->dx = calloc(3 * (size_t)max_poses, sizeof *g->dx);
    g->cs = calloc(2 * (size_t)max_poses, sizeof *g->cs);
    g->chi2 = calloc((size_t)max_edges + 1, sizeof *g->chi2);
    if (!g->ldlt || !g->blocks || !g->g || !g->dx || !g->cs || !g->chi2) {
        hl_posegraph_destroy(g);
        return NULL;
    }
    return g;
}

void hl_posegraph_destroy(hl_posegraph_t *g)
{
    if (!g)
        return;
    hl_sparse_ldlt_destroy(g->ldlt);
    free(g->blocks);
    free(g->g);
    free(g->dx);
    free(g->cs);
    free(g->chi2);
    free(g);
}

static double wrap(double a)
{
    return atan2(sin(a), cos(a));
}

hl_pg_pose_t hl_pg_from_pose(hl_pose_t p)
{
    return (hl_pg_pose_t){ p.x_mm, p.y_mm, hl_bam_to_rad(p.theta) };
}

static hl_mm_t clamp_mm(double v)
{
    return (hl_mm_t)lround(fmax(-HL_COORD_MAX_MM, fmin(HL_COORD_MAX_MM, v)));
}

hl_pose_t hl_pg_to_pose(hl_pg_pose_t p)
{
    return (hl_pose_t){ clamp_mm(p.x), clamp_mm(p.y), hl_bam_from_rad(p.theta) };
}

hl_pg_pose_t hl_pg_between(hl_pg_pose_t a, hl_pg_pose_t b)
{
    double c = cos(a.theta), s = sin(a.theta), dx = b.x - a.x, dy = b.y - a.y;
    return (hl_pg_pose_t){ c * dx + s * dy, -s * dx + c * dy, wrap(b.theta - a.theta) };
}

hl_pg_pose_t hl_pg_compose(hl_pg_pose_t a, hl_pg_pose_t rel)
{
    double c = cos(a.theta), s = sin(a.theta);
    return (hl_pg_pose_t){ a.x + c * rel.x - s * rel.y, a.y + s * rel.x + c * rel.y,
                           wrap(a.theta + rel.theta) };
}

/* Each pose's cosine and sine into @p cs, once for all the edges from it. */
static void pose_trig(const hl_pg_pose_t *poses, uint32_t n, double *cs)
{
    for (uint32_t i = 0; i < n; i++) {
        cs[2 * i] = cos(poses[i].theta);
        cs[2 * i + 1] = sin(poses[i].theta);
    }
}

/* The edge's error (the measured relative pose against the poses' own) and Jacobians, @p cs
 * the poses' cosines and sines (pose_trig). */
static void linearize(const hl_pg_pose_t *poses, const double *cs, const hl_pg_edge_t *e,
                      edge_terms_t *t)
{
    hl_pg_pose_t a = poses[e->from], b = poses[e->to];
    double c = cs[2 * e->from], s = cs[2 * e->from + 1], dx = b.x - a.x, dy = b.y - a.y;
    t->r[0] = c * dx + s * dy - e->rel.x;
    t->r[1] = -s * dx + c * dy - e->rel.y;
    t->r[2] = wrap(b.theta - a.theta - e->rel.theta);
    t->a = (mat3_t){ { -c, -s, -s * dx + c * dy,
                       s, -c, -c * dx - s * dy,
                       0, 0, -1 } };
    t->b = (mat3_t){ { c, s, 0,
                       -s, c, 0,
                       0, 0, 1 } };
}

/* out += a^T diag(w) b, and the same for vectors below. */
static void add_atwb(mat3_t *out, const mat3_t *a, const double w[3], const mat3_t *b)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                out->v[3 * i + j] += a->v[3 * k + i] * w[k] * b->v[3 * k + j];
}

static void add_jtw(double *out, const mat3_t *m, const double w[3], const double r[3])
{
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            out[i] += m->v[3 * k + i] * w[k] * r[k];
}

/* An edge's squared error in standard deviations, summed over its three terms. */
static double squared_sigmas(const edge_terms_t *t, const double w[3])
{
    return t->r[0] * t->r[0] * w[0] + t->r[1] * t->r[1] * w[1] + t->r[2] * t->r[2] * w[2];
}

/* A fit's fixed inputs besides the poses and edges: the headings of the poses' own, the
 * edges' weights and the kernel. */
typedef struct problem {
    const hl_pg_heading_t *headings;
    uint32_t n_headings;
    double sigma_mm, sigma_rad;
    double w[3];            /* steps' and matches' weights: 1 / sigma^2 */
    double kernel;
} problem_t;

/* Adds @p m (or its transpose) into the solver's block @p out. */
static void add_into(hl_solve_block_t *out, const mat3_t *m, bool transposed)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out->v[3 * i + j] += transposed ? m->v[3 * j + i] : m->v[3 * i + j];
}

/* H dx = -g for g->dx[3 ..]: by conjugate gradients on the last factorization while the
 * poses have moved little since it was made (a refit, the last steps of a fit), else by a
 * new factorization, which the steps after are preconditioned by. */
static hl_solve_status_t solve_step(hl_posegraph_t *g, uint32_t n, uint32_t n_blocks)
{
    if (g->factored && g->moved_mm < PCG_MOVED_MM && g->moved_rad < PCG_MOVED_RAD) {
        uint32_t iterations = 0;
        hl_solve_status_t st = hl_sparse_ldlt_pcg(g->ldlt, n - 1, g->blocks, n_blocks, &g->g[3],
                                                  &g->dx[3], PCG_TOLERANCE, PCG_ITERATIONS,
                                                  &iterations);
        g->stats.pcg_iterations += iterations;
        if (st == HL_SOLVE_OK) {
            g->stats.pcg_solves++;
            return st;
        }
        g->stats.pcg_failures++;
    }
    g->factored = false;
    bool reused = false;
    hl_solve_status_t st = hl_sparse_ldlt_solve(g->ldlt, n - 1, g->blocks, n_blocks, &g->g[3],
                                                &g->dx[3], &reused);
    g->stats.analyses += !reused;
    if (st != HL_SOLVE_OK)
        return st;
    g->stats.factorizations++;
    g->factored = true;
    g->moved_mm = g->moved_rad = 0;
    return st;
}

/* One Gauss-Newton step of iteratively reweighted least squares: g->dx solves H dx = -g,
 * pose 0 held, each loop edge weighed by the Cauchy kernel at the current poses. A
 * heading adds to its pose's own block alone. @return false when the solver refuses
 * the system (a pose nothing ties to the held one): g->dx is then zero. */
static bool gauss_newton_step(hl_posegraph_t *g, const hl_pg_pose_t *poses, uint32_t n,
                              const hl_pg_edge_t *edges, uint32_t n_edges,
                              const problem_t *pb)
{
    const double *w = pb->w;
    const double kernel = pb->kernel;
    hl_solve_block_t *own = g->blocks;          /* pose i's at own[i - 1] */
    uint32_t n_blocks = n - 1;
    memset(g->g, 0, 3 * n * sizeof *g->g);
    memset(g->dx, 0, 3 * n * sizeof *g->dx);
    for (uint32_t i = 1; i < n; i++)
        own[i - 1] = (hl_solve_block_t){ i - 1, i - 1, { 0 } };
    pose_trig(poses, n, g->cs);
    for (uint32_t k = 0; k < n_edges; k++) {
        edge_terms_t t;
        uint32_t i = edges[k].from, j = edges[k].to;
        linearize(poses, g->cs, &edges[k], &t);
        double robust = edges[k].loop && kernel > 0
                            ? 1 / (1 + squared_sigmas(&t, w) / (kernel * kernel)) : 1;
        if (edges[k].loop)
            robust *= g->match_weight;
        const double wk[3] = { w[0] * robust, w[1] * robust, w[2] * robust };
        add_jtw(&g->g[3 * i], &t.a, wk, t.r);
        add_jtw(&g->g[3 * j], &t.b, wk, t.r);
        mat3_t aa = { { 0 } }, bb = { { 0 } }, ab = { { 0 } };
        add_atwb(&aa, &t.a, wk, &t.a);
        add_atwb(&bb, &t.b, wk, &t.b);
        if (i > 0)
            add_into(&own[i - 1], &aa, false);
        if (j > 0)
            add_into(&own[j - 1], &bb, false);
        if (i > 0 && j > 0 && i != j) {
            add_atwb(&ab, &t.a, wk, &t.b);      /* H's block (i, j) */
            hl_solve_block_t *between = &g->blocks[n_blocks++];
            *between = (hl_solve_block_t){ (i < j ? i : j) - 1, (i < j ? j : i) - 1, { 0 } };
            add_into(between, &ab, i > j);
        }
    }
    for (uint32_t k = 0; k < pb->n_headings; k++) {
        const hl_pg_heading_t *h = &pb->headings[k];
        if (h->pose == 0)
            continue;
        double r = wrap(poses[h->pose].theta - h->theta), wh = 1 / (h->sigma_rad * h->sigma_rad);
        g->g[3 * h->pose + 2] += wh * r;
        own[h->pose - 1].v[8] += wh;
    }
    for (uint32_t q = 3; q < 3 * n; q++)
        g->g[q] = -g->g[q];
    g->stats.steps++;
    if (solve_step(g, n, n_blocks) != HL_SOLVE_OK) {
        memset(g->dx, 0, 3 * n * sizeof *g->dx);
        return false;
    }
    return true;
}

static void solve(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n, const hl_pg_edge_t *edges,
                  uint32_t n_edges, const problem_t *pb, int steps)
{
    for (int step = 0; step < steps; step++) {
        if (!gauss_newton_step(g, poses, n, edges, n_edges, pb))
            return;
        double most_mm = 0, most_rad = 0;
        for (uint32_t i = 1; i < n; i++) {
            const double *d = &g->dx[3 * i];
            poses[i].x += d[0];
            poses[i].y += d[1];
            poses[i].theta = wrap(poses[i].theta + d[2]);
            most_mm = fmax(most_mm, fmax(fabs(d[0]), fabs(d[1])));
            most_rad = fmax(most_rad, fabs(d[2]));
        }
        g->moved_mm += most_mm;
        g->moved_rad += most_rad;
        if (most_mm < GN_DONE_SHARE * pb->sigma_mm && most_rad < GN_DONE_SHARE * pb->sigma_rad)
            break;
    }
}

/* Drops the loop edges beyond the gate from @p edges (the order kept), worst first, at most
 * @p most: as many times dropping the one farthest from the fit, the poses unchanged
 * between. Each edge's error is measured once (g->chi2, squared in standard deviations,
 * averaged over its three terms; steps 0). @return the number dropped. */
static uint32_t drop_outliers(hl_posegraph_t *g, const hl_pg_pose_t *poses, uint32_t n,
                              hl_pg_edge_t *edges, uint32_t *n_edges, const double w[3],
                              double gate, uint32_t most)
{
    double *chi2 = g->chi2;
    pose_trig(poses, n, g->cs);
    for (uint32_t k = 0; k < *n_edges; k++) {
        edge_terms_t t;
        chi2[k] = 0;
        if (edges[k].loop) {
            linearize(poses, g->cs, &edges[k], &t);
            chi2[k] = squared_sigmas(&t, w) / 3;
        }
    }
    uint32_t dropped = 0;
    for (; dropped < most; dropped++) {
        uint32_t worst = UINT32_MAX;
        double worst_chi2 = gate * gate;
        for (uint32_t k = 0; k < *n_edges; k++)
            if (chi2[k] > worst_chi2) {
                worst_chi2 = chi2[k];
                worst = k;
            }
        if (worst == UINT32_MAX)
            break;
        chi2[worst] = -1;       /* marked: gone below */
    }
    if (dropped) {
        uint32_t kept = 0;
        for (uint32_t k = 0; k < *n_edges; k++)
            if (chi2[k] >= 0)
                edges[kept++] = edges[k];
        *n_edges = kept;
    }
    return dropped;
}

/* Whether every heading names a pose below n, is a number and has a positive, finite
 * sigma. */
static bool headings_fit(const hl_pg_heading_t *headings, uint32_t n_headings, uint32_t n)
{
    if (n_headings && !headings)
        return false;
    for (uint32_t k = 0; k < n_headings; k++)
        if (headings[k].pose >= n || !isfinite(headings[k].theta) ||
            !(headings[k].sigma_rad > 0) || !isfinite(headings[k].sigma_rad))
            return false;
    return true;
}

void hl_posegraph_shift(hl_posegraph_t *g, uint32_t k)
{
    if (g)
        hl_sparse_ldlt_shift(g->ldlt, k);
}

hl_pg_work_t hl_posegraph_work(const hl_posegraph_t *g)
{
    return g ? g->stats : (hl_pg_work_t){ 0 };
}

bool hl_posegraph_weigh_matches(hl_posegraph_t *g, double weight)
{
    if (!g || !(weight > 0 && weight <= 1))
        return false;
    g->match_weight = weight;
    return true;
}

uint32_t hl_posegraph_fit(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n,
                          hl_pg_edge_t *edges, uint32_t *n_edges,
                          const hl_pg_heading_t *headings, uint32_t n_headings,
                          double sigma_mm, double sigma_rad, double kernel, double gate)
{
    if (!g || !poses || !edges || !n_edges || n < 2 || n > g->max_poses ||
        *n_edges > g->max_edges || !(kernel >= 0) || !(sigma_mm > 0) || !(sigma_rad > 0) ||
        !headings_fit(headings, n_headings, n))
        return 0;
    const problem_t pb = { headings, n_headings, sigma_mm, sigma_rad,
                           { 1 / (sigma_mm * sigma_mm), 1 / (sigma_mm * sigma_mm),
                             1 / (sigma_rad * sigma_rad) },
                           kernel };
    const double *w = pb.w;
    /* Without a kernel one wrong match bends the whole fit, so right matches near it can
     * look wrong too: drop only the worst beyond the gate and fit again. Under the kernel
     * a wrong match bends the fit little, so those beyond the gate are the wrong ones and
     * go at once (worst first); the fit of the rest is near, a few steps away. On 72
     * simulated lab tours that gave the same mean error as one at a time (206.7 mm
     * against 206.6), in a quarter of the corridor's worst time a stop
     * (docs/results/performance.md). */
    const uint32_t batch = kernel > 0 ? MAX_DROPS : 1;
    const int steps_after = kernel > 0 ? GN_STEPS_AFTER_DROP : GN_STEPS;
    solve(g, poses, n, edges, *n_edges, &pb, GN_STEPS);
    uint32_t dropped = 0;
    for (;;) {
        uint32_t most = MAX_DROPS - dropped, now;
        now = drop_outliers(g, poses, n, edges, n_edges, w, gate, most < batch ? most : batch);
        if (now == 0)
            return dropped;
        dropped += now;
        solve(g, poses, n, edges, *n_edges, &pb, steps_after);
        if (dropped == MAX_DROPS)
            return dropped;
    }
}
