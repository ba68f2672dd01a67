// test_robot.cpp - the sounding's shape, body rotation, odometry noise, determinism.
#include "houghloc/fixed.h"
#include "robot.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

static World square_room()
{
    World w;
    std::string err;
    w.parse("polygon -3000 -3000 3000 -3000 3000 3000 -3000 3000\n"
            "circle 1200 800 250\n",
            "room", &err);
    return w;
}

static void test_sounding_shape(void **state)
{
    (void)state;
    World w = square_room();
    Rng rng(3);
    SonarParams sp;
    RobotParams rp;
    Robot r(w, sp, rp, rng, 1000);
    Pose p{100, -200, deg2rad(30)};
    r.place(p, p);
    Sounding s = r.sound();
    assert_int_equal(s.readings.size(), 128);
    for (std::size_t i = 0; i < 128; i++) {
        const RingReading &x = s.readings[i];
        // Ordered by nominal bearing, 2.8125 degrees (512 BAM) apart.
        assert_int_equal(x.bearing_bam, i * 512);
        assert_int_equal(x.transducer, i / 8);
        assert_int_equal(x.step, i % 8);
        // The true direction errs from the nominal by the accumulated step errors.
        double nominal = p.theta + hl_bam_to_rad(x.bearing_bam);
        assert_true(std::fabs(wrap_pi(x.true_axis - nominal)) < deg2rad(3.0));
    }
    // The body returns to its heading; time moves on; odometry is unchanged.
    assert_near(r.truth().theta, p.theta, 1e-12);
    assert_near(s.odom.x, 100.0, 1e-12);
    assert_true(s.utime > 1000 + 2000000);
    assert_true(r.take_odometry().empty());
}

static void test_rotation_error(void **state)
{
    (void)state;
    World w = square_room();
    Rng rng(4);
    SonarParams sp;
    RobotParams rp;
    rp.rotation_sigma_deg = 0.0;
    Robot exact(w, sp, rp, rng, 0);
    exact.place({}, {});
    Sounding s = exact.sound();
    for (const RingReading &x : s.readings)
        assert_near(wrap_pi(x.true_axis - hl_bam_to_rad(x.bearing_bam)), 0.0, 1e-4);
    // With the default 0.3 degrees per step, step 7 errs by sqrt(7) * 0.3 on average.
    rp.rotation_sigma_deg = 0.3;
    Robot noisy(w, sp, rp, rng, 0);
    noisy.place({}, {});
    double s2 = 0.0;
    int n = 0;
    for (int k = 0; k < 200; k++)
        for (const RingReading &x : noisy.sound().readings)
            if (x.step == 7 && x.transducer == 0) {
                double e = rad2deg(wrap_pi(x.true_axis - hl_bam_to_rad(x.bearing_bam)));
                s2 += e * e;
                n++;
            }
    assert_near(std::sqrt(s2 / n), std::sqrt(7.0) * 0.3, 0.12);
}

static void test_odometry_noise(void **state)
{
    (void)state;
    World w = square_room();
    Rng rng(5);
    SonarParams sp;
    RobotParams rp;
    Robot r(w, sp, rp, rng, 0);
    double sf = 0, sl = 0, sh = 0;
    const int n = 4000;
    for (int k = 0; k < n; k++) {
        r.place({}, {});
        r.drive(1000.0);
        // Odometry integrates the command exactly; the truth errs.
        assert_near(r.odom().x, 1000.0, 1e-9);
        assert_near(r.odom().y, 0.0, 1e-9);
        double fwd = r.truth().x - 1000.0, lat = r.truth().y;
        sf += fwd * fwd;
        sl += lat * lat;
        sh += r.truth().theta * r.truth().theta;
    }
    assert_near(std::sqrt(sf / n), 50.0, 3.0);            // 5% of 1 m
    assert_near(std::sqrt(sl / n), 50.0 * 1.0, 4.0);      // plus the heading's share
    assert_near(rad2deg(std::sqrt(sh / n)), 2.0, 0.15);   // 2 degrees per metre
    double st = 0;
    for (int k = 0; k < n; k++) {
        r.place({}, {});
        r.turn(kPi / 2);
        assert_near(r.odom().theta, kPi / 2, 1e-12);
        st += std::pow(r.truth().theta - kPi / 2, 2);
    }
    assert_near(std::sqrt(st / n), 0.02 * kPi / 2, 0.003);  // 2% of the turn
}

static void test_motion_reports(void **state)
{
    (void)state;
    World w = square_room();
    Rng rng(6);
    SonarParams sp;
    RobotParams rp;
    Robot r(w, sp, rp, rng, 0);
    r.place({}, {});
    r.go_to({0, 600});  // turn 90 degrees (2 s), drive 600 mm (2 s)
    std::vector<OdoSample> odo = r.take_odometry();
    assert_int_equal(r.utime(), 4000000);
    assert_true(odo.size() >= 38);
    for (std::size_t i = 1; i < odo.size(); i++)
        assert_true(odo[i].utime > odo[i - 1].utime);
    assert_true(odo.back().stopped);
    assert_near(odo.back().odom.y, 600.0, 1e-9);
    // steer_to aims from the truth, so the truth lands near the goal.
    r.place({0, 0, 0}, {500, 500, 1.0});
    r.steer_to({600, 0});
    assert_true((r.truth().pos() - Vec2{600, 0}).norm() < 200.0);
    assert_near((r.odom().pos() - Vec2{500, 500}).norm(), 600.0, 1e-9);
}

static std::vector<uint16_t> raws(uint64_t seed)
{
    World w = square_room();
    Rng rng(seed);
    SonarParams sp;
    RobotParams rp;
    Robot r(w, sp, rp, rng, 0);
    r.place({-500, 300, 0.3}, {-500, 300, 0.3});
    std::vector<uint16_t> out;
    for (int k = 0; k < 3; k++) {
        r.steer_to({-500.0 + 400 * k, 300});
        for (const RingReading &x : r.sound().readings)
            out.push_back(x.sonar.raw);
    }
    return out;
}

static void test_determinism(void **state)
{
    (void)state;
    std::vector<uint16_t> a = raws(42), b = raws(42), c = raws(43);
    assert_int_equal(a.size(), 384);
    assert_true(a == b);
    int differ = 0;
    for (std::size_t i = 0; i < a.size(); i++)
        differ += a[i] != c[i];
    assert_true(differ > 300);  // noise touches nearly every reading
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sounding_shape),
        cmocka_unit_test(test_rotation_error),
        cmocka_unit_test(test_odometry_noise),
        cmocka_unit_test(test_motion_reports),
        cmocka_unit_test(test_determinism),
    };
    return cmocka_run_group_tests_name("sim/robot", tests, NULL, NULL);
}
