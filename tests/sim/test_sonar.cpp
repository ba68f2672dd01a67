// test_sonar.cpp - the physical echo model (beam pattern, range loss, surfaces, corners,
// thin targets), the old cone model's first echo and specular loss, calibration, noise
// and garbage rates, and the generator's determinism.
#include <algorithm>
#include <cmath>
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

// The first simulator's hard 22-degree cone.
static SonarParams cone()
{
    SonarParams p = noiseless();
    p.model = SonarParams::Model::Cone;
    return p;
}

// A long wall whose normal points @p normal_deg off the +x axis, @p dist_mm away.
static World tilted_wall(double normal_deg, double dist_mm, Surface s)
{
    World w;
    Vec2 n = Vec2::polar(deg2rad(normal_deg));
    Vec2 foot = n * dist_mm, along{-n.y, n.x};
    w.segments.push_back({foot - along * 20000.0, foot + along * 20000.0, s});
    return w;
}

// The strongest echo of a ping along +x from the origin (-infinity when none).
static double strongest_db(const World &w, const SonarParams &p)
{
    double best = -INFINITY;
    for (const EchoCandidate &e : sonar_echoes(w, p, {0, 0}, 0.0))
        best = std::max(best, e.level_db);
    return best;
}

// J1 by its power series, independent of the library's std::cyl_bessel_j.
static double bessel_j1(double x)
{
    double term = x / 2.0, sum = 0.0;
    for (int m = 0; m < 40; m++) {
        sum += term;
        term *= -(x / 2.0) * (x / 2.0) / ((m + 1.0) * (m + 2.0));
    }
    return sum;
}

static void test_beam_pattern(void **state)
{
    (void)state;
    SonarParams p;
    // ka = 2 pi 49.4 kHz / 343.2 m/s * 19 mm = 17.18: first null at asin(3.8317 / ka).
    double ka = 2.0 * kPi * 49400.0 / 343.2 * 0.019;
    assert_near(rad2deg(sonar_main_lobe(p)), rad2deg(std::asin(3.8317059702 / ka)), 1e-6);
    assert_near(rad2deg(sonar_main_lobe(p)), 12.89, 0.01);
    assert_near(sonar_beam_db(p, 0.0), 0.0, 1e-12);
    double prev = 0.0;
    for (double deg : {1.0, 3.0, 5.0, 8.0, 11.0, 12.5}) {
        double x = ka * std::sin(deg2rad(deg));
        double expect = 40.0 * std::log10(std::fabs(2.0 * bessel_j1(x) / x));
        double got = sonar_beam_db(p, deg2rad(deg));
        assert_near(got, expect, 1e-6);
        assert_near(sonar_beam_db(p, -deg2rad(deg)), got, 1e-12);  // symmetric
        assert_true(got < prev);
        prev = got;
    }
    assert_near(sonar_beam_db(p, deg2rad(8.0)), -14.4, 0.1);
    assert_true(std::isinf(sonar_beam_db(p, deg2rad(13.0))));  // no side lobes
}

static void test_level_falls_with_range_and_angle(void **state)
{
    (void)state;
    SonarParams p;
    // A smooth wall square to the beam: the sensor's image at twice the range, and
    // 1.6 dB/m of absorption each way.
    double prev = 0.0;
    for (double d : {500.0, 1000.0, 2000.0, 4000.0, 7000.0}) {
        double got = strongest_db(tilted_wall(0.0, d, Surface::Smooth), p);
        double r = d / 1000.0;
        assert_near(got, -20.0 * std::log10(2.0 * r) - 2.0 * 1.6 * r, 1e-9);
        assert_true(got < prev);
        prev = got;
    }
    // A wall at 10 m, square on, is too weak (the 6500 board reaches ~10.7 m; our
    // listening window ends at 8 m anyway, so open it for this test).
    p.max_range_mm = 12000.0;
    assert_true(sonar_first_echo(tilted_wall(0.0, 10000.0, Surface::Smooth), p, {0, 0}, 0.0) > 0.0);
    assert_true(sonar_first_echo(tilted_wall(0.0, 11000.0, Surface::Smooth), p, {0, 0}, 0.0) < 0.0);
    // A post off the axis: weaker by the beam pattern. (At the lobe's edge a ray nearer
    // the axis, meeting the post obliquely, is a little louder than its centre's.)
    SonarParams q;
    prev = 0.0;
    for (double deg : {0.0, 4.0, 8.0, 12.0}) {
        World w;
        w.circles.push_back({Vec2::polar(deg2rad(deg)) * 2000.0, 100.0, Surface::Smooth});
        double got = strongest_db(w, q);
        // Cylinder: spreading 40 log r, target strength 10 log(a r / 2).
        double expect = -40.0 * std::log10(1.9) + 10.0 * std::log10(0.1 * 1.9 / 2.0) -
                        3.2 * 1.9 + sonar_beam_db(q, deg2rad(deg));
        if (deg < 10.0)
            assert_near(got, expect, 1e-6);
        else
            assert_true(got < expect + 5.0);
        if (deg > 0.0)
            assert_true(got < prev);
        prev = got;
    }
}

static void test_smooth_and_rough_at_60_degrees(void **state)
{
    (void)state;
    SonarParams p;
    // 60 degrees off the normal a smooth wall reflects the sound away...
    assert_true(sonar_first_echo(tilted_wall(60.0, 1000.0, Surface::Smooth), p, {0, 0}, 0.0) < 0.0);
    // ... a rough one scatters some back, from a ray between the lobe's edge nearest the
    // normal (47.1 degrees incidence) and the axis (60 degrees).
    double r = sonar_first_echo(tilted_wall(60.0, 1000.0, Surface::Rough), p, {0, 0}, 0.0);
    assert_true(r > 1000.0 / std::cos(deg2rad(60.0 - 12.9)) - 1.0);
    assert_true(r < 1000.0 / std::cos(deg2rad(60.0)));
    // Square on, the rough wall is weaker than the smooth one (part of its sound is
    // scattered), and near the normal a smooth wall still echoes.
    double smooth = strongest_db(tilted_wall(0.0, 2000.0, Surface::Smooth), p);
    double rough = strongest_db(tilted_wall(0.0, 2000.0, Surface::Rough), p);
    assert_true(rough < smooth && rough > smooth - 3.1);
    assert_near(sonar_first_echo(tilted_wall(20.0, 1000.0, Surface::Smooth), p, {0, 0}, 0.0),
                1000.0 / std::cos(deg2rad(20.0 - 12.89)), 30.0);
}

static void test_concave_corner_returns_at_45_degrees(void **state)
{
    (void)state;
    SonarParams p;
    // Two smooth walls meet at a right angle 2 m ahead, each at 45 degrees to the beam.
    World corner;
    Vec2 c{2000, 0};
    corner.segments.push_back({c, c + Vec2{-3000, 3000}});
    corner.segments.push_back({c + Vec2{-3000, -3000}, c});
    Hit h;
    assert_near(sonar_first_echo(corner, p, {0, 0}, 0.0, &h), 2000.0, 1e-9);
    assert_near(h.point.x, 2000.0, 1e-9);
    // As strong as a wall square to the beam at that range.
    assert_near(strongest_db(corner, p), strongest_db(tilted_wall(0.0, 2000.0, Surface::Smooth), p),
                1e-9);
    // A corner reflector works off its bisector too (sensor 30 degrees off it): as loud
    // as a mirror at 1.5 m. (The wall it then faces at 15 degrees echoes a little nearer.)
    bool found = false;
    for (const EchoCandidate &e :
         sonar_echoes(corner, p, c + Vec2::polar(deg2rad(150.0)) * 1500.0, deg2rad(-30.0)))
        if (std::fabs(e.range_mm - 1500.0) < 1e-6) {
            assert_near(e.level_db, -20.0 * std::log10(3.0) - 2.0 * 1.6 * 1.5, 1e-9);
            found = true;
        }
    assert_true(found);
    // One of those walls alone, through the same point: no echo.
    World flat;
    flat.segments.push_back({c + Vec2{-3000, 3000}, c + Vec2{3000, -3000}});
    assert_true(sonar_first_echo(flat, p, {0, 0}, 0.0) < 0.0);
    // The same walls 8 mm apart still make a corner; 5 cm apart they do not, and their
    // free ends only diffract: 30 dB weaker than the corner.
    double mirror = -20.0 * std::log10(4.0) - 2.0 * 1.6 * 2.0;
    for (double gap : {8.0, 50.0}) {
        World w;
        w.segments.push_back({c + Vec2{0, gap}, c + Vec2{-3000, 3000 + gap}});
        w.segments.push_back({c + Vec2{-3000, -3000}, c});
        assert_near(sonar_first_echo(w, p, {0, 0}, 0.0), 2000.0, 0.7);
        double expect = gap < 10.0 ? mirror : -40.0 * std::log10(2.0) - 2.0 * 1.6 * 2.0 - 30.0;
        assert_near(strongest_db(w, p), expect, 0.05);
    }
    // The convex side of a corner (a box's edge) diffracts weakly: heard at 1 m, not at 4.
    World box;
    box.add_box({1000 + 300 * std::sqrt(2.0), 0}, 600, 600, deg2rad(45.0));
    assert_near(sonar_first_echo(box, p, {0, 0}, 0.0), 1000.0, 1e-6);
    World far_box;
    far_box.add_box({4000 + 300 * std::sqrt(2.0), 0}, 600, 600, deg2rad(45.0));
    assert_true(sonar_first_echo(far_box, p, {0, 0}, 0.0) < 0.0);
}

static void test_thin_leg_is_weaker_than_a_wall(void **state)
{
    (void)state;
    SonarParams p;
    World leg;
    leg.circles.push_back({{2012.5, 0}, 12.5, Surface::Thin});
    double leg_db = strongest_db(leg, p);
    double wall_db = strongest_db(tilted_wall(0.0, 2000.0, Surface::Smooth), p);
    assert_true(leg_db < wall_db - 15.0);
    assert_near(sonar_first_echo(leg, p, {0, 0}, 0.0), 2000.0, 1e-6);  // alone, it is heard
    // A circle thinner than 30 mm is thin whatever its word.
    World smooth_leg;
    smooth_leg.circles.push_back({{2012.5, 0}, 12.5, Surface::Smooth});
    assert_near(strongest_db(smooth_leg, p), leg_db, 1e-9);
    // A leg at 1.5 m, 11 degrees off the axis, before a wall at 2.5 m: the cone heard the
    // leg; the physical sonar hears the wall (the leg is too weak that far off the axis).
    World w = tilted_wall(0.0, 2500.0, Surface::Smooth);
    w.circles.push_back({Vec2::polar(deg2rad(11.0)) * 1512.5, 12.5, Surface::Thin});
    assert_near(sonar_first_echo(w, cone(), {0, 0}, 0.0), 1500.0, 1e-6);
    assert_near(sonar_first_echo(w, p, {0, 0}, 0.0), 2500.0, 1e-6);
    // On the axis the leg is nearer and loud enough: it comes first.
    w.circles[0].c = {1512.5, 0};
    assert_near(sonar_first_echo(w, p, {0, 0}, 0.0), 1500.0, 1e-6);
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
    SonarParams p = cone();
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
    SonarParams p = cone();
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
        cmocka_unit_test(test_beam_pattern),
        cmocka_unit_test(test_level_falls_with_range_and_angle),
        cmocka_unit_test(test_smooth_and_rough_at_60_degrees),
        cmocka_unit_test(test_concave_corner_returns_at_45_degrees),
        cmocka_unit_test(test_thin_leg_is_weaker_than_a_wall),
        cmocka_unit_test(test_cone_returns_nearest_surface),
        cmocka_unit_test(test_critical_angle_gives_no_echo),
        cmocka_unit_test(test_nothing_within_max_range),
        cmocka_unit_test(test_raw_is_inverse_calibration),
        cmocka_unit_test(test_noise_and_garbage_rates),
        cmocka_unit_test(test_rng_is_standard_and_deterministic),
    };
    return cmocka_run_group_tests_name("sim/sonar", tests, NULL, NULL);
}
