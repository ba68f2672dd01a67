// test_calib_fit.cpp - the calibration fit and its input parser.
#include <sstream>

#include "calib_fit.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

static std::vector<CalibPair> line_pairs(double gain, double offset)
{
    std::vector<CalibPair> v;
    for (int raw = 900; raw <= 3800; raw += 145)
        v.push_back({gain * raw + offset, static_cast<double>(raw), 0});
    return v;
}

static void test_fit_recovers_noiseless_line(void **state)
{
    (void)state;
    CalibFit f;
    std::string err;
    assert_true(calib_fit(line_pairs(1.07, -35.0), 200, 16384, 100.0, &f, &err));
    assert_near(f.gain, 1.07, 1.07 * 0.001);  // within 0.1%
    assert_near(f.offset, -35.0, 1.0);
    assert_near(f.rms_mm, 0.0, 1e-6);
    assert_int_equal(f.gain_q16(), 70124);
    assert_int_equal(f.offset_mm(), -35);
    assert_int_equal(f.used, 21);
    assert_true(calib_fit(line_pairs(0.5, 120.0), 200, 16384, 100.0, &f, &err));
    assert_near(f.gain, 0.5, 0.5 * 0.001);
    assert_near(f.offset, 120.0, 1.0);
}

static void test_fit_drops_garbage_and_outliers(void **state)
{
    (void)state;
    std::vector<CalibPair> v = line_pairs(1.07, -35.0);
    v.push_back({2000, 50, 0});     // cable echo
    v.push_back({3000, 16384, 0});  // no echo
    v.push_back({1500, 3000, 0});   // multipath-like: far off the line
    CalibFit f;
    std::string err;
    assert_true(calib_fit(v, 200, 16384, 100.0, &f, &err));
    assert_int_equal(f.garbage, 2);
    assert_int_equal(f.outliers, 1);
    assert_int_equal(f.used, 21);
    assert_near(f.gain, 1.07, 1e-9);
    assert_near(f.offset, -35.0, 1e-6);
}

static void test_fit_rejects_degenerate(void **state)
{
    (void)state;
    std::vector<CalibPair> v{{1000, 1000, 1}, {1100, 1000, 2}};
    CalibFit f;
    std::string err;
    assert_false(calib_fit(v, 200, 16384, 100.0, &f, &err));
    assert_string_equal(err.c_str(), "need at least two distinct raw values (2 usable pairs)");
    assert_false(calib_fit({}, 200, 16384, 100.0, &f, &err));
}

static void test_fit_simulated_procedure(void **state)
{
    (void)state;
    SonarParams sp;
    Rng rng(1);
    std::vector<CalibPair> v = calib_simulate(sp, rng, 1000, 4000, 250, 8);
    assert_int_equal(v.size(), 13 * 8);
    CalibFit f;
    std::string err;
    assert_true(calib_fit(v, sp.calib.min_raw, sp.calib.sentinel_raw, 100.0, &f, &err));
    assert_near(f.gain, 1.07, 1.07 * 0.005);
    assert_near(f.offset, -35.0, 20.0);
    assert_true(f.rms_mm < 50.0);
}

static void expect_read_error(const char *text, const char *message)
{
    std::istringstream in(text);
    std::vector<CalibPair> v;
    std::string err;
    assert_false(calib_read_pairs(in, "in", &v, &err));
    assert_string_equal(err.c_str(), message);
    assert_true(v.empty());
}

static void test_read_pairs(void **state)
{
    (void)state;
    std::istringstream in("# distance raw\n\n1000 967   # first\n 4000\t3771\n");
    std::vector<CalibPair> v;
    std::string err;
    assert_true(calib_read_pairs(in, "in", &v, &err));
    assert_int_equal(v.size(), 2);
    assert_near(v[1].mm, 4000.0, 0.0);
    assert_near(v[1].raw, 3771.0, 0.0);
    assert_int_equal(v[1].line, 4);
    expect_read_error("1000 967\n1000 abc\n", "in:2: 'abc' is not a finite number");
    expect_read_error("1000\n", "in:1: expected 'distance_mm raw', got 1 fields");
    expect_read_error("1 2 3\n", "in:1: expected 'distance_mm raw', got 3 fields");
    expect_read_error("-5 100\n", "in:1: distance -5 outside (0, 32767] mm");
    expect_read_error("1000 70000\n", "in:1: raw reading 70000 is not an integer 0..65535");
    expect_read_error("1000 1.5\n", "in:1: raw reading 1.5 is not an integer 0..65535");
    expect_read_error("inf 10\n", "in:1: 'inf' is not a finite number");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_recovers_noiseless_line),
        cmocka_unit_test(test_fit_drops_garbage_and_outliers),
        cmocka_unit_test(test_fit_rejects_degenerate),
        cmocka_unit_test(test_fit_simulated_procedure),
        cmocka_unit_test(test_read_pairs),
    };
    return cmocka_run_group_tests_name("sim/calib_fit", tests, NULL, NULL);
}
