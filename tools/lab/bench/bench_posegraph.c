/*
 * bench_posegraph - times loop closure's fit (hl_posegraph_fit, houghloc-internal/posegraph.h) on a
 * synthetic graph of any size, so that the cost of a large `slam.closure_stops` can be
 * read before a robot pays it (docs/results/performance.md).
 *
 *   hl-bench-posegraph [--stops N] [--wrong PCT]
 *
 * The graph: N stops (default 256, 2..4096) back and forth along a 28 m corridor, 0.6 m
 * apart and weaving 1 m either side of its middle; a step between consecutive stops and,
 * for each stop, a match with up to 16 of the stops at least 5 before it within 1.5 m
 * (closure.h's rules at their most), every one measured with 30 mm and 1.1 degrees of
 * noise, PCT per cent of the matches (default 5) 2 m and 29 degrees wrong. The fit starts
 * from the stops chained by their steps, as a tour's drift leaves them, under the
 * daemon's sigmas, kernel and gate; then fits again from its own answer, as the next stop
 * does. Prints one line:
 *
 *   bench posegraph_fit stops=<n> edges=<n> dropped=<n> first_ms=<x> refit_ms=<x> worst_mm=<x>
 *
 * (worst_mm: the stop farthest from its truth after the first fit). Everything is a
 * function of the stops and the share wrong (a fixed seed). Exit status: 0 done, 1 no
 * memory, 2 bad usage (one line naming it).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "corridor.h"
#include "timing.h"
#include "houghloc-internal/closure.h"

#define PI 3.14159265358979323846
static void usage(FILE *to)
{
    fprintf(to, "usage: hl-bench-posegraph [--stops N] [--wrong PCT]\n"
                "Times loop closure's fit on a synthetic corridor tour of N stops (2..%d,\n"
                "default 256), PCT per cent of its matches wrong (0..100, default 5), and\n"
                "prints one line:\n"
                "  bench posegraph_fit stops=N edges=N dropped=N first_ms=X refit_ms=X worst_mm=X\n",
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

int main(int argc, char **argv)
{
    long stops = 256;
    double wrong_pct = 5;
    for (int i = 1; i < argc; i++) {
        char *end = NULL;
        if (strcmp(argv[i], "--help") == 0) {
            usage(stdout);
            return 0;
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
    double worst = 0;
    for (uint32_t i = 0; i < n; i++)
        worst = fmax(worst, hypot(poses[i].x - truth[i].x, poses[i].y - truth[i].y));
    double refit = fit_ms(g, poses, n, edges, &n_edges, &again);
    printf("bench posegraph_fit stops=%u edges=%u dropped=%u first_ms=%.1f refit_ms=%.1f "
           "worst_mm=%.0f\n", n, all, dropped + again, first, refit, worst);
    hl_posegraph_destroy(g);
    free(truth);
    free(poses);
    free(edges);
    return 0;
}
