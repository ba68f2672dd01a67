/* Tests for src/core/votelone.c: on random rasters, candidates, slice ranges and
 * offsets, the lone vectors' loop leaves the raster, the tiles' notes (once folded) and
 * the count of votes that the general loop's arithmetic gives, vote by vote: a cell of
 * floor((point - offset) / cell) when in the raster, a saturating sum, the most votes of
 * a cell per tile. Cells start with votes (some near saturation) noted in their tiles,
 * as the raster of a run holds only what its notes bound. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "houghloc-internal/fixed.h"
#include "houghloc/rng.h"
#include "tiles.h"
#include "votelone.h"

enum { MAX_SIDE = 150, MAX_NT = 17, MAX_CELLS = MAX_SIDE * MAX_SIDE * MAX_NT,
       MAX_GROUPS = 600, MAX_TILES = 64 };

static hl_rng_t rng;

static uint32_t rnd(uint32_t n)  /* 0 .. n - 1, n >= 1 */
{
    return hl_rng_below(&rng, n);
}

static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

static void note(uint16_t *most, uint32_t ntx, int64_t ix, int64_t iy, uint16_t v)
{
    uint16_t *m = most + (iy >> HL_TILE_H_SHIFT) * ntx + (ix >> HL_TILE_W_SHIFT);
    *m = v > *m ? v : *m;
}

static void test_lone_is_the_general_loop(void **state)
{
    (void)state;
    uint16_t *votes = malloc(MAX_CELLS * sizeof *votes);
    uint16_t *ref = malloc(MAX_CELLS * sizeof *ref);
    uint16_t most[MAX_TILES], ref_most[MAX_TILES];
    int32_t gx[MAX_GROUPS], gy[MAX_GROUPS], lo[MAX_GROUPS], hi[MAX_GROUPS];
    int32_t tx[MAX_NT], ty[MAX_NT];
    hl_votelone_t v;
    hl_rng_seed(&rng, 4242);
    assert_non_null(votes);
    assert_non_null(ref);
    assert_true(hl_votelone_init(&v, MAX_GROUPS, MAX_TILES));
    uint64_t total = 0;
    int saturated = 0;
    for (int trial = 0; trial < 400; trial++) {
        int32_t nx = 1 + (int32_t)rnd(MAX_SIDE), ny = 1 + (int32_t)rnd(MAX_SIDE);
        int32_t nt = 1 + (int32_t)rnd(MAX_NT);
        if (trial % 10 == 0)
            nx = ny = nt = 1;
        int32_t cell = 2 + (int32_t)rnd(rnd(2) ? 60 : 1000);
        int32_t d = 256 * cell;
        uint32_t ntx = (uint32_t)(nx + HL_TILE_W - 1) / HL_TILE_W;
        uint32_t ntiles = ntx * (uint32_t)((ny + HL_TILE_H - 1) / HL_TILE_H);
        size_t cells = (size_t)nx * ny * nt;
        bool notes = rnd(4) != 0;
        memset(votes, 0, cells * sizeof *votes);
        memset(most, 0, sizeof most);
        for (size_t k = rnd(4) ? rnd(20) : cells / 3; k > 0; k--) {   /* earlier votes, noted */
            size_t c = rnd((uint32_t)cells);
            votes[c] = (uint16_t)(rnd(2) ? 1 + rnd(30) : HL_VOTE_MAX - rnd(3));
            note(most, ntx, (int64_t)(c % (size_t)nx), (int64_t)(c / (size_t)nx % (size_t)ny),
                 votes[c]);
        }
        memcpy(ref, votes, cells * sizeof *votes);
        memcpy(ref_most, most, sizeof most);
        /* points within half a raster's width beyond each side, offsets up to that */
        uint32_t ngroups = 1 + rnd(MAX_GROUPS);
        int64_t w = (int64_t)nx * d, h = (int64_t)ny * d;
        for (uint32_t k = 0; k < ngroups; k++) {
            gx[k] = (int32_t)((int64_t)rnd((uint32_t)(2 * w)) - w / 2);
            gy[k] = (int32_t)((int64_t)rnd((uint32_t)(2 * h)) - h / 2);
        }
        for (int32_t it = 0; it < nt; it++) {
            tx[it] = (int32_t)((int64_t)rnd((uint32_t)w) - w / 2);
            ty[it] = (int32_t)((int64_t)rnd((uint32_t)h) - h / 2);
        }
        hl_votelone_prepare(&v, gx, gy, ngroups, d);
        uint32_t cast = 0, ref_cast = 0;
        for (int reading = 0; reading < 3; reading++) {
            hl_votelone_clear(&v);
            uint32_t listed = rnd(ngroups + 1);
            for (uint32_t i = 0; i < listed; i++) {
                uint32_t k = rnd(ngroups);
                lo[i] = (int32_t)rnd((uint32_t)nt);
                hi[i] = lo[i] + (int32_t)rnd((uint32_t)(nt - lo[i]));
                hl_votelone_push(&v, k, lo[i], hi[i]);
                for (int32_t it = lo[i]; it <= hi[i]; it++) {
                    int64_t ix = floor_div((int64_t)gx[k] - tx[it], d);
                    int64_t iy = floor_div((int64_t)gy[k] - ty[it], d);
                    if (ix < 0 || ix >= nx || iy < 0 || iy >= ny)
                        continue;
                    uint16_t *c = ref + ((size_t)it * ny + (size_t)iy) * nx + (size_t)ix;
                    uint32_t sum = *c + 1u;
                    *c = (uint16_t)(sum < HL_VOTE_MAX ? sum : HL_VOTE_MAX);
                    saturated += *c == HL_VOTE_MAX;
                    note(ref_most, ntx, ix, iy, *c);
                    ref_cast++;
                }
            }
            hl_votelone_raster_t r = { nx, ny, nt, (uint32_t)(nx * d), (uint32_t)(ny * d), d,
                                       tx, ty, votes, notes ? most : NULL, ntx };
            cast += hl_votelone_cast(&v, &r);
        }
        hl_votelone_fold(&v, most, ntiles);
        assert_int_equal(cast, ref_cast);
        assert_memory_equal(votes, ref, cells * sizeof *votes);
        if (notes)
            assert_memory_equal(most, ref_most, ntiles * sizeof *most);
        for (uint32_t t = 0; t < MAX_TILES; t++)   /* the lanes are left zero */
            for (int l = 0; l < 3; l++)
                assert_int_equal(v.lane[l][t], 0);
        total += cast;
    }
    assert_true(total > 100000);    /* the trials voted, some into saturated cells */
    assert_true(saturated > 0);
    hl_votelone_free(&v);
    free(votes);
    free(ref);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lone_is_the_general_loop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
