// test_options.cpp - houghloc-sim's strict command line: numbers, options, --help and
// --version.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "houghloc/version.h"
#include "options.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

static void test_numbers(void **state)
{
    (void)state;
    double d = 0;
    uint64_t n = 0;
    assert_true(parse_number("2.5", &d));
    assert_near(d, 2.5, 0.0);
    assert_true(parse_number("-3e2", &d));
    assert_near(d, -300.0, 0.0);
    for (const char *bad : {"", " 1", "1 ", "1e", "0x10", "inf", "nan", "1,5", "--1", "1e999"})
        assert_false(parse_number(bad, &d));
    assert_true(parse_count("65535", 65535, &n));
    assert_int_equal(n, 65535);
    assert_true(parse_count("18446744073709551615", UINT64_MAX, &n));
    for (const char *bad : {"", "-1", "+1", "65536", "1.0", "1a", "18446744073709551616"})
        assert_false(parse_count(bad, bad[0] == '1' && bad[1] == '8' ? UINT64_MAX : 65535, &n));
}

static ParseResult parse(std::vector<const char *> args, SimOptions *o, std::string *err)
{
    args.insert(args.begin(), "houghloc-sim");
    return parse_options(static_cast<int>(args.size()), const_cast<char **>(args.data()), o, err);
}

static void test_options(void **state)
{
    (void)state;
    SimOptions o;
    std::string err;
    assert_int_equal(static_cast<int>(parse({"--speed", "10", "--port", "0", "--start",
                                             "1.5,-2,90", "--profile", "pioneer3",
                                             "--garbage-every", "7", "--no-truth"},
                                            &o, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_near(o.speed, 10.0, 0.0);
    assert_int_equal(o.port, 0);
    assert_true(o.has_start);
    assert_near(o.start_x_m, 1.5, 0.0);
    assert_near(o.start_y_m, -2.0, 0.0);
    assert_near(o.start_deg, 90.0, 0.0);
    assert_string_equal(o.profile.c_str(), "pioneer3");
    assert_int_equal(o.faults.garbage_every, 7);
    assert_false(o.truth);
    assert_int_equal(static_cast<int>(parse({"--port", "1", "--help"}, &o, &err)),
                     static_cast<int>(ParseResult::Help));
    assert_int_equal(static_cast<int>(parse({"--port", "1", "--version"}, &o, &err)),
                     static_cast<int>(ParseResult::Version));
    const std::vector<std::vector<const char *>> bad = {
        {"--speed", "0.05"}, {"--speed", "101"}, {"--speed", "1x"}, {"--port", "65536"},
        {"--start", "1,2"}, {"--start", "1,2,3,4"}, {"--profile", "p3dx"},
        {"--sonar-model", "ray"}, {"--bind", "localhost"}, {"--garbage-every", "0"},
        {"--prefix", "a b"}, {"--watchdog", "-1"}, {"--frobnicate"}, {"--seed"}};
    for (const auto &args : bad) {
        SimOptions x;
        err.clear();
        assert_int_equal(static_cast<int>(parse(args, &x, &err)),
                         static_cast<int>(ParseResult::Error));
        assert_true(err.find(args[0]) != std::string::npos);   // names the option
        assert_true(err.find('\n') == std::string::npos);      // one line
    }
}

// --lockstep: the flag, and --speed up to 1000 with it (up to 100 without), in either
// order.
static void test_lockstep_option(void **state)
{
    (void)state;
    SimOptions o;
    std::string err;
    assert_false(o.lockstep);
    assert_int_equal(static_cast<int>(parse({"--speed", "1000", "--lockstep"}, &o, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_true(o.lockstep);
    assert_near(o.speed, 1000.0, 0.0);
    SimOptions o2;
    assert_int_equal(static_cast<int>(parse({"--lockstep", "--speed", "250"}, &o2, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_near(o2.speed, 250.0, 0.0);
    SimOptions o3;
    assert_int_equal(static_cast<int>(parse({"--speed", "100"}, &o3, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_false(o3.lockstep);
    const std::vector<std::vector<const char *>> bad = {
        {"--speed", "100.5"}, {"--speed", "1000"}, {"--speed", "1001", "--lockstep"},
        {"--speed", "0.05", "--lockstep"}, {"--lockstep", "--speed", "1e4"}};
    for (const auto &args : bad) {
        SimOptions x;
        err.clear();
        assert_int_equal(static_cast<int>(parse(args, &x, &err)),
                         static_cast<int>(ParseResult::Error));
        assert_true(err.find("--speed") == 0);
        assert_true(err.find('\n') == std::string::npos);
    }
    char *text = nullptr;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    print_usage(f);
    std::fclose(f);
    assert_non_null(std::strstr(text, "--lockstep"));
    std::free(text);
}

// The start pose: --start, else the world's start line, else its tour start; each
// checked to be free space.
static void test_start_pose(void **state)
{
    (void)state;
    std::string err;
    Pose p;
    SimOptions none;
    // The lab: its start line, in the open south-east leg.
    World lab = World::lab();
    assert_true(start_pose(lab, none, &p, &err));
    assert_near(p.x, 5400.0, 0.0);
    assert_near(p.y, 1500.0, 0.0);
    assert_near(p.theta, 0.0, 0.0);
    // --start wins (the old default, the tour start in the north-west corner).
    SimOptions old;
    assert_int_equal(static_cast<int>(parse({"--start", "0.6096,6.7056,0"}, &old, &err)),
                     static_cast<int>(ParseResult::Run));
    assert_true(start_pose(lab, old, &p, &err));
    assert_near(p.x, 609.6, 1e-9);
    assert_near(p.y, 6705.6, 1e-9);
    // Without a start line: the tour start (snapped to the tile grid), heading 0.
    World w;
    const char *room = "polygon 0 0 4000 0 4000 4000 0 4000\n";
    assert_true(w.parse(std::string(room) + "tour 1100 1300\n", "t.world", &err));
    assert_true(start_pose(w, none, &p, &err));
    assert_near(p.x, 2 * 609.6, 1e-9);
    assert_near(p.y, 2 * 609.6, 1e-9);
    assert_near(p.theta, 0.0, 0.0);
    assert_true(w.parse(std::string(room) + "tour 1100 1300\nstart 3000 2000 90\n", "t.world",
                        &err));
    assert_true(start_pose(w, none, &p, &err));
    assert_near(p.x, 3000.0, 0.0);
    assert_near(p.theta, kPi / 2, 1e-12);
    // A start line too close to a wall, or outside the room, is refused as --start is.
    assert_true(w.parse(std::string(room) + "start 3900 2000 0\n", "t.world", &err));
    assert_false(start_pose(w, none, &p, &err));
    assert_true(err.find("the world's start: (3.900, 2.000) m is not in free space") == 0);
    assert_true(err.find("give --start") != std::string::npos);
    assert_true(w.parse(std::string(room) + "start 5000 2000 0\n", "t.world", &err));
    assert_false(start_pose(w, none, &p, &err));
    assert_true(err.find("the world's start: ") == 0);
    // Neither: --start is needed.
    assert_true(w.parse(room, "t.world", &err));
    assert_false(start_pose(w, none, &p, &err));
    assert_true(err.find("--start") == 0);
}

// --version prints "houghloc-sim <version>" like every houghloc program, and --help
// lists it.
static void test_version(void **state)
{
    (void)state;
    assert_string_equal(version_line().c_str(), "houghloc-sim " HL_VERSION);
    assert_true(std::strlen(HL_VERSION) > 0);
    char *text = nullptr;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    print_usage(f);
    std::fclose(f);
    assert_non_null(std::strstr(text, "--version"));
    std::free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_numbers),
        cmocka_unit_test(test_options),
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_lockstep_option),
        cmocka_unit_test(test_start_pose),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
