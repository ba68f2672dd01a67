/*
 * bench_posegraph - times loop closure's fit (hl_posegraph_fit, houghloc-internal/posegraph.h) on a
 * synthetic graph of any size, so that the cost of a large `slam.closure_stops` can be
 * read before a robot pays it (docs/results/performance.md).
 *
 *   hl-bench-posegraph [--stops N] [--wrong PCT] [--work]
 *
 * The graph: N stops (default 256, 2..4096) back and forth along a 28 m corridor, 0.6 m
 * apart and weaving 1 m either side of its middle; a step between consecutive stops and,
 * for each stop, a match with up to 8 of the stops at least 5 before it within 1.5 m
 * (closure.h's rules at their most), every one measured with 30 mm and 1.1 degrees of
 * noise, PCT per cent of the matches (default 5) 2 m and 29 degrees wrong. The fit starts
 * from the stops chained by their steps, as a tour's drift leaves them, under the
 * daemon's sigmas, kernel and gate; then fits again from its own answer (refit: the same
 * graph). And the next stop as the daemon's full record meets it (next: the same corridor
 * one stop longer, its first N stops fitted, then the oldest forgotten and the new stop
 * added with its step and matches, and fitted again; on a workspace of its own). Prints
 * one line:
 *
 *   bench posegraph_fit stops=<n> edges=<n> dropped=<n> first_ms=<x> refit_ms=<x> next_ms=<x> worst_mm=<x>
 *
 * (worst_mm: the stop farthest from its truth after the first fit), and with --work one
 * more for each fit, what it did (hl_posegraph_stats):
 *
 *   bench posegraph_work fit=first|refit|next steps=<n> analyses=<n> factorizations=<n> pcg=<n> pcg_iterations=<n> pcg_failures=<n>
 *
 * Everything is a function of the stops and the share wrong (a fixed seed). Exit status:
 * 0 done, 1 no memory, 2 bad usage (one line naming it).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "corridor.h"
#include "timing.h"
#include "houghloc-internal/closure.h"

#define PI 3.14159265358979323846
static void usage(FILE *to)
{
    fprintf(to, "usage: hl-bench-posegraph [--stops N] [--wrong PCT] [--work]\n"
                "Times loop closure's fit on a synthetic corridor tour of N stops (2..%d,\n"
                "default 256), PCT per cent of its matches wrong (0..100, default 5): the\n"
                "first fit, a refit of the same graph, and the next stop's fit (the oldest\n"
                "forgotten, one added). Prints one line:\n"
                "  bench posegraph_fit stops=N edges=N dropped=N first_ms=X refit_ms=X next_ms=X worst_mm=X\n"
                "--work: a line more for each fit, its steps, factorizations and conjugate\n"
                "gradients.\n",
            HL_CLOSURE_MAX_STOPS);
}

/* Bad usage: one line naming it, exit 2. */
static int bad(const char *what, const char *value)
{
    fprintf(stderr, "hl-bench-posegraph: %s, not '%s' (--help)\n", what, value);
    return 2;
}

static double fit_ms(hl_posegraph_t *g, hl_pg_pose_t *poses, uint32_t n, hl_pg_edge_t *edges,
                     uint32_t *n_edges, uint32_t *dropped)
{
    double t0 = now_us();
    *dropped = hl_posegraph_fit(g, poses, n, edges, n_edges, NULL, 0, HL_CLOSURE_SIGMA_MM,
                                HL_CLOSURE_SIGMA_DEG * (PI / 180), HL_CLOSURE_KERNEL,
                                HL_CLOSURE_OUTLIER);
    return (now_us() - t0) / 1e3;
}

/* What a fit did, from the stats @p before it to @p a after it, as a line (--work). */
static void print_work(const char *fit, hl_pg_work_t a, hl_pg_work_t before)
{
    printf("bench posegraph_work fit=%s steps=%llu analyses=%llu factorizations=%llu pcg=%llu "
           "pcg_iterations=%llu pcg_failures=%llu\n", fit,
           (unsigned long long)(a.steps - before.steps),
           (unsigned long long)(a.analyses - before.analyses),
           (unsigned long long)(a.factorizations - before.factorizations),
           (unsigned long long)(a.pcg_solves - before.pcg_solves),
           (unsigned long long)(a.pcg_iterations - before.pcg_iterations),
           (unsigned long long)(a.pcg_failures - before.pcg_failures));
}

/* The next stop's fit with the record full (header): the corridor of n + 1 stops, its first
 * n fitted, then stop 0 forgotten with its edges (the others renumbered, as closure.c
 * forgets its oldest) and stop n added, chained by its step from the fitted stop before
 * it, with its edges. @return the milliseconds of that last fit, or -1 on no memory. */
static double next_stop_ms(uint32_t n, double wrong_pct, hl_pg_work_t *work_before,
                           hl_posegraph_t **graph)
{
    const uint32_t max_edges = sr_corridor_max_edges(n + 1);
    hl_pg_pose_t *truth = malloc((n + 1) * sizeof *truth), *poses = malloc((n + 1) * sizeof *poses);
    hl_pg_edge_t *edges = malloc(max_edges * sizeof *edges), *added = malloc(max_edges * sizeof *added);
    hl_posegraph_t *g = hl_posegraph_create(n, max_edges);
    double ms = -1;
    if (!truth || !poses || !edges || !added || !g)
        goto out;
    uint32_t all = sr_corridor(n + 1, wrong_pct, truth, poses, edges), n_edges = 0, n_added = 0;
    for (uint32_t k = 0; k < all; k++) {
        if (edges[k].to < n)
            edges[n_edges++] = edges[k];
        else
            added[n_added++] = edges[k];
    }
    uint32_t dropped;
    fit_ms(g, poses, n, edges, &n_edges, &dropped);
    uint32_t kept = 0;
    for (uint32_t k = 0; k < n_edges; k++)
        if (edges[k].from > 0)
            edges[kept++] = (hl_pg_edge_t){ edges[k].from - 1, edges[k].to - 1, edges[k].rel,
                                            edges[k].loop };
    memmove(poses, poses + 1, n * sizeof *poses);
    hl_posegraph_shift(g, 1);
    for (uint32_t k = 0; k < n_added; k++) {
        hl_pg_edge_t e = added[k];
        e.from--;
        e.to--;
        if (!e.loop)
            poses[n - 1] = hl_pg_compose(poses[n - 2], e.rel);
        if (e.from < n)     /* a match with the stop forgotten is gone with it */
            edges[kept++] = e;
    }
    *work_before = hl_posegraph_work(g);
    ms = fit_ms(g, poses, n, edges, &kept, &dropped);
out:
    free(truth);
    free(poses);
    free(edges);
    free(added);
    *graph = g;
    return ms;
}

int main(int argc, char **argv)
{
    long stops = 256;
    double wrong_pct = 5;
    bool work = false;
    for (int i = 1; i < argc; i++) {
        char *end = NULL;
        if (strcmp(argv[i], "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(argv[i], "--work") == 0) {
            work = true;
        } else if (strcmp(argv[i], "--stops") == 0 && i + 1 < argc) {
            stops = strtol(argv[++i], &end, 10);
            if (*end || end == argv[i] || stops < 2 || stops > HL_CLOSURE_MAX_STOPS)
                return bad("--stops wants 2..4096", argv[i]);
        } else if (strcmp(argv[i], "--wrong") == 0 && i + 1 < argc) {
            wrong_pct = strtod(argv[++i], &end);
            if (*end || end == argv[i] || !(wrong_pct >= 0 && wrong_pct <= 100))
                return bad("--wrong wants a per cent, 0..100", argv[i]);
        } else {
            return bad("an unknown option or one without its value", argv[i]);
        }
    }
    const uint32_t n = (uint32_t)stops, max_edges = sr_corridor_max_edges(n);
    hl_pg_pose_t *truth = malloc(n * sizeof *truth), *poses = malloc(n * sizeof *poses);
    hl_pg_edge_t *edges = malloc(max_edges * sizeof *edges);
    hl_posegraph_t *g = hl_posegraph_create(n, max_edges);
    if (!truth || !poses || !edges || !g) {
        fprintf(stderr, "hl-bench-posegraph: no memory for %u stops\n", n);
        return 1;
    }
    uint32_t n_edges = sr_corridor(n, wrong_pct, truth, poses, edges);
    uint32_t all = n_edges, dropped, again;
    double first = fit_ms(g, poses, n, edges, &n_edges, &dropped);
    hl_pg_work_t after_first = hl_posegraph_work(g);
    double worst = 0;
    for (uint32_t i = 0; i < n; i++)
        worst = fmax(worst, hypot(poses[i].x - truth[i].x, poses[i].y - truth[i].y));
    double refit = fit_ms(g, poses, n, edges, &n_edges, &again);
    hl_pg_work_t before_next;
    hl_posegraph_t *g_next = NULL;
    double next = next_stop_ms(n, wrong_pct, &before_next, &g_next);
    if (next < 0) {
        fprintf(stderr, "hl-bench-posegraph: no memory for %u stops\n", n);
        return 1;
    }
    printf("bench posegraph_fit stops=%u edges=%u dropped=%u first_ms=%.1f refit_ms=%.1f "
           "next_ms=%.1f worst_mm=%.0f\n", n, all, dropped + again, first, refit, next, worst);
    if (work) {
        print_work("first", after_first, (hl_pg_work_t){ 0 });
        print_work("refit", hl_posegraph_work(g), after_first);
        print_work("next", hl_posegraph_work(g_next), before_next);
    }
    hl_posegraph_destroy(g);
    hl_posegraph_destroy(g_next);
    free(truth);
    free(poses);
    free(edges);
    return 0;
}
