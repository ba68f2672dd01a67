// test_sonar.cpp - the cone's first echo, specular loss, calibration, noise and
// garbage rates, and the generator's determinism.
#include <cstring>

#include "houghloc/calib.h"
#include "rng.hpp"
#include "sonar.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

// Every random effect off: the reading is the geometric first echo.
static SonarParams noiseless()
{
    SonarParams p;
    p.noise_sigma_mm = 0.0;
    p.noise_frac = 0.0;
    p.p_multipath = 0.0;
    p.p_cable = 0.0;
    p.p_dropout = 0.0;
    return p;
}

static World wall_at(double x)
{
    World w;
    w.segments.push_back({{x, -5000}, {x, 5000}});
    return w;
}

static void test_cone_returns_nearest_surface(void **state)
{
    (void)state;
    SonarParams p = noiseless();
    World w = wall_at(3000);
    // A thin post 8 degrees off the axis, nearer than the wall: the cone sees it.
    double a = deg2rad(8.0);
    w.circles.push_back({{2000 * std::cos(a), 2000 * std::sin(a)}, 20});
    assert_near(sonar_first_echo(w, p, {0, 0}, 0.0), 1980.0, 1e-6);
    // Outside the 22-degree cone (15 degrees off) it is not seen: the wall is.
    World w2 = wall_at(3000);
    double b = deg2rad(15.0);
    w2.circles.push_back({{2000 * std::cos(b), 2000 * std::sin(b)}, 20});
    assert_near(sonar_first_echo(w2, p, {0, 0}, 0.0), 3000.0, 1e-6);
    // A wall whose normal is 8 degrees off the axis echoes from its nearest point.
    World w3;
    Vec2 n = Vec2::polar(deg2rad(8.0));
    Vec2 foot = n * 2500.0, along{-n.y, n.x};
    w3.segments.push_back({foot - along * 4000.0, foot + along * 4000.0});
    Hit h;
    assert_near(sonar_first_echo(w3, p, {0, 0}, 0.0, &h), 2500.0, 1e-6);
    assert_near(h.point.x, foot.x, 1e-6);
}

static void test_critical_angle_gives_no_echo(void **state)
{
    (void)state;
    SonarParams p = noiseless();
    // A wall whose normal is 60 degrees off the axis: every ray in the cone meets it
    // at 49..71 degrees incidence, beyond the 40-degree critical angle.
    World w;
    Vec2 n = Vec2::polar(deg2rad(60.0));
    Vec2 foot = n * 1000.0, along{-n.y, n.x};
    w.segments.push_back({foot - along * 8000.0, foot + along * 8000.0});
    assert_true(sonar_first_echo(w, p, {0, 0}, 0.0) < 0.0);
    Rng rng(1);
    SonarReading r = sonar_ping(w, p, {0, 0}, 0.0, rng);
    assert_int_equal(r.raw, 16384);
    assert_int_equal(static_cast<int>(r.kind), static_cast<int>(Echo::None));
    // At 30 degrees the cone's edge (11 degrees) meets it at 19 degrees: an echo, at
    // the perpendicular distance over cos(19 degrees).
    World w2;
    Vec2 n2 = Vec2::polar(deg2rad(30.0));
    Vec2 foot2 = n2 * 1000.0, along2{-n2.y, n2.x};
    w2.segments.push_back({foot2 - along2 * 8000.0, foot2 + along2 * 8000.0});
    assert_near(sonar_first_echo(w2, p, {0, 0}, 0.0), 1000.0 / std::cos(deg2rad(19.0)), 1e-6);
    // Raising the critical angle lets the 60-degree wall echo.
    p.critical_deg = 50.0;
    assert_near(sonar_first_echo(w, p, {0, 0}, 0.0), 1000.0 / std::cos(deg2rad(49.0)), 1e-6);
}

static void test_nothing_within_max_range(void **state)
{
    (void)state;
    SonarParams p = noiseless();
    World w = wall_at(9000);  // beyond the 8000 mm default
    Rng rng(1);
    assert_true(sonar_first_echo(w, p, {0, 0}, 0.0) < 0.0);
    assert_int_equal(sonar_ping(w, p, {0, 0}, 0.0, rng).raw, p.sentinel_raw);
}

static void test_raw_is_inverse_calibration(void **state)
{
    (void)state;
    SonarParams p = noiseless();
    World w = wall_at(2000);
    Rng rng(1);
    SonarReading r = sonar_ping(w, p, {0, 0}, 0.0, rng);
    // 2000 mm = 1.07 mm/raw * raw - 35 mm  ->  raw = 1901.87
    assert_int_equal(r.raw, 1902);
    assert_int_equal(r.raw, hl_calib_raw_for(&p.calib, 2000));
    int32_t mm;
    assert_true(hl_calib_apply(&p.calib, r.raw, &mm));
    assert_in_range(mm, 1999, 2001);
}

static void test_noise_and_garbage_rates(void **state)
{
    (void)state;
    SonarParams p;  // defaults
    World w = wall_at(2000);
    Rng rng(7);
    const int n = 40000;
    int cable = 0, sentinel = 0, multipath = 0, surface = 0;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; i++) {
        SonarReading r = sonar_ping(w, p, {0, 0}, 0.0, rng);
        int32_t mm;
        hl_calib_apply(&p.calib, r.raw, &mm);
        if (r.raw < 200)
            cable++;
        if (r.raw == p.sentinel_raw)
            sentinel++;
        if (r.kind == Echo::Multipath) {
            multipath++;
            assert_true(mm >= 2000 + 300 - 250 && mm <= 2000 + 2000 + 250);  // 6 sigma
        }
        if (r.kind == Echo::Surface) {
            surface++;
            sum += mm - 2000.0;
            sum2 += (mm - 2000.0) * (mm - 2000.0);
        }
    }
    assert_in_range(cable, n * 0.027, n * 0.033);
    assert_in_range(sentinel, n * 0.027, n * 0.033);
    // Multipath applies to readings that survived cable and dropout: 0.05 * 0.94.
    assert_in_range(multipath, n * 0.043, n * 0.051);
    double mean = sum / surface, sd = std::sqrt(sum2 / surface - mean * mean);
    assert_near(mean, 0.0, 1.5);
    assert_near(sd, 10.0 + 0.01 * 2000.0, 1.5);  // plus ~0.3 mm of raw quantization
}

static void test_rng_is_standard_and_deterministic(void **state)
{
    (void)state;
    // The C++ standard fixes mt19937_64's 10000th output for the default seed.
    std::mt19937_64 ref;
    ref.discard(9999);
    assert_true(ref() == 9981545732273789042ULL);
    Rng a(5), b(5), c(6);
    bool differs = false;
    for (int i = 0; i < 1000; i++) {
        double x = a.normal(), y = b.normal(), z = c.normal();
        assert_true(std::memcmp(&x, &y, sizeof x) == 0);
        differs |= x != z;
    }
    assert_true(differs);
    Rng d(11);
    double s = 0.0, s2 = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; i++) {
        double x = d.normal();
        s += x;
        s2 += x * x;
    }
    assert_near(s / n, 0.0, 0.01);
    assert_near(s2 / n, 1.0, 0.01);
    for (int i = 0; i < 1000; i++) {
        double u = d.uniform();
        assert_true(u >= 0.0 && u < 1.0);
        int64_t k = d.uniform_int(20, 199);
        assert_true(k >= 20 && k <= 199);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone_returns_nearest_surface),
        cmocka_unit_test(test_critical_angle_gives_no_echo),
        cmocka_unit_test(test_nothing_within_max_range),
        cmocka_unit_test(test_raw_is_inverse_calibration),
        cmocka_unit_test(test_noise_and_garbage_rates),
        cmocka_unit_test(test_rng_is_standard_and_deterministic),
    };
    return cmocka_run_group_tests_name("sim/sonar", tests, NULL, NULL);
}
