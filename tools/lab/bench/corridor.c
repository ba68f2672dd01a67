/* corridor.c - the benchmarks' synthetic loop-closure graph (corridor.h). */
#include "corridor.h"

#include <math.h>

#include "houghloc-internal/closure.h"
#include "houghloc/rng.h"
#include "synthroom.h"

#define PI 3.14159265358979323846
#define NOISE_MM 30.0
#define NOISE_RAD 0.02

static hl_pg_pose_t measured(hl_rng_t *rng, hl_pg_pose_t from, hl_pg_pose_t to)
{
    hl_pg_pose_t rel = hl_pg_between(from, to);
    rel.x += NOISE_MM * sr_gauss_rng(rng);
    rel.y += NOISE_MM * sr_gauss_rng(rng);
    rel.theta += NOISE_RAD * sr_gauss_rng(rng);
    return rel;
}

uint32_t sr_corridor_max_edges(uint32_t n)
{
    return n * (1 + HL_CLOSURE_MAX_TAKEN);
}

uint32_t sr_corridor(uint32_t n, double wrong_pct, hl_pg_pose_t *truth, hl_pg_pose_t *chained,
                     hl_pg_edge_t *edges)
{
    hl_rng_t rng;
    hl_rng_seed(&rng, 1);
    double x = 0, dir = 1;
    for (uint32_t i = 0; i < n; i++) {
        x += dir * 600;
        if (x > 28000 || x < 0) {
            dir = -dir;
            x += 2 * dir * 600;
        }
        truth[i] = (hl_pg_pose_t){ x, 1000 * sin(i * 0.37), dir > 0 ? 0 : PI };
    }
    uint32_t n_edges = 0;
    chained[0] = truth[0];
    for (uint32_t i = 1; i < n; i++) {
        edges[n_edges] = (hl_pg_edge_t){ i - 1, i, measured(&rng, truth[i - 1], truth[i]), false };
        chained[i] = hl_pg_compose(chained[i - 1], edges[n_edges++].rel);
    }
    for (uint32_t k = 0; k < n; k++)
        for (uint32_t j = 0, m = 0; j + HL_CLOSURE_GAP <= k && m < HL_CLOSURE_MAX_TAKEN; j++)
            if (hypot(truth[j].x - truth[k].x, truth[j].y - truth[k].y) <= HL_CLOSURE_RADIUS_MM) {
                hl_pg_pose_t rel = measured(&rng, truth[j], truth[k]);
                if (hl_rng_below(&rng, 10000) < wrong_pct * 100) {
                    rel.x += 2000;
                    rel.theta += 0.5;
                }
                edges[n_edges++] = (hl_pg_edge_t){ j, k, rel, true };
                m++;
            }
    return n_edges;
}
