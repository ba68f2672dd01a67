/* posegraph.c - a 2-D pose graph by Gauss-Newton and conjugate gradients (posegraph.h). */
#include "posegraph.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GN_STEPS 10             /* Gauss-Newton steps at most ... */
#define GN_STEPS_AFTER_DROP 3   /* ... and after matches are dropped, from the fit before */
#define GN_DONE_MM 0.01         /* ... until no pose moves more than this */
#define GN_DONE_RAD 1e-7
#define CG_TOLERANCE 1e-12      /* residual / right-hand side, squared */
#define CG_MAX_ITERATIONS 500   /* a bound on one step's time whatever the graph: the
                                   simulated corridor's 256 stops and their matches
                                   needed at most 218, mean 110; the lab's at most 79 */
#define MAX_DROPS 8             /* outliers dropped a fit at most */

typedef struct { double v[9]; } mat3_t;     /* row-major */

typedef struct edge_terms {
    double r[3];        /* the edge's error at the current poses */
    mat3_t a, b;        /* its Jacobians in the `from` and `to` poses */
} edge_terms_t;

/* The preconditioner is the chain's part of H, factored exactly (block LDL^T): each
 * pose's own block and the blocks between consecutive poses, which the steps fill. */
struct hl_posegraph {
    uint32_t max_poses, max_edges;
    mat3_t *between;                /* [max_edges] each edge's block of H between its two
                                       poses, a^T W b: all the products read of an edge */
    mat3_t *diag;                   /* [max_poses] H's own block of each pose */
    mat3_t *pivot_inv;              /* [max_poses] D's blocks, inverted */
    mat3_t *upper;                  /* [max_poses] H's block between poses i and i + 1 */
    mat3_t *lower;                  /* [max_poses] L's block between poses i and i - 1 */
    double *g, *dx, *res, *z, *p, *hp;  /* [3 * max_poses] each */
};

size_t hl_posegraph_mem_bytes(uint32_t max_poses, uint32_t max_edges)
{
    return sizeof(hl_posegraph_t) + (size_t)max_edges * sizeof(mat3_t) +
           (size_t)max_poses * (4 * sizeof(mat3_t) + 6 * 3 * sizeof(double));
}

hl_posegraph_t *hl_posegraph_create(uint32_t max_poses, uint32_t max_edges)
{
    hl_posegraph_t *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->max_poses = max_poses;
    g->max_edges = max_edges;
    g->between = calloc(max_edges ? max_edges : 1, sizeof *g->between);
    mat3_t **blocks[] = { &g->diag, &g->pivot_inv, &g->upper, &g->lower };
    double **vecs[] = { &g->g, &g->dx, &g->res, &g->z, &g->p, &g->hp };
    bool ok = g->between != NULL;
    for (size_t k = 0; k < sizeof blocks / sizeof blocks[0]; k++) {
        *blocks[k] = calloc(max_poses ? max_poses : 1, sizeof(mat3_t));
        ok = ok && *blocks[k];
    }
    for (size_t k = 0; k < sizeof vecs / sizeof vecs[0]; k++) {
        *vecs[k] = calloc(3 * (size_t)(max_poses ? max_poses : 1), sizeof(double));
        ok = ok && *vecs[k];
    }
    if (!ok) {
        hl_posegraph_destroy(g);
        return NULL;
    }
    return g;
}

void hl_posegraph_destroy(hl_posegraph_t *g)
{
    if (!g)
        return;
    free(g->between);
    free(g->diag);
    free(g->pivot_inv);
    free(g->upper);
    free(g->lower);
    free(g->g);
    free(g->dx);
    free(g->res);
    free(g->z);
    free(g->p);
    free(g->hp);
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

/* The edge's error (the measured relative pose against the poses' own) and Jacobians. */
static void linearize(const hl_pg_pose_t *poses, const hl_pg_edge_t *e, edge_terms_t *t)
{
    hl_pg_pose_t a = poses[e->from], b = poses[e->to];
    double c = cos(a.theta), s = sin(a.theta), dx = b.x - a.x, dy = b.y - a.y;
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

static void mul3(const mat3_t *m, const double *x, double *out)
{
    for (int i = 0; i < 3; i++)
        out[i] = m->v[3 * i] * x[0] + m->v[3 * i + 1] * x[1] + m->v[3 * i + 2] * x[2];
}

/* out = m^T x */
static void mul3t(const mat3_t *m, const double *x, double *out)
{
    for (int i = 0; i < 3; i++)
        out[i] = m->v[i] * x[0] + m->v[3 + i] * x[1] + m->v[6 + i] * x[2];
}

/* out += m, or its transpose */
static void add_block(mat3_t *out, const mat3_t *m, bool transposed)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out->v[3 * i + j] += transposed ? m->v[3 * j + i] : m->v[3 * i + j];
}

/* a^T b */
static mat3_t product_tn(const mat3_t *a, const mat3_t *b)
{
    mat3_t c = { { 0 } };
    const double ones[3] = { 1, 1, 1 };
    add_atwb(&c, a, ones, b);
    return c;
}

/* The inverse of a symmetric positive definite 3 x 3 block; zero when it has none (a
 * pose no edge reaches: it does not move). */
static mat3_t inverse(const mat3_t *m)
{
    const double *a = m->v;
    mat3_t inv = { { a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
                     a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
                     a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3] } };
    double det = a[0] * inv.v[0] + a[1] * inv.v[3] + a[2] * inv.v[6];
    if (!(fabs(det) > 1e-300))
        return (mat3_t){ { 0 } };
    for (int i = 0; i < 9; i++)
        inv.v[i] /= det;
    return inv;
}

/* hp = H p from H's blocks: each pose's own, then each edge's between its two poses; pose
 * 0 held (its rows and columns left out: p is zero there). */
static void product(const hl_posegraph_t *g, const hl_pg_edge_t *edges, uint32_t n_edges,
                    uint32_t n, const double *p, double *hp)
{
    hp[0] = hp[1] = hp[2] = 0;
    for (uint32_t i = 1; i < n; i++)
        mul3(&g->diag[i], &p[3 * i], &hp[3 * i]);
    for (uint32_t k = 0; k < n_edges; k++) {
        const mat3_t *ab = &g->between[k];
        uint32_t i = edges[k].from, j = edges[k].to;
        double to_i[3], to_j[3];
        mul3(ab, &p[3 * j], to_i);
        mul3t(ab, &p[3 * i], to_j);
        for (int q = 0; q < 3; q++) {
            hp[3 * i + q] += to_i[q];
            hp[3 * j + q] += to_j[q];
        }
    }
    hp[0] = hp[1] = hp[2] = 0;
}

static double dot(const double *a, const double *b, uint32_t n)
{
    double s = 0;
    for (uint32_t i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* An edge's squared error in standard deviations, summed over its three terms. */
static double squared_sigmas(const edge_terms_t *t, const double w[3])
{
    return t->r[0] * t->r[0] * w[0] + t->r[1] * t->r[1] * w[1] + t->r[2] * t->r[2] * w[2];
}

/* The preconditioner's factors from its blocks (each pose's own and the chain's): the
 * pivots D_i = H_ii - U_{i-1}^T D_{i-1}^-1 U_{i-1}, inverted, and
 * L_i = U_{i-1}^T D_{i-1}^-1. Pose 0 is held, so the chain starts at pose 1. */
static void factor_chain(hl_posegraph_t *g, uint32_t n)
{
    g->pivot_inv[0] = (mat3_t){ { 0 } };
    for (uint32_t i = 1; i < n; i++) {
        mat3_t pivot = g->diag[i];
        if (i > 1) {
            const mat3_t *u = &g->upper[i - 1], *before = &g->pivot_inv[i - 1];
            mat3_t d_inv_u = product_tn(before, u);     /* D^-1 is symmetric */
            mat3_t utdu = product_tn(u, &d_inv_u);
            for (int q = 0; q < 9; q++)
                pivot.v[q] -= utdu.v[q];
            g->lower[i] = product_tn(u, before);
        }
        g->pivot_inv[i] = inverse(&pivot);
    }
}

/* z = M^-1 r for the chain's M = L D L^T: forward through L, then back through D L^T. */
static void precondition(const hl_posegraph_t *g, uint32_t n, const double *r, double *z)
{
    z[0] = z[1] = z[2] = 0;
    for (uint32_t i = 1; i < n; i++) {
        double ly[3] = { 0, 0, 0 };
        if (i > 1)
            mul3(&g->lower[i], &z[3 * (i - 1)], ly);
        for (int q = 0; q < 3; q++)
            z[3 * i + q] = r[3 * i + q] - ly[q];
    }
    for (uint32_t i = n - 1; i >= 1; i--) {
        double y[3] = { z[3 * i], z[3 * i + 1], z[3 * i + 2] }, uz[3];
        if (i + 1 < n) {
            mul3(&g->upper[i], &z[3 * (i + 1)], uz);
            for (int q = 0; q < 3; q++)
                y[q] -= uz[q];
        }
        mul3(&g->pivot_inv[i], y, &z[3 * i]);
    }
}

/* A fit's fixed inputs besides the poses and edges: the headings of the poses' own, the
 * edges' weights and the kernel. */
typedef struct problem {
    const hl_pg_heading_t *headings;
    uint32_t n_headings;
    double w[3];            /* steps' and matches' weights: 1 / sigma^2 */
    double kernel;
} problem_t;

/* One Gauss-Newton step of iteratively reweighted least squares: g->dx solves H dx = -g,
 * pose 0 held, each loop edge weighed by the Cauchy kernel at the current poses. A
 * heading adds to its pose's own block alone, so the products need not know of it. */
static void gauss_newton_step(hl_posegraph_t *g, const hl_pg_pose_t *poses, uint32_t n,
                              const hl_pg_edge_t *edges, uint32_t n_edges,
                              const problem_t *pb)
{
    const double *w = pb->w;
    const double kernel = pb->kernel;
    const uint32_t m = 3 * n;
    memset(g->g, 0, m * sizeof *g->g);
    memset(g->diag, 0, n * sizeof *g->diag);
    memset(g->upper, 0, n * sizeof *g->upper);
    for (uint32_t k = 0; k < n_edges; k++) {
        edge_terms_t t;
        uint32_t i = edges[k].from, j = edges[k].to;
        linearize(poses, &edges[k], &t);
        double robust = edges[k].loop && kernel > 0
                            ? 1 / (1 + squared_sigmas(&t, w) / (kernel * kernel)) : 1;
        const double wk[3] = { w[0] * robust, w[1] * robust, w[2] * robust };
        add_jtw(&g->g[3 * i], &t.a, wk, t.r);
        add_jtw(&g->g[3 * j], &t.b, wk, t.r);
        add_atwb(&g->diag[i], &t.a, wk, &t.a);
        add_atwb(&g->diag[j], &t.b, wk, &t.b);
        mat3_t *ab = &g->between[k];
        *ab = (mat3_t){ { 0 } };
        add_atwb(ab, &t.a, wk, &t.b);
        if (j == i + 1)                 /* the chain's blocks, for the preconditioner */
            add_block(&g->upper[i], ab, false);
        else if (i == j + 1)
            add_block(&g->upper[j], ab, true);
    }
    for (uint32_t k = 0; k < pb->n_headings; k++) {
        const hl_pg_heading_t *h = &pb->headings[k];
        double r = wrap(poses[h->pose].theta - h->theta), wh = 1 / (h->sigma_rad * h->sigma_rad);
        g->g[3 * h->pose + 2] += wh * r;
        g->diag[h->pose].v[8] += wh;
    }
    factor_chain(g, n);
    /* Preconditioned conjugate gradients from dx = 0: res = -g. */
    memset(g->dx, 0, m * sizeof *g->dx);
    for (uint32_t i = 0; i < m; i++)
        g->res[i] = i < 3 ? 0 : -g->g[i];
    precondition(g, n, g->res, g->z);
    memcpy(g->p, g->z, m * sizeof *g->p);
    double rz = dot(g->res, g->z, m), rz0 = rz;
    for (uint32_t it = 0; it < CG_MAX_ITERATIONS && rz > CG_TOLERANCE * rz0 && rz > 0; it++) {
        product(g, edges, n_edges, n, g->p, g->hp);
        double php = dot(g->p, g->hp, m);
        if (!(php > 0))
            break;
        double alpha = rz / php;
        for (uint32_t i = 0; i < m; i++) {
            g->dx[i] += alpha * g->p[i];
            g->res[i] -= alpha * g->hp[i];
        }
        precondition(g, n, g->res, g->z);
        double rz_next = dot(g->res, g->z, m);
        for (uint32_t i = 0; i < m; i++)
            g->p[i] = g->z[i] + (rz_next / rz) * g->p[i];
        rz = rz_next;
    }
}

static void solve(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n, const hl_pg_edge_t *edges,
                  uint32_t n_edges, const problem_t *pb, int steps)
{
    for (int step = 0; step < steps; step++) {
        gauss_newton_step(g, poses, n, edges, n_edges, pb);
        double most_mm = 0, most_rad = 0;
        for (uint32_t i = 1; i < n; i++) {
            const double *d = &g->dx[3 * i];
            poses[i].x += d[0];
            poses[i].y += d[1];
            poses[i].theta = wrap(poses[i].theta + d[2]);
            most_mm = fmax(most_mm, fmax(fabs(d[0]), fabs(d[1])));
            most_rad = fmax(most_rad, fabs(d[2]));
        }
        if (most_mm < GN_DONE_MM && most_rad < GN_DONE_RAD)
            break;
    }
}

/* An edge's squared error in standard deviations, averaged over its three terms. */
static double chi2(const hl_pg_pose_t *poses, const hl_pg_edge_t *e, const double w[3])
{
    edge_terms_t t;
    linearize(poses, e, &t);
    return squared_sigmas(&t, w) / 3;
}

/* Drops the loop edge farthest from the fit if it lies beyond the gate. */
static bool drop_worst(const hl_pg_pose_t *poses, hl_pg_edge_t *edges, uint32_t *n_edges,
                       const double w[3], double gate)
{
    uint32_t worst = UINT32_MAX;
    double worst_chi2 = gate * gate;
    for (uint32_t k = 0; k < *n_edges; k++) {
        double c = edges[k].loop ? chi2(poses, &edges[k], w) : 0;
        if (c > worst_chi2) {
            worst_chi2 = c;
            worst = k;
        }
    }
    if (worst == UINT32_MAX)
        return false;
    memmove(&edges[worst], &edges[worst + 1], (*n_edges - worst - 1) * sizeof *edges);
    (*n_edges)--;
    return true;
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

uint32_t hl_posegraph_fit(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n,
                          hl_pg_edge_t *edges, uint32_t *n_edges,
                          const hl_pg_heading_t *headings, uint32_t n_headings,
                          double sigma_mm, double sigma_rad, double kernel, double gate)
{
    if (!g || !poses || !edges || !n_edges || n < 2 || n > g->max_poses ||
        *n_edges > g->max_edges || !(kernel >= 0) || !headings_fit(headings, n_headings, n))
        return 0;
    const problem_t pb = { headings, n_headings,
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
        uint32_t now = 0;
        while (now < batch && dropped + now < MAX_DROPS &&
               drop_worst(poses, edges, n_edges, w, gate))
            now++;
        if (now == 0)
            return dropped;
        dropped += now;
        solve(g, poses, n, edges, *n_edges, &pb, steps_after);
        if (dropped == MAX_DROPS)
            return dropped;
    }
}
