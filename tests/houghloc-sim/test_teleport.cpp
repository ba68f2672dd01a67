// test_teleport.cpp - houghloc-sim's kidnapped-robot fault: the true pose jumps to
// --teleport-to while the odometry does not; random destinations are clear, far enough
// and the same for the same seed; a teleport due during a motion waits for the base to
// stand still; the options and the free-space check refuse bad values.
#include <algorithm>

#include "houghloc/calib.h"
#include "options.hpp"
#include "simrobot.hpp"
#include "teleport.hpp"

#include "rooms.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

namespace {

struct Rig {
    World world;
    std::vector<std::string> lines;
    Log log{[this](const std::string &s) { lines.push_back(s); }};
    SimConfig cfg;
    SimRobot robot;
    Rig(World w, const TeleportPlan &plan, Pose start = {}, uint64_t seed = 1)
        : world(std::move(w)), cfg(config(plan, seed)), robot(world, cfg, start, log) {}
    static SimConfig config(const TeleportPlan &plan, uint64_t seed)
    {
        SimConfig c;
        sim_profile("bonnie", &c.profile);
        c.seed = seed;
        c.teleport = plan;
        // Exact sonar ranges, so a reading tells where the robot truly is.
        c.sonar.noise_sigma_mm = c.sonar.noise_frac = 0.0;
        c.sonar.p_multipath = c.sonar.p_cable = c.sonar.p_dropout = 0.0;
        return c;
    }
    void cmd(uint8_t n, int32_t arg)
    {
        hl_arcos_cmd_t c{};
        c.number = n;
        c.arg_kind = HL_ARCOS_ARG_INT;
        c.arg = arg;
        robot.heard();
        assert_true(robot.command(c));
    }
    hl_arcos_sip_t step()
    {
        robot.heard();
        return robot.step();
    }
    int count(const char *what) const
    {
        int n = 0;
        for (const std::string &l : lines)
            n += l.find(what) != std::string::npos;
        return n;
    }
};

TeleportPlan to_plan(double after_s, double every_s, double x_mm, double y_mm, double deg)
{
    TeleportPlan p;
    p.after_s = after_s;
    p.every_s = every_s;
    p.has_to = true;
    p.to = Pose{x_mm, y_mm, deg2rad(deg)};
    return p;
}

void assert_pose(const Pose &p, double x_mm, double y_mm, double deg)
{
    assert_near(p.x, x_mm, 1.0);                                  // 1 mm
    assert_near(p.y, y_mm, 1.0);
    assert_near(rad2deg(wrap_pi(p.theta - deg2rad(deg))), 0.0, 0.01);   // 0.01 deg
}

}  // namespace

// --teleport-after 5 --teleport-to 1,0.5,90: the truth jumps there at 5 s, the
// odometry and the SIPs' x, y, heading do not; the sonar ranges from the new pose.
static void test_teleport_to(void **state)
{
    (void)state;
    Rig r(six_metre_room(), to_plan(5.0, -1.0, 1000.0, 500.0, 90.0));
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_MOVE, 400);
    hl_arcos_sip_t s{};
    for (int k = 0; k < 40 && (k < 2 || s.type != HL_ARCOS_SIP_STOPPED); k++)
        s = r.step();
    r.cmd(HL_ARCOS_HEAD, 30);
    for (int k = 0; k < 40 && (k < 2 || s.type != HL_ARCOS_SIP_STOPPED); k++)
        s = r.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_true(r.robot.utime() < 5000000);
    const Pose odom = r.robot.base().odom();
    const Pose before = r.robot.base().truth();
    assert_near(odom.x, 400.0, 1e-6);
    while (r.robot.utime() < 4900000) {
        s = r.step();
        assert_near(r.robot.base().truth().x, before.x, 0.0);   // not yet
    }
    assert_int_equal(r.robot.teleports(), 0);
    hl_arcos_sip_t last = s;
    s = r.step();                                  // 4.9 .. 5.0 s: it happens
    assert_int_equal(r.robot.teleports(), 1);
    assert_pose(r.robot.base().truth(), 1000.0, 500.0, 90.0);
    // The odometry did not move, nor do the SIPs say anything moved.
    assert_near(r.robot.base().odom().x, odom.x, 0.0);
    assert_near(r.robot.base().odom().y, odom.y, 0.0);
    assert_near(r.robot.base().odom().theta, odom.theta, 0.0);
    assert_int_equal(s.x, last.x);
    assert_int_equal(s.y, last.y);
    assert_int_equal(s.th, last.th);
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(r.count("fault: teleported (--teleport-after): true pose from ("), 1);
    assert_int_equal(r.count("to (1.000, 0.500) m 90.0 deg; odometry unchanged"), 1);
    // Once only; the sonar now ranges from (1, 0.5) facing north: 2.5 m ahead (transducer
    // 0), 2 m to the right (transducer 12, 270 degrees).
    r.cmd(HL_ARCOS_SONAR, 1);
    int found = 0;
    for (int k = 0; k < 30; k++) {
        s = r.step();
        for (int i = 0; i < s.sonar_count; i++) {
            int32_t mm = 0;
            int t = s.sonar[i].transducer;
            if ((t == 0 || t == 12) && hl_calib_apply(&r.cfg.sonar.calib, s.sonar[i].range, &mm)) {
                assert_near(mm, t == 0 ? 2500.0 : 2000.0, 3.0);
                found++;
            }
        }
    }
    assert_true(found >= 8);
    assert_int_equal(r.robot.teleports(), 1);
    assert_pose(r.robot.base().truth(), 1000.0, 500.0, 90.0);
}

// Random destinations: 2 m away or more, 0.6 m clear of every surface, closed in, and
// the same for the same seed.
static std::vector<Pose> random_run(uint64_t seed, int *logged)
{
    TeleportPlan plan;
    plan.every_s = 1.0;
    Rig r(World::lab(), plan, Pose{609.6, 6705.6, 0.0}, seed);   // the lab's tour start
    std::vector<Pose> poses{r.robot.base().truth()};
    for (int k = 0; k < 80; k++) {                 // 8 s: 8 teleports
        r.step();
        const Pose &t = r.robot.base().truth();
        if (t.x != poses.back().x || t.y != poses.back().y || t.theta != poses.back().theta)
            poses.push_back(t);
    }
    assert_int_equal(r.robot.teleports(), 8);
    *logged = r.count("fault: teleported (--teleport-every)");
    for (std::size_t i = 1; i < poses.size(); i++) {
        std::string why;
        assert_true((poses[i].pos() - poses[i - 1].pos()).norm() >= kTeleportMinJumpMm);
        assert_true(r.world.clearance(poses[i].pos()) >= kTeleportClearanceMm);
        assert_true(r.world.enclosed(poses[i].pos(), &why));
        assert_true(poses[i].theta >= -kPi && poses[i].theta < kPi);
    }
    return poses;
}

static void test_teleport_random(void **state)
{
    (void)state;
    int logged = 0;
    std::vector<Pose> a = random_run(7, &logged);
    assert_int_equal(a.size(), 9);
    assert_int_equal(logged, 8);
    std::vector<Pose> b = random_run(7, &logged);
    assert_int_equal(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); i++) {
        assert_near(b[i].x, a[i].x, 0.0);
        assert_near(b[i].y, a[i].y, 0.0);
        assert_near(b[i].theta, a[i].theta, 0.0);
    }
    std::vector<Pose> c = random_run(8, &logged);   // another seed, other places
    assert_true(c[1].x != a[1].x || c[1].y != a[1].y);
    // Headings spread over the circle, not one value.
    double lo = a[1].theta, hi = a[1].theta;
    for (std::size_t i = 1; i < a.size(); i++) {
        lo = std::min(lo, a[i].theta);
        hi = std::max(hi, a[i].theta);
    }
    assert_true(hi - lo > 1.0);
}

// A teleport due while a MOVE runs waits until the base stands still: the move ends
// where odometry says, then the truth jumps. The next motion starts from there.
static void test_teleport_waits_for_stop(void **state)
{
    (void)state;
    Rig r(six_metre_room(), to_plan(1.0, -1.0, -1500.0, -1500.0, 180.0));
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_MOVE, 1000);                    // about 3.8 s
    hl_arcos_sip_t s{};
    Pose moving_truth;
    int steps = 0;
    for (; steps < 100; steps++) {
        s = r.step();
        if (s.type == HL_ARCOS_SIP_STOPPED)
            break;
        assert_int_equal(r.robot.teleports(), 0);
        moving_truth = r.robot.base().truth();
        assert_true(moving_truth.x > 0.0 && moving_truth.x < 1300.0);   // still on its way
        if (r.robot.utime() > 1000000)
            assert_true(r.robot.teleport_pending());
    }
    assert_true(steps >= 35);                      // well past the 1 s it was due at
    assert_int_equal(r.count("it waits until the base stands still"), 1);
    // The SIP that says stopped: the move finished in odometry, then the jump.
    assert_int_equal(s.x, 1000);
    assert_near(r.robot.base().odom().x, 1000.0, 1e-6);
    assert_int_equal(r.robot.teleports(), 1);
    assert_false(r.robot.teleport_pending());
    assert_pose(r.robot.base().truth(), -1500.0, -1500.0, 180.0);
    assert_true(moving_truth.x > 700.0);           // the last moving SIP was near the end
    // Driving on: 500 mm west from the new pose (heading 180), odometry from 1000 on.
    r.cmd(HL_ARCOS_MOVE, 500);
    for (int k = 0; k < 40 && (k < 2 || s.type != HL_ARCOS_SIP_STOPPED); k++)
        s = r.step();
    assert_int_equal(s.x, 1500);
    assert_near(r.robot.base().truth().x, -2000.0, 100.0);
    assert_near(r.robot.base().truth().y, -1500.0, 100.0);
    assert_int_equal(r.robot.teleports(), 1);
}

static ParseResult parse(std::vector<const char *> args, SimOptions *o, std::string *err)
{
    args.insert(args.begin(), "houghloc-sim");
    return parse_options(static_cast<int>(args.size()), const_cast<char **>(args.data()), o, err);
}

static void test_teleport_options(void **state)
{
    (void)state;
    SimOptions o;
    std::string err;
    assert_int_equal(static_cast<int>(parse({"--teleport-after", "12.5", "--teleport-every",
                                             "0.1", "--teleport-to", "1.5,-2,-90"},
                                            &o, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_near(o.teleport.after_s, 12.5, 0.0);
    assert_near(o.teleport.every_s, 0.1, 0.0);
    assert_true(o.teleport.has_to);
    assert_pose(o.teleport.to, 1500.0, -2000.0, -90.0);
    SimOptions d;                                  // none given: never
    assert_int_equal(static_cast<int>(parse({"--teleport-after", "0"}, &d, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_near(d.teleport.after_s, 0.0, 0.0);
    assert_false(d.teleport.has_to);
    const std::vector<std::vector<const char *>> bad = {
        {"--teleport-after", "-1"}, {"--teleport-after", "x"}, {"--teleport-after", "1e8"},
        {"--teleport-after", ""}, {"--teleport-after", "nan"}, {"--teleport-after"},
        {"--teleport-every", "0"}, {"--teleport-every", "0.05"}, {"--teleport-every", "-3"},
        {"--teleport-every", "2s"}, {"--teleport-to", "1,2", "--teleport-after", "1"},
        {"--teleport-to", "a,b,c", "--teleport-after", "1"},
        {"--teleport-to", "1,2,400", "--teleport-after", "1"},
        {"--teleport-to", "1,2,3"}};               // and nothing says when
    for (const auto &args : bad) {
        SimOptions x;
        err.clear();
        assert_int_equal(static_cast<int>(parse(args, &x, &err)),
                         static_cast<int>(ParseResult::Error));
        assert_true(err.find(args[0]) == 0);                    // names the option
        assert_true(err.find('\n') == std::string::npos);      // one line
    }
}

// main() checks --teleport-to against the world with check_free_pose (exit 2 if not).
static void test_free_pose_check(void **state)
{
    (void)state;
    World w = six_metre_room();
    std::string err;
    assert_true(check_free_pose(w, Pose{0, 0, 0}, "--teleport-to", &err));
    assert_true(check_free_pose(w, Pose{2750, 2750, 0}, "--teleport-to", &err));   // 250 mm
    for (const Pose &p : {Pose{2900, 0, 0}, Pose{3000, 1000, 0}, Pose{-2990, -2990, 0},
                          Pose{5000, 0, 0}, Pose{-40000, 3000, 1}}) {
        err.clear();
        assert_false(check_free_pose(w, p, "--teleport-to", &err));
        assert_true(err.find("--teleport-to: (") == 0);
        assert_true(err.find("is not in free space") != std::string::npos);
        assert_true(err.find('\n') == std::string::npos);
    }
    // Random destinations in a world with no such place: given up, not looped forever.
    World small;
    small.parse("polygon 0 0 1500 0 1500 1500 0 1500\n", "small", &err);
    Rng rng(1);
    Pose out;
    assert_false(random_free_pose(small, Pose{750, 750, 0}, rng, &out));
    TeleportPlan plan;
    plan.after_s = 0.0;
    Rig r(std::move(small), plan, Pose{750, 750, 0});
    r.step();
    assert_int_equal(r.robot.teleports(), 0);
    assert_int_equal(r.count("fault: teleport (--teleport-after) skipped"), 1);
    assert_near(r.robot.base().truth().x, 750.0, 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teleport_to),
        cmocka_unit_test(test_teleport_random),
        cmocka_unit_test(test_teleport_waits_for_stop),
        cmocka_unit_test(test_teleport_options),
        cmocka_unit_test(test_free_pose_check),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
