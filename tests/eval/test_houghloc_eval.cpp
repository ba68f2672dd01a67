// test_houghloc_eval.cpp - houghloc-eval's metrics (tools/eval/metrics.cpp) on synthetic
// trajectories whose answer is known: by construction, by hand, or from evo itself.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics.hpp"

// cmocka last: its macros clash with standard headers included after it; its header has
// no extern "C" of its own.
#include <cstdarg>
#include <csetjmp>
extern "C" {
#include <cmocka.h>
}

using hleval::IdPairs;
using hleval::Pose2;
using hleval::Trajectory;

namespace {

constexpr double kPi = 3.14159265358979323846;

void assert_near(double got, double want, double tol)
{
    if (!(std::fabs(got - want) <= tol))
        fail_msg("got %.12f, want %.12f (+- %g)", got, want, tol);
}

void assert_pair(const std::pair<std::size_t, std::size_t> &p, std::size_t i, std::size_t j)
{
    if (p.first != i || p.second != j)
        fail_msg("pair (%zu, %zu), want (%zu, %zu)", p.first, p.second, i, j);
}

// A loop of @p n poses on a circle of radius @p r around (cx, cy), heading along it.
Trajectory circle(std::size_t n, double r, double cx, double cy)
{
    Trajectory t;
    for (std::size_t i = 0; i < n; i++) {
        double a = 2 * kPi * static_cast<double>(i) / static_cast<double>(n);
        t.push_back({ static_cast<double>(i), cx + r * std::cos(a), cy + r * std::sin(a),
                      std::remainder(a + kPi / 2, 2 * kPi) });
    }
    return t;
}

// Straight along +x, heading 0, at the given positions.
Trajectory line(const std::vector<double> &xs)
{
    Trajectory t;
    for (std::size_t i = 0; i < xs.size(); i++)
        t.push_back({ static_cast<double>(i), xs[i], 0, 0 });
    return t;
}

// Moves a trajectory rigidly: turn by @p angle about the origin, then shift.
Trajectory moved(const Trajectory &in, double angle, double dx, double dy)
{
    Trajectory out = in;
    double c = std::cos(angle), s = std::sin(angle);
    for (Pose2 &p : out) {
        double x = p.x, y = p.y;
        p.x = c * x - s * y + dx;
        p.y = s * x + c * y + dy;
        p.theta = std::remainder(p.theta + angle, 2 * kPi);
    }
    return out;
}

void test_identical_is_zero(void **state)
{
    (void)state;
    Trajectory gt = circle(50, 3.0, 1.0, -2.0);
    hleval::Scores s = hleval::score(gt, gt);
    assert_int_equal(s.ate.n, 50);
    assert_near(s.ate.rmse, 0, 1e-12);
    assert_near(s.ate.max, 0, 1e-12);
    assert_near(s.alignment.angle, 0, 1e-12);
    assert_true(s.rpe.n > 0);
    assert_near(s.rpe.rmse, 0, 1e-12);
    assert_near(s.rpe.mean, 0, 1e-12);
}

// The alignment takes out any rigid motion of the estimate, and RPE never sees it.
void test_rigid_copy_aligns_to_zero(void **state)
{
    (void)state;
    Trajectory gt = circle(40, 2.5, 0, 0);
    gt.resize(30);  // an open arc, off the origin after the move
    Trajectory est = moved(gt, 0.7, 5.0, -3.0);
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.ate.rmse, 0, 1e-9);
    assert_near(s.ate.max, 0, 1e-9);
    assert_near(s.rpe.rmse, 0, 1e-9);
    // The alignment is the inverse motion.
    assert_near(s.alignment.angle, -0.7, 1e-9);
    Trajectory back = hleval::transformed(s.alignment, est);
    assert_near(back[7].x, gt[7].x, 1e-9);
    assert_near(back[7].y, gt[7].y, 1e-9);
    assert_near(back[7].theta, gt[7].theta, 1e-9);
    // Without the alignment the error is there.
    assert_true(hleval::stats_of(hleval::position_errors(gt, est)).rmse > 1.0);
}

// Half the poses shifted by d. The two halves are chosen point-symmetric about the
// circle's centre, so both have the centroid of the whole: the best rigid alignment is
// then no turn and a shift by -d/2, leaving |d|/2 on every pose. Without alignment the
// RMSE is |d| / sqrt(2).
void test_offset_on_half_the_poses(void **state)
{
    (void)state;
    Trajectory gt = circle(40, 2.0, 3.0, 1.0);
    Trajectory est = gt;
    for (std::size_t i = 0; i < est.size(); i++) {
        if (i < 10 || (i >= 20 && i < 30)) {
            est[i].x += 0.3;
            est[i].y += 0.4;
        }
    }
    hleval::Stats raw = hleval::stats_of(hleval::position_errors(gt, est));
    assert_near(raw.rmse, 0.5 / std::sqrt(2.0), 1e-12);
    assert_near(raw.max, 0.5, 1e-12);
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.alignment.angle, 0, 1e-12);
    assert_near(s.alignment.tx, -0.15, 1e-12);
    assert_near(s.alignment.ty, -0.2, 1e-12);
    assert_near(s.ate.rmse, 0.25, 1e-12);
    assert_near(s.ate.mean, 0.25, 1e-12);
    assert_near(s.ate.max, 0.25, 1e-12);
}

// 101 poses along +x, @p step metres apart.
Trajectory steps_along_x(double step)
{
    std::vector<double> xs;
    for (int i = 0; i <= 100; i++)
        xs.push_back(step * i);
    return line(xs);
}

// Straight line, 0.1 m steps in truth, the estimate 5 % long: pairs close every 10
// estimated steps (10 x 0.105 >= 1 > 9 x 0.105), each with 1.05 m estimated against
// 1.00 m true, so every RPE is 0.05 m (5 cm per metre).
void test_rpe_straight_line_per_metre_error(void **state)
{
    (void)state;
    Trajectory gt = steps_along_x(0.1), est = steps_along_x(0.105);
    IdPairs pairs = hleval::pairs_by_path(est, 1.0);
    assert_int_equal(pairs.size(), 10);
    for (std::size_t k = 0; k < pairs.size(); k++) {
        assert_int_equal(pairs[k].first, 10 * k);
        assert_int_equal(pairs[k].second, 10 * k + 10);
    }
    hleval::Stats rpe = hleval::stats_of(hleval::rpe_translation_errors(gt, est, pairs));
    assert_near(rpe.rmse, 0.05, 1e-12);
    assert_near(rpe.mean, 0.05, 1e-12);
    // score() pairs on the (aligned) estimate, as evo does, and gets the same.
    hleval::Scores s = hleval::score(gt, est);
    assert_int_equal(s.rpe.n, 10);
    assert_near(s.rpe.rmse, 0.05, 1e-9);
}

// The RPE's split: along a straight line the 5 % long estimate errs 0.05 m a metre along
// the path and none across it; the same run turned 90 degrees (the estimate too) splits
// the same way, and an estimate 0.02 m to the left of every true step errs across only.
void test_rpe_split_along_and_across(void **state)
{
    (void)state;
    Trajectory gt = steps_along_x(0.1), est = steps_along_x(0.105);
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.rpe_along.rmse, 0.05, 1e-9);
    assert_near(s.rpe_across.rmse, 0.0, 1e-9);
    Trajectory gt_up = gt, est_up = est;
    for (std::size_t i = 0; i < gt.size(); i++) {
        gt_up[i] = { gt[i].t, 0, gt[i].x, kPi / 2 };
        est_up[i] = { est[i].t, 0, est[i].x, kPi / 2 };
    }
    IdPairs pairs = hleval::pairs_by_path(est_up, 1.0);
    hleval::SplitErrors e = hleval::rpe_translation_split(gt_up, est_up, pairs);
    assert_int_equal(e.along.size(), 10);
    for (std::size_t k = 0; k < e.along.size(); k++) {
        assert_near(e.along[k], 0.05, 1e-9);
        assert_near(e.across[k], 0.0, 1e-9);
    }
    Trajectory left = gt;   /* each step's end 0.02 m to the left of where it started */
    for (std::size_t i = 0; i < left.size(); i++)
        left[i].y = 0.02 * (double)(i / 10);
    IdPairs every = { { 0, 10 }, { 10, 20 } };
    e = hleval::rpe_translation_split(gt, left, every);
    assert_near(e.along[0], 0.0, 1e-12);
    assert_near(e.across[0], 0.02, 1e-9);
    assert_near(e.across[1], 0.02, 1e-9);
}

// The heading counts: the same positions with every heading 10 degrees off see each
// 1 m step 10 degrees turned, an error of 2 sin(5 deg) m; the positions' ATE is 0.
void test_rpe_heading_error(void **state)
{
    (void)state;
    std::vector<double> xs;
    for (int i = 0; i <= 20; i++)
        xs.push_back(0.5 * i);
    Trajectory gt = line(xs), est = gt;
    for (Pose2 &p : est)
        p.theta += 10 * kPi / 180;
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.ate.rmse, 0, 1e-12);
    assert_int_equal(s.rpe.n, 10);
    assert_near(s.rpe.mean, 2 * std::sin(5 * kPi / 180), 1e-12);
}

// Pairing by distance travelled, by hand, as evo's filter_pairs_by_path walks.
void test_pairs_irregular_spacing(void **state)
{
    (void)state;
    // Steps: 0.3 0.2 0.7 | 0.05 0.65 0.4 | 0.1 1.1 | 0.1 (tail, no pair).
    Trajectory t = line({ 0, 0.3, 0.5, 1.2, 1.25, 1.9, 2.3, 2.4, 3.5, 3.6 });
    IdPairs p = hleval::pairs_by_path(t, 1.0);
    assert_int_equal(p.size(), 3);
    assert_pair(p[0], 0, 3);
    assert_pair(p[1], 3, 6);
    assert_pair(p[2], 6, 8);

    // The path, not the displacement: 0.6 m east then 0.6 m north is 1.2 m travelled
    // (0.85 m apart), so a pair closes at the corner's next pose.
    Trajectory corner = { { 0, 0, 0, 0 }, { 1, 0.6, 0, 0 }, { 2, 0.6, 0.6, 0 } };
    p = hleval::pairs_by_path(corner, 1.0);
    assert_int_equal(p.size(), 1);
    assert_pair(p[0], 0, 2);

    // Exactly delta closes a segment (>=); standing still adds nothing.
    Trajectory exact = line({ 0, 0.5, 0.5, 1.0, 1.25 });
    p = hleval::pairs_by_path(exact, 1.0);
    assert_int_equal(p.size(), 1);
    assert_pair(p[0], 0, 3);

    // Another delta, and nothing to pair.
    p = hleval::pairs_by_path(t, 2.0);
    assert_int_equal(p.size(), 1);
    assert_pair(p[0], 0, 6);
    assert_int_equal(hleval::pairs_by_path(line({ 0, 0.4, 0.8 }), 1.0).size(), 0);
    assert_int_equal(hleval::pairs_by_path(Trajectory{}, 1.0).size(), 0);
}

// A spiral and a perturbed, moved copy; the reference figures are evo 1.38.1's
// (evo_ape tum gt est -a; evo_rpe tum gt est -r trans_part --delta 1 --delta_unit m -a)
// on these trajectories written to TUM files (positions to 1e-9 m, quaternions 1e-12).
void test_against_evo(void **state)
{
    (void)state;
    Trajectory gt, est;
    for (int i = 0; i < 60; i++) {
        double a = 0.15 * i, r = 3 + 0.02 * i;
        Pose2 g{ 100 + 0.5 * i, r * std::cos(a), r * std::sin(a),
                 std::remainder(a + kPi / 2, 2 * kPi) };
        gt.push_back(g);
        Pose2 e = g;
        e.x += 0.05 * std::sin(1.7 * i);
        e.y += 0.04 * std::cos(2.3 * i);
        e.theta += 0.03 * std::sin(0.9 * i);
        est.push_back(e);
    }
    est = moved(est, 0.4, 2.0, -1.0);
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.ate.rmse, 0.045079206, 2e-9);
    assert_near(s.ate.mean, 0.042959373, 2e-9);
    assert_near(s.ate.max, 0.062487456, 2e-9);
    assert_int_equal(s.rpe.n, 25);
    assert_near(s.rpe.rmse, 0.079950740, 2e-9);
    assert_near(s.rpe.mean, 0.073864528, 2e-9);
    IdPairs p = hleval::pairs_by_path(hleval::transformed(s.alignment, est), 1.0);
    assert_pair(p[3], 9, 12);
    assert_pair(p[4], 12, 14);
}

void test_single_pose_and_stats(void **state)
{
    (void)state;
    Trajectory gt = { { 0, 1, 2, 0 } }, est = { { 0, 4, 6, 1 } };
    hleval::Scores s = hleval::score(gt, est);
    assert_near(s.ate.rmse, 0, 1e-12);  // one pose: a pure translation aligns it
    assert_near(s.alignment.tx, -3, 1e-12);
    assert_near(s.alignment.ty, -4, 1e-12);
    assert_int_equal(s.rpe.n, 0);
    assert_true(std::isnan(s.rpe.rmse) && std::isnan(s.rpe.mean));

    hleval::Stats st = hleval::stats_of({ 3, 4, 0, 5 });
    assert_int_equal(st.n, 4);
    assert_near(st.rmse, std::sqrt(50.0 / 4), 1e-12);
    assert_near(st.mean, 3, 1e-12);
    assert_near(st.max, 5, 1e-12);
    assert_true(std::isnan(hleval::stats_of({}).rmse));
}

void test_bad_arguments(void **state)
{
    (void)state;
    Trajectory a = circle(5, 1, 0, 0), b = circle(6, 1, 0, 0);
    int thrown = 0;
    try {
        hleval::score(a, b);
    } catch (const std::invalid_argument &) {
        thrown++;
    }
    try {
        hleval::score(Trajectory{}, Trajectory{});
    } catch (const std::invalid_argument &) {
        thrown++;
    }
    try {
        hleval::pairs_by_path(a, 0.0);
    } catch (const std::invalid_argument &) {
        thrown++;
    }
    try {
        hleval::rpe_translation_errors(a, a, { { 0, 5 } });
    } catch (const std::invalid_argument &) {
        thrown++;
    }
    assert_int_equal(thrown, 4);
}

void test_tum_line(void **state)
{
    (void)state;
    assert_string_equal(hleval::tum_line({ 12.5, 1, -2, kPi / 2 }).c_str(),
                        "12.500000 1.000000 -2.000000 0 0 0 0.707106781 0.707106781");
    assert_string_equal(hleval::tum_line({ 1000000002.4375, 0.614, 0, -kPi / 2 }).c_str(),
                        "1000000002.437500 0.614000 0.000000 0 0 0 -0.707106781 0.707106781");
}

}  // namespace

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identical_is_zero),
        cmocka_unit_test(test_rigid_copy_aligns_to_zero),
        cmocka_unit_test(test_offset_on_half_the_poses),
        cmocka_unit_test(test_rpe_straight_line_per_metre_error),
        cmocka_unit_test(test_rpe_heading_error),
        cmocka_unit_test(test_rpe_split_along_and_across),
        cmocka_unit_test(test_pairs_irregular_spacing),
        cmocka_unit_test(test_against_evo),
        cmocka_unit_test(test_single_pose_and_stats),
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_tum_line),
    };
    return cmocka_run_group_tests_name("eval/houghloc_eval", tests, nullptr, nullptr);
}
