/* Tests for src/core/blur.c: kernel normalization, impulse response, the overflow
 * bound at saturation, zero padding at the borders. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>

#include "blur.h"

static void test_kernel_sums_to_256(void **state)
{
    (void)state;
    const double sigmas[] = { 0.0, 0.3, 1.0, 1.5, 2.7, 6.0, 100.0 };
    for (size_t i = 0; i < sizeof sigmas / sizeof sigmas[0]; i++) {
        hl_kernel_t k;
        hl_kernel_gaussian(&k, sigmas[i]);
        uint32_t sum = 0;
        for (int32_t j = 0; j <= 2 * k.radius; j++)
            sum += k.taps[j];
        assert_int_equal(sum, 256);
        assert_true(k.radius <= HL_BLUR_MAX_RADIUS);
        for (int32_t j = 0; j < k.radius; j++) {
            assert_int_equal(k.taps[j], k.taps[2 * k.radius - j]);   /* symmetric */
            assert_true(k.taps[j] <= k.taps[j + 1]);                  /* unimodal */
        }
    }
    hl_kernel_t k;
    hl_kernel_gaussian(&k, 0.0);
    assert_int_equal(k.radius, 0);
    hl_kernel_gaussian(&k, 1.5);
    assert_int_equal(k.radius, 4);
}

static void test_impulse_response_is_the_kernel(void **state)
{
    (void)state;
    enum { NX = 21, NY = 15, NT = 5 };
    uint16_t *v = calloc(NX * NY * NT, sizeof *v);
    uint32_t *a = calloc(NX * NY * NT, sizeof *a), *b = calloc(NX * NY * NT, sizeof *b);
    v[(2 * NY + 7) * NX + 10] = 1000;
    hl_kernel_t kx, kt;
    hl_kernel_gaussian(&kx, 1.5);
    hl_kernel_gaussian(&kt, 0.8);
    uint32_t *out = hl_blur3(v, NX, NY, NT, &kx, &kx, &kt, a, b);
    /* the centre holds 1000 * kx[c]^2 * kt[c] / 256^3, in units of votes x 256 */
    uint32_t c = kx.taps[kx.radius], ct = kt.taps[kt.radius];
    uint64_t want = (uint64_t)1000 * c * c * ct / (256 * 256);
    uint32_t got = out[(2 * NY + 7) * NX + 10];
    assert_true(got + 2 >= want && got <= want + 2);
    /* symmetric in x and y, zero beyond the radius */
    assert_int_equal(out[(2 * NY + 7) * NX + 9], out[(2 * NY + 7) * NX + 11]);
    assert_int_equal(out[(2 * NY + 6) * NX + 10], out[(2 * NY + 8) * NX + 10]);
    assert_int_equal(out[(2 * NY + 7) * NX + 10 + kx.radius + 1], 0);
    /* total mass conserved up to rounding (all inside the raster) */
    uint64_t total = 0;
    for (int i = 0; i < NX * NY * NT; i++)
        total += out[i];
    assert_true(total >= 1000u * 256u - 300 && total <= 1000u * 256u + 300);
    free(v);
    free(a);
    free(b);
}

/* Every cell saturated: the output must be exactly 65535 x 256 in the interior (no
 * overflow anywhere in the passes, fixed.h's bound) and less at the zero-padded edges. */
static void test_saturated_raster_does_not_overflow(void **state)
{
    (void)state;
    enum { NX = 40, NY = 30, NT = 7 };
    uint16_t *v = malloc(NX * NY * NT * sizeof *v);
    uint32_t *a = calloc(NX * NY * NT, sizeof *a), *b = calloc(NX * NY * NT, sizeof *b);
    for (int i = 0; i < NX * NY * NT; i++)
        v[i] = UINT16_MAX;
    hl_kernel_t k, kt;
    hl_kernel_gaussian(&k, 3.0);
    hl_kernel_gaussian(&kt, 1.0);
    uint32_t *out = hl_blur3(v, NX, NY, NT, &k, &k, &kt, a, b);
    assert_int_equal(out[(3 * NY + 15) * NX + 20], 65535u * 256u);
    assert_true(out[0] < 65535u * 256u && out[0] > 0);
    for (int i = 0; i < NX * NY * NT; i++)
        assert_true(out[i] <= 65535u * 256u);
    free(v);
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kernel_sums_to_256),
        cmocka_unit_test(test_impulse_response_is_the_kernel),
        cmocka_unit_test(test_saturated_raster_does_not_overflow),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
