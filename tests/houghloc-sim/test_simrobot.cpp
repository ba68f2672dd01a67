// test_simrobot.cpp - houghloc-sim's pure robot model: position and velocity commands,
// odometry and its wrap, the watchdog, the sonar ring, walls, SETO, motion noise.
#include "houghloc/calib.h"
#include "simrobot.hpp"

#include "rooms.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

namespace {

struct Rig {
    World world = six_metre_room();
    std::vector<std::string> lines;
    Log log{[this](const std::string &s) { lines.push_back(s); }};
    SimConfig cfg;
    SimRobot robot;
    explicit Rig(Pose start = {}, const char *profile = "bonnie", uint64_t seed = 1)
        : cfg(config(profile, seed)), robot(world, cfg, start, log) {}
    static SimConfig config(const char *profile, uint64_t seed)
    {
        SimConfig c;
        sim_profile(profile, &c.profile);
        c.seed = seed;
        return c;
    }
    void cmd(uint8_t n, int32_t arg, hl_arcos_arg_t kind = HL_ARCOS_ARG_INT)
    {
        hl_arcos_cmd_t c{};
        c.number = n;
        c.arg_kind = kind;
        c.arg = arg;
        robot.heard();
        assert_true(robot.command(c));
    }
    void none(uint8_t n) { cmd(n, 0, HL_ARCOS_ARG_NONE); }
    // Steps until a stopped SIP (at most @p max); returns it, counting the steps.
    hl_arcos_sip_t until_stopped(int max, int *steps = nullptr)
    {
        hl_arcos_sip_t s{};
        int k = 0;
        for (; k < max; k++) {
            robot.heard();
            s = robot.step();
            if (s.type == HL_ARCOS_SIP_STOPPED)
                break;
        }
        if (steps)
            *steps = k + 1;
        return s;
    }
    bool logged(const char *what) const
    {
        for (const std::string &l : lines)
            if (l.find(what) != std::string::npos)
                return true;
        return false;
    }
};

}  // namespace

static void test_move(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_MOVE, 1000);
    hl_arcos_sip_t s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_true(s.flags & HL_ARCOS_FLAG_MOTORS);
    assert_true(s.vel_left > 0 && s.vel_left == s.vel_right);
    int steps = 0;
    s = r.until_stopped(100, &steps);
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(s.x, 1000);
    assert_int_equal(s.y, 0);
    assert_int_equal(s.th, 0);
    assert_int_equal(s.vel_left, 0);
    assert_near(r.robot.base().odom().x, 1000.0, 1.0);
    // 267 mm to reach 400 mm/s at 300 mm/s^2, as much to brake: about 3.8 s.
    assert_true(steps >= 36 && steps <= 42);
    // Stopped for good; the true pose moved about as far, with noise.
    for (int k = 0; k < 5; k++) {
        s = r.robot.step();
        assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
        assert_int_equal(s.x, 1000);
    }
    assert_near(r.robot.base().truth().pos().norm(), 1000.0, 250.0);
    // Backwards: x goes out as the low 15 bits (-300 mm is 32468) and unwraps.
    hl_arcos_odom_t u;
    hl_arcos_odom_init(&u, 4096);
    assert_int_equal(hl_arcos_odom_unwrap(&u, &s), HL_OK);
    r.cmd(HL_ARCOS_MOVE, -1300);
    for (int k = 0; k < 100; k++) {
        r.robot.heard();
        s = r.robot.step();
        assert_int_equal(hl_arcos_odom_unwrap(&u, &s), HL_OK);
        if (s.type == HL_ARCOS_SIP_STOPPED)
            break;
    }
    assert_int_equal(s.x, 32768 - 300);
    assert_int_equal(u.x, -300);
}

static void test_head_dhead(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_HEAD, 90);
    hl_arcos_sip_t s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_int_equal(s.control, 1024);           // the setpoint
    assert_true(s.vel_right > 0 && s.vel_left == -s.vel_right);
    s = r.until_stopped(100);
    assert_int_equal(s.th, 1024);
    assert_near(r.robot.base().odom().theta, kPi / 2, 1e-9);
    assert_near(r.robot.base().odom().pos().norm(), 0.0, 1e-9);  // turned in place
    // HEAD 350 from 90 is 100 degrees clockwise, not 260 counter-clockwise.
    r.cmd(HL_ARCOS_HEAD, 350);
    int lowest = 4096;
    for (int k = 0; k < 100; k++) {
        r.robot.heard();
        s = r.robot.step();
        lowest = std::min(lowest, static_cast<int>(s.th));
        if (s.type == HL_ARCOS_SIP_STOPPED)
            break;
    }
    assert_int_equal(s.th, -114);                // -10 degrees = -113.8 units
    assert_int_equal(lowest, -114);              // never past it
    // DHEAD turns relative to the heading, past 180 included.
    r.cmd(HL_ARCOS_DHEAD, 100);
    s = r.until_stopped(100);
    assert_int_equal(s.th, 1024);
    r.cmd(HL_ARCOS_DHEAD, -270);
    s = r.until_stopped(200);
    assert_int_equal(s.th, -2048);               // 90 - 270 = -180
    r.cmd(HL_ARCOS_DHEAD, 45);
    s = r.until_stopped(100);
    assert_int_equal(s.th, -1536);
}

static void test_stop_and_limits(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_SETV, 200);
    r.cmd(HL_ARCOS_SETA, 1000);
    r.cmd(HL_ARCOS_SETA, -500);
    r.cmd(HL_ARCOS_VEL, 300);                    // capped at SETV
    hl_arcos_sip_t s{};
    for (int k = 0; k < 10; k++)
        s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_int_equal(s.vel_left, 200);
    r.none(HL_ARCOS_STOP);
    int steps = 0;
    s = r.until_stopped(20, &steps);
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_true(steps <= 5);                     // 200 mm/s at 500 mm/s^2: 0.4 s
    uint16_t x = s.x;
    for (int k = 0; k < 5; k++)
        assert_int_equal(r.robot.step().x, x);
    // RVEL, then STOP.
    r.cmd(HL_ARCOS_RVEL, -30);
    for (int k = 0; k < 10; k++)
        s = r.robot.step();
    assert_true(s.vel_left > 0 && s.vel_right < 0);   // clockwise
    r.none(HL_ARCOS_STOP);
    s = r.until_stopped(20);
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(s.vel_left, 0);
}

static void test_watchdog(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_VEL, 100);                    // heard at t = 0
    hl_arcos_sip_t s{};
    for (int k = 0; k < 20; k++)                 // 2.0 s without a packet
        s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_false(r.logged("watchdog"));
    s = r.robot.step();                          // due now: it brakes
    assert_true(r.logged("watchdog"));
    for (int k = 0; k < 5 && s.type != HL_ARCOS_SIP_STOPPED; k++)
        s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    // A client that keeps talking keeps the robot going.
    r.lines.clear();
    r.cmd(HL_ARCOS_VEL, 100);
    for (int k = 0; k < 60; k++) {
        if (k % 15 == 0)
            r.robot.heard();
        s = r.robot.step();
    }
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_false(r.logged("watchdog"));
}

// Every transducer within one ring period (16 x 40 ms), 2 or 3 readings per SIP.
static void check_ring(const char *profile)
{
    Rig r({0, 0, 0}, profile);
    r.cmd(HL_ARCOS_SONAR, 1);
    std::vector<int> seen(16, 0);
    for (int k = 0; k < 7; k++) {                // 700 ms
        hl_arcos_sip_t s = r.robot.step();
        assert_true(s.sonar_count == 2 || s.sonar_count == 3);
        assert_int_equal(s.flags & HL_ARCOS_FLAG_SONAR, 0x6);   // arrays 1 and 2
        for (int i = 0; i < s.sonar_count; i++) {
            assert_true(s.sonar[i].transducer < 16);
            seen[s.sonar[i].transducer]++;
        }
    }
    for (int t = 0; t < 16; t++)
        assert_true(seen[t] >= 1);
}

static void test_sonar_ring(void **state)
{
    (void)state;
    check_ring("bonnie");
    check_ring("pioneer3");
    Rig r;
    r.cmd(HL_ARCOS_SONAR, 3);                    // array 1 alone: transducers 0..7
    r.cmd(HL_ARCOS_SONARCYCLE, 20);              // 5 readings per SIP
    for (int k = 0; k < 4; k++) {
        hl_arcos_sip_t s = r.robot.step();
        assert_int_equal(s.sonar_count, 5);
        assert_int_equal(s.flags & HL_ARCOS_FLAG_SONAR, 0x2);
        for (int i = 0; i < 5; i++)
            assert_true(s.sonar[i].transducer < 8);
    }
    r.cmd(HL_ARCOS_SONAR, 0);
    assert_int_equal(r.robot.step().sonar_count, 0);
}

// The raw value is tools/sim's, from the true pose: without noise, the calibration
// inverse of the distance to the wall.
static void test_sonar_values(void **state)
{
    (void)state;
    World w = six_metre_room();
    Log log{[](const std::string &) {}};
    SimConfig c;
    sim_profile("bonnie", &c.profile);
    c.sonar.noise_sigma_mm = c.sonar.noise_frac = 0.0;
    c.sonar.p_multipath = c.sonar.p_cable = c.sonar.p_dropout = 0.0;
    SimRobot robot(w, c, Pose{1000, 0, 0}, log);   // 2 m from the east wall, 3 m from N/S
    hl_arcos_cmd_t on{};
    on.number = HL_ARCOS_SONAR;
    on.arg_kind = HL_ARCOS_ARG_INT;
    on.arg = 1;
    assert_true(robot.command(on));
    int found = 0;
    for (int k = 0; k < 6; k++) {                // 16 firings, 0 to 600 ms
        hl_arcos_sip_t s = robot.step();
        for (int i = 0; i < s.sonar_count; i++) {
            int32_t mm = 0;
            bool valid = hl_calib_apply(&c.sonar.calib, s.sonar[i].range, &mm);
            if (s.sonar[i].transducer % 4 == 0)
                assert_true(valid);                  // the four facing a wall squarely
            if (s.sonar[i].transducer == 0) {
                assert_near(mm, 2000.0, 3.0);
                found++;
            } else if (s.sonar[i].transducer == 4 || s.sonar[i].transducer == 12) {
                assert_near(mm, 3000.0, 3.0);    // 90 and 270 degrees
                found++;
            }
        }
    }
    assert_int_equal(found, 3);
}

static void test_wall_stall(void **state)
{
    (void)state;
    Rig r(Pose{2400, 0, 0});                     // 600 mm from the east wall
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_MOVE, 1000);
    hl_arcos_sip_t s{};
    int stalled = 0;
    for (int k = 0; k < 60; k++) {
        r.robot.heard();
        s = r.robot.step();
        if (s.stall_bumpers == (HL_ARCOS_STALL_LEFT | HL_ARCOS_STALL_RIGHT))
            stalled++;
    }
    assert_true(stalled >= 35);                  // every SIP once it is at the wall (~1.6 s)
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);   // the MOVE still pushes
    assert_true(r.robot.base().truth().x <= 2750.0 + 1e-9);
    assert_true(r.robot.base().truth().x > 2700.0);
    assert_true(s.x < 1000 && s.x > 250);        // odometry stopped with the wheels
    assert_true(r.logged("against a wall"));
    r.none(HL_ARCOS_STOP);
    s = r.until_stopped(10);
    s = r.robot.step();
    assert_int_equal(s.stall_bumpers, 0);
    // Backing away is free.
    uint16_t x0 = s.x;
    r.cmd(HL_ARCOS_MOVE, -500);
    s = r.until_stopped(60);
    assert_int_equal(s.x, (x0 - 500) & 0x7FFF);
    assert_int_equal(s.stall_bumpers, 0);
}

// A collision is a contact episode, counted and logged once at its first refused step.
static void test_collisions(void **state)
{
    (void)state;
    Rig r(Pose{2400, 0, 0});                     // 600 mm from the east wall
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_VEL, 300);                    // into the wall, and keeps pushing
    for (int k = 0; k < 60; k++) {
        r.robot.heard();
        r.robot.step();
    }
    assert_true(r.robot.base().truth().x > 2700.0);
    assert_int_equal(r.robot.collisions(), 1);
    int logged = 0;
    for (const std::string &l : r.lines)
        logged += l.find("collision at (2.7") != std::string::npos &&
                  l.find(" m, heading ") != std::string::npos &&
                  l.find(" deg") != std::string::npos;
    assert_int_equal(logged, 1);
    // Stopping, standing, turning in place and pushing again: still the same contact.
    r.none(HL_ARCOS_STOP);
    r.until_stopped(10);
    r.cmd(HL_ARCOS_DHEAD, 10);
    r.until_stopped(30);
    r.cmd(HL_ARCOS_MOVE, 300);
    for (int k = 0; k < 20; k++) {
        r.robot.heard();
        r.robot.step();
    }
    assert_int_equal(r.robot.collisions(), 1);
    // Back away, then drive into the wall again: a second collision.
    r.none(HL_ARCOS_STOP);
    r.until_stopped(10);
    r.cmd(HL_ARCOS_MOVE, -400);
    r.until_stopped(60);
    assert_true(r.robot.base().truth().x < 2500.0);
    assert_int_equal(r.robot.collisions(), 1);
    r.cmd(HL_ARCOS_MOVE, 1000);
    for (int k = 0; k < 60; k++) {
        r.robot.heard();
        r.robot.step();
    }
    assert_int_equal(r.robot.collisions(), 2);

    // Driven along a free line, through the room and back: never.
    Rig f(Pose{-2000, 0, 0});
    f.cmd(HL_ARCOS_ENABLE, 1);
    f.cmd(HL_ARCOS_MOVE, 4000);
    assert_int_equal(f.until_stopped(200).type, HL_ARCOS_SIP_STOPPED);
    f.cmd(HL_ARCOS_MOVE, -4000);
    assert_int_equal(f.until_stopped(200).type, HL_ARCOS_SIP_STOPPED);
    assert_true(f.robot.base().truth().x < -1000.0);
    assert_int_equal(f.robot.collisions(), 0);
    assert_false(f.logged("collision"));

    // Stalled wheels (--stall-after) push against nothing: no collision.
    Rig st;
    st.cmd(HL_ARCOS_ENABLE, 1);
    st.robot.stall_wheels();
    st.cmd(HL_ARCOS_VEL, 300);
    for (int k = 0; k < 10; k++)
        st.robot.step();
    assert_int_equal(st.robot.collisions(), 0);
}

static void test_stall_fault_and_motors(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_MOVE, 500);                   // motors off: ignored
    hl_arcos_sip_t s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(s.flags & HL_ARCOS_FLAG_MOTORS, 0);
    assert_true(r.logged("motors are off"));
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.robot.stall_wheels();
    r.cmd(HL_ARCOS_MOVE, 500);
    for (int k = 0; k < 5; k++)
        s = r.robot.step();
    assert_int_equal(s.x, 0);
    assert_int_equal(s.stall_bumpers, HL_ARCOS_STALL_LEFT | HL_ARCOS_STALL_RIGHT);
    assert_int_equal(s.type, HL_ARCOS_SIP_MOVING);
    assert_near(r.robot.base().truth().pos().norm(), 0.0, 1e-12);
    assert_true(r.logged("wheels do not turn"));
}

static void test_seto_and_connection_end(void **state)
{
    (void)state;
    Rig r;
    r.cmd(HL_ARCOS_ENABLE, 1);
    r.cmd(HL_ARCOS_MOVE, 300);
    hl_arcos_sip_t s = r.until_stopped(50);
    r.cmd(HL_ARCOS_HEAD, 45);
    s = r.until_stopped(50);
    assert_int_equal(s.x, 300);
    assert_int_equal(s.th, 512);
    Pose truth = r.robot.base().truth();
    r.none(HL_ARCOS_SETO);
    s = r.robot.step();
    assert_int_equal(s.x, 0);
    assert_int_equal(s.y, 0);
    assert_int_equal(s.th, 0);
    assert_near(r.robot.base().truth().x, truth.x, 1e-12);   // the world did not move
    // The client goes: stopped, motors and sonar off; the pose stays.
    r.cmd(HL_ARCOS_SONAR, 1);
    r.cmd(HL_ARCOS_VEL, 200);
    r.robot.step();
    r.robot.connection_end();
    s = r.robot.step();
    assert_int_equal(s.type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(s.flags, 0);
    assert_int_equal(s.sonar_count, 0);
    assert_true(s.x > 0 && s.x < 100);
}

// The leg's true error has tools/sim's distribution: 5% of the distance forward and
// sideways, 2 degrees per metre of heading (RobotParams' defaults).
static void test_motion_noise(void **state)
{
    (void)state;
    const int n = 300;
    double sf = 0, sl = 0, sh = 0;
    for (int k = 0; k < n; k++) {
        Rig r(Pose{-1000, 0, 0}, "bonnie", 100 + k);
        r.cmd(HL_ARCOS_ENABLE, 1);
        r.cmd(HL_ARCOS_MOVE, 1000);
        hl_arcos_sip_t s = r.until_stopped(100);
        assert_int_equal(s.x, 1000);
        const Pose &t = r.robot.base().truth();
        sf += (t.x - 0.0) * (t.x - 0.0);
        sl += t.y * t.y;
        sh += t.theta * t.theta;
    }
    assert_near(std::sqrt(sf / n), 50.0, 8.0);
    assert_near(std::sqrt(sl / n), 53.0, 10.0);  // slip, and 17 mm from the drift
    assert_near(rad2deg(std::sqrt(sh / n)), 2.0, 0.3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_move),
        cmocka_unit_test(test_head_dhead),
        cmocka_unit_test(test_stop_and_limits),
        cmocka_unit_test(test_watchdog),
        cmocka_unit_test(test_sonar_ring),
        cmocka_unit_test(test_sonar_values),
        cmocka_unit_test(test_wall_stall),
        cmocka_unit_test(test_collisions),
        cmocka_unit_test(test_stall_fault_and_motors),
        cmocka_unit_test(test_seto_and_connection_end),
        cmocka_unit_test(test_motion_noise),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
