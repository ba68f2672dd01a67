/* votecast.c - the vote loop (votecast.h). */
#include "votecast.h"

#include "houghloc-internal/fixed.h"
#include "gate.h"
#include "simd.h"
#include "tiles.h"

/* The groups that can pair with one reading under some heading (hl_vgroups_gather),
 * listed in in->cand; returns how many. */
static uint32_t gather_candidates(const hl_vote_inputs_t *in, const hl_vote_ctx_t *c,
                                  const hl_loc_surface_t *s, hl_bam_t tn0, int32_t gate)
{
    return hl_vgroups_gather(in->groups, c->tx, c->ty, c->nt, c->width_q8, c->height_q8,
                             (uint32_t)s->theta_step, tn0, gate, in->cand);
}

/* The hot loop: every candidate group votes under each heading where some member passes
 * the normal gate, with the weight of how many do. A lone vector (most groups of a
 * sparse map) takes the short way. What the loop reads besides the candidate is copied
 * to locals first: the compiler cannot tell that the stores into the raster leave the
 * context alone, and would reload it for every vote. */
static HL_ALWAYS_INLINE void vote_candidates_as(const hl_vote_inputs_t *in, hl_vote_ctx_t *c,
                                                uint32_t ncand,
                                                hl_bam_t tn0, const gate_t *gate,
                                                uint16_t *votes, const bool once,
                                                const bool note)
{
    const hl_vgroups_t *g = in->groups;
    const size_t plane = (size_t)c->nx * c->ny;
    const uint32_t width = c->width_q8, height = c->height_q8, nx = (uint32_t)c->nx;
    const uint64_t recip = c->recip;
    const int32_t *tx = c->tx, *ty = c->ty, nt = c->nt;
    uint16_t *stamps = in->stamps;
    const uint16_t tag = c->tag;
    uint16_t *most = c->most;
    const uint32_t ntx = c->ntx;
    int32_t *diff = in->slice_diff;
    uint32_t nvotes = 0, npairs = 0;
    for (uint32_t i = 0; i < ncand; i++) {
        uint32_t k = in->cand[i];
        uint32_t m0 = g->first[k], m1 = g->first[k + 1];
        int32_t lo, hi;
        if (m1 - m0 == 1) {
            if (!gated_slices(gate, (int16_t)(uint16_t)(g->normal[m0] - tn0), &lo, &hi))
                continue;
        } else {
            lo = nt;
            hi = -1;
            for (uint32_t j = m0; j < m1; j++) {
                int32_t a, b;
                if (!gated_slices(gate, (int16_t)(uint16_t)(g->normal[j] - tn0), &a, &b))
                    continue;
                diff[a]++;
                diff[b + 1]--;
                lo = a < lo ? a : lo;
                hi = b > hi ? b : hi;
            }
            if (lo > hi)
                continue;
        }
        const int32_t x = g->gx[k], y = g->gy[k];
        uint16_t *slice = votes + (size_t)lo * plane;
        int32_t w = 0;
        for (int32_t it = lo; it <= hi; it++, slice += plane) {
            if (m1 - m0 == 1) {
                w = 1;
            } else {
                w += diff[it];
                diff[it] = 0;
            }
            npairs += (uint32_t)w;
            uint32_t vx = (uint32_t)(x - tx[it]);
            uint32_t vy = (uint32_t)(y - ty[it]);
            if (w == 0 || vx >= width || vy >= height)
                continue;
            /* floor(v / (256 cell)) == floor(floor(v / 256) / cell) */
            uint32_t ix = (uint32_t)(((uint64_t)(vx >> 8) * recip) >> 32);
            uint32_t iy = (uint32_t)(((uint64_t)(vy >> 8) * recip) >> 32);
            uint16_t *cell = slice + iy * nx + ix;
            int32_t weight = w;
            if (once) {                 /* vote_once: has this reading voted here? */
                uint16_t *seen = stamps + (cell - votes);
                weight = *seen != tag;
                *seen = tag;
            }
            uint32_t sum = *cell + (uint32_t)weight;
            *cell = (uint16_t)(sum < HL_VOTE_MAX ? sum : HL_VOTE_MAX);
            if (note)   /* the sparse path: the tile's most votes */
                hl_tiles_note(most, ntx, ix, iy, *cell);
            nvotes += (uint32_t)weight;
        }
        if (m1 - m0 > 1)
            diff[hi + 1] = 0;
    }
    c->votes += nvotes;
    c->pairs += npairs;
}

/* The loop four times, with and without vote_once and the sparse path's notes, so that
 * the common cases carry no test of them per vote (the compiler folds the constants). */
static void vote_candidates(const hl_vote_inputs_t *in, hl_vote_ctx_t *c, uint32_t ncand,
                            hl_bam_t tn0, const gate_t *gate, uint16_t *votes)
{
    if (in->lone->capacity) {   /* lone vectors, weight 1 (votelone.h) */
        hl_votelone_raster_t r = { c->nx, c->ny, c->nt, c->width_q8, c->height_q8,
                                   c->cell_q8, c->tx, c->ty, votes, c->most, c->ntx };
        c->votes += hl_votelone_vote(in->lone, in->groups, in->cand, ncand, gate, tn0,
                                     &r, &c->pairs);
    } else if (c->most) {
        if (in->stamps)
            vote_candidates_as(in, c, ncand, tn0, gate, votes, true, true);
        else
            vote_candidates_as(in, c, ncand, tn0, gate, votes, false, true);
    } else {
        if (in->stamps)
            vote_candidates_as(in, c, ncand, tn0, gate, votes, true, false);
        else
            vote_candidates_as(in, c, ncand, tn0, gate, votes, false, false);
    }
}

void hl_vote_cast(const hl_vote_inputs_t *in, uint32_t nread, const hl_loc_surface_t *s,
                  hl_vote_ctx_t *c)
{
    int32_t gate = in->normal_gate;
    /* step < 2^14 (a slice spans under half a turn, loc_params.c), so the reciprocal is
     * exact for the operands below 2^18 */
    gate_t g = gate_make(gate, s->theta_step, c->nt);
    for (uint32_t i = 0; i < nread; i++) {
        hl_bam_t a0 = (hl_bam_t)(s->theta0 + in->bearing[i]);
        for (int32_t it = 0; it < c->nt; it++) {
            int32_t tx, ty;
            hl_polar_to_xy_q8(in->range[i], (hl_bam_t)(a0 + it * s->theta_step), &tx, &ty);
            c->tx[it] = tx;
            c->ty[it] = ty;
        }
        /* The test vector's normal points back at the robot, like the map's. */
        hl_bam_t tn0 = (hl_bam_t)(a0 + HL_BAM_HALF_TURN + in->tilt[i]);
        c->tag = (uint16_t)(i + 1);
        uint32_t ncand = gather_candidates(in, c, s, tn0, gate);
        vote_candidates(in, c, ncand, tn0, &g, in->votes);
    }
}

