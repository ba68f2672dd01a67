/* Tests for src/core/tiles.c and hl_blur3_box (src/core/blur.c): on random sparse vote
 * rasters, the tiles' search finds hl_peak_find's peak and second peak over hl_blur3's
 * raster, ties included, and lays out and reads hl_blur3's cells; a box's blur is
 * hl_blur3's on its cells; clearing the voted tiles leaves the raster zero. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "blur.h"
#include "peak.h"
#include "tiles.h"

enum { MAX_SIDE = 300, MAX_NT = 9, MAX_CELLS = MAX_SIDE * MAX_SIDE * MAX_NT };

static uint32_t rng_state = 12345;

static uint32_t rnd(uint32_t n)  /* 0 .. n - 1 (xorshift32) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state % n;
}

typedef struct raster {
    int32_t nx, ny, nt;
    uint16_t *votes;
    uint32_t *a, *b, *laid;
} raster_t;

/* A random sparse raster: a few blobs (some copies of one another, so that maxima tie)
 * and scattered single votes, some near saturation. Every vote noted in @p t. */
static void fill(raster_t *r, hl_tiles_t *t)
{
    size_t cells = (size_t)r->nx * r->ny * r->nt;
    uint16_t blob[5][5];
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++)
            blob[i][j] = (uint16_t)(1 + rnd(rnd(4) ? 50 : 65535));
    int nblobs = (int)rnd(6);
    for (int k = 0; k < nblobs; k++) {
        int32_t x0 = (int32_t)rnd((uint32_t)r->nx), y0 = (int32_t)rnd((uint32_t)r->ny);
        int32_t it = (int32_t)rnd((uint32_t)r->nt);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) {
                int32_t x = x0 + j, y = y0 + i;
                if (x >= r->nx || y >= r->ny)
                    continue;
                r->votes[((size_t)it * r->ny + y) * r->nx + x] = blob[i][j];
            }
    }
    size_t scattered = rnd(4) ? cells / (1 + rnd(200)) : rnd(5);
    for (size_t k = 0; k < scattered; k++)
        r->votes[rnd((uint32_t)cells)] = (uint16_t)(1 + rnd(rnd(8) ? 20 : 65535));
    for (int32_t it = 0; it < r->nt; it++)
        for (int32_t iy = 0; iy < r->ny; iy++)
            for (int32_t ix = 0; ix < r->nx; ix++) {
                uint16_t v = r->votes[((size_t)it * r->ny + iy) * r->nx + ix];
                if (v)
                    hl_tiles_note(t->most, (uint32_t)t->ntx, (uint32_t)ix, (uint32_t)iy, v);
            }
}

/* The buffers of the largest raster, zero. */
static raster_t raster_alloc(void)
{
    raster_t r = { 0 };
    r.votes = calloc(MAX_CELLS, sizeof *r.votes);
    r.a = calloc(MAX_CELLS, sizeof *r.a);
    r.b = calloc(MAX_CELLS, sizeof *r.b);
    r.laid = calloc(MAX_CELLS, sizeof *r.laid);
    assert_true(r.votes && r.a && r.b && r.laid);
    return r;
}

static void raster_free(raster_t *r)
{
    free(r->votes);
    free(r->a);
    free(r->b);
    free(r->laid);
}

static void test_box_is_hl_blur3(void **state)
{
    (void)state;
    raster_t r = raster_alloc();
    uint32_t *box = malloc(HL_BLUR_BOX_MAX_W * 40 * MAX_NT * sizeof *box);
    uint32_t *scratch = malloc(HL_BLUR_BOX_SCRATCH(HL_BLUR_BOX_MAX_W, 40, MAX_NT) *
                               sizeof *scratch);
    for (int trial = 0; trial < 300; trial++) {
        r.nx = 1 + (int32_t)rnd(120);
        r.ny = 1 + (int32_t)rnd(120);
        r.nt = 1 + (int32_t)rnd(MAX_NT);
        size_t cells = (size_t)r.nx * r.ny * r.nt;
        for (size_t i = 0; i < cells; i++)
            r.votes[i] = rnd(3) ? 0 : (uint16_t)rnd(rnd(10) ? 100 : 65536);
        hl_kernel_t kx, ky, kt;
        hl_kernel_gaussian(&kx, rnd(50) / 10.0);
        hl_kernel_gaussian(&ky, rnd(50) / 10.0);
        hl_kernel_gaussian(&kt, rnd(20) / 10.0);
        const uint32_t *full = hl_blur3(r.votes, r.nx, r.ny, r.nt, &kx, &ky, &kt, r.a, r.b);
        int32_t x0 = (int32_t)rnd((uint32_t)r.nx), y0 = (int32_t)rnd((uint32_t)r.ny);
        int32_t w = 1 + (int32_t)rnd(HL_BLUR_BOX_MAX_W), h = 1 + (int32_t)rnd(40);
        w = x0 + w > r.nx ? r.nx - x0 : w;
        h = y0 + h > r.ny ? r.ny - y0 : h;
        uint32_t m = hl_blur3_box(r.votes, r.nx, r.ny, r.nt, &kx, &ky, &kt, x0, y0, w, h,
                                  scratch, box);
        uint32_t want_m = 0;
        for (int32_t it = 0; it < r.nt; it++)
            for (int32_t i = 0; i < h; i++)
                for (int32_t j = 0; j < w; j++) {
                    uint32_t want = full[((size_t)it * r.ny + y0 + i) * r.nx + x0 + j];
                    assert_int_equal(box[((size_t)it * h + i) * w + j], want);
                    want_m = want > want_m ? want : want_m;
                }
        assert_int_equal(m, want_m);
    }
    raster_free(&r);
    free(box);
    free(scratch);
}

static void test_search_is_the_plain_peak(void **state)
{
    (void)state;
    raster_t r = raster_alloc();
    uint32_t *store = calloc(MAX_CELLS, sizeof *store);
    uint32_t *row_max = calloc(MAX_SIDE * MAX_NT, sizeof *row_max);
    hl_tiles_t t;
    assert_true(hl_tiles_init(&t, MAX_CELLS, MAX_SIDE, MAX_NT));
    assert_true(hl_tiles_mem_bytes(&t) > 0);
    assert_false(hl_tiles_fit(&t, 10, 10, MAX_NT + 1));
    int found = 0, ties = 0;
    for (int trial = 0; trial < 400; trial++) {
        /* one hl_tiles_t through rasters of every shape, as a localizer's runs */
        r.nx = 1 + (int32_t)rnd(MAX_SIDE);
        r.ny = 1 + (int32_t)rnd(MAX_SIDE);
        r.nt = 1 + (int32_t)rnd(MAX_NT);
        assert_true(hl_tiles_fit(&t, r.nx, r.ny, r.nt));
        size_t cells = (size_t)r.nx * r.ny * r.nt;
        hl_tiles_begin(&t, r.nx, r.ny, r.nt);
        fill(&r, &t);
        hl_tiles_take_votes(&t);
        hl_kernel_t kx, kt;
        hl_kernel_gaussian(&kx, rnd(40) / 10.0);
        hl_kernel_gaussian(&kt, rnd(15) / 10.0);
        int32_t cell_mm = 10 + (int32_t)rnd(90), sep_mm = (int32_t)rnd(3000);

        const uint32_t *full = hl_blur3(r.votes, r.nx, r.ny, r.nt, &kx, &kx, &kt, r.a, r.b);
        hl_grid_t g = { .cells = full, .nx = r.nx, .ny = r.ny, .nt = r.nt,
                        .row_max = row_max };
        hl_peak_t want, got;
        int want_found = hl_peak_find(&g, cell_mm, sep_mm, &want);
        int got_found = hl_tiles_search(&t, r.votes, &kx, &kx, &kt, store, cell_mm, sep_mm,
                                        &got);
        assert_int_equal(got_found, want_found);
        if (want_found) {
            found++;
            assert_int_equal(got.score, want.score);
            assert_int_equal(got.ix, want.ix);
            assert_int_equal(got.iy, want.iy);
            assert_int_equal(got.it, want.it);
            assert_int_equal(got.second, want.second);
            ties += want.second == want.score;
        }
        /* single cells, the peak's neighbours among them, then the whole raster */
        for (int k = 0; k < 50; k++) {
            int32_t ix = (int32_t)rnd((uint32_t)r.nx), iy = (int32_t)rnd((uint32_t)r.ny);
            int32_t it = (int32_t)rnd((uint32_t)r.nt);
            if (want_found && k < 3) {
                ix = want.ix + (k == 1) - (k == 2);
                ix = ix < 0 ? 0 : ix >= r.nx ? r.nx - 1 : ix;
                iy = want.iy;
                it = want.it;
            }
            assert_int_equal(hl_tiles_cell(&t, ix, iy, it),
                             full[((size_t)it * r.ny + iy) * r.nx + ix]);
        }
        memset(r.laid, 0, cells * sizeof *r.laid);
        hl_tiles_lay_out(&t, r.laid);
        assert_memory_equal(r.laid, full, cells * sizeof *full);

        hl_tiles_clear_votes(&t, r.votes);
        for (size_t i = 0; i < cells; i++)
            assert_int_equal(r.votes[i], 0);
        for (uint32_t i = 0; i < t.capacity; i++)
            assert_int_equal(t.most[i], 0);
    }
    assert_true(found > 300);   /* the trials found peaks, and some tied */
    assert_true(ties > 5);
    hl_tiles_free(&t);
    raster_free(&r);
    free(store);
    free(row_max);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_is_hl_blur3),
        cmocka_unit_test(test_search_is_the_plain_peak),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
