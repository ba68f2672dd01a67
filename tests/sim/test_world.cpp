// test_world.cpp - ray casting, the world file parser, the default lab, the tour.
#include <cmath>
#include <cstring>
#include <string>

#include "tour.hpp"
#include "world.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

static void test_cast_segment_exact(void **state)
{
    (void)state;
    World w;
    w.segments.push_back({{1000, -500}, {1000, 500}});
    Hit h;
    assert_true(w.cast({0, 0}, {1, 0}, 1e6, &h));
    assert_near(h.dist, 1000.0, 1e-9);
    assert_near(h.point.x, 1000.0, 1e-9);
    assert_near(h.point.y, 0.0, 1e-9);
    assert_near(h.normal.x, -1.0, 1e-12);  // faces back at the sensor
    assert_near(h.normal.y, 0.0, 1e-12);
    // Oblique ray through (1000, 400): distance sqrt(1000^2 + 400^2).
    Vec2 d = Vec2{1000, 400} * (1.0 / std::hypot(1000.0, 400.0));
    assert_true(w.cast({0, 0}, d, 1e6, &h));
    assert_near(h.dist, std::hypot(1000.0, 400.0), 1e-9);
    // From the other side the normal flips toward the new origin.
    assert_true(w.cast({3000, 0}, {-1, 0}, 1e6, &h));
    assert_near(h.dist, 2000.0, 1e-9);
    assert_near(h.normal.x, 1.0, 1e-12);
    // Past the segment's end, or beyond max_dist: no hit.
    Vec2 miss = Vec2{1000, 600} * (1.0 / std::hypot(1000.0, 600.0));
    assert_false(w.cast({0, 0}, miss, 1e6, &h));
    assert_false(w.cast({0, 0}, {1, 0}, 999.0, &h));
}

static void test_cast_circle_exact(void **state)
{
    (void)state;
    World w;
    w.circles.push_back({{2000, 0}, 300});
    Hit h;
    assert_true(w.cast({0, 0}, {1, 0}, 1e6, &h));
    assert_near(h.dist, 1700.0, 1e-9);
    assert_near(h.normal.x, -1.0, 1e-12);
    // Off-centre by 100 mm: 2000 - sqrt(300^2 - 100^2).
    assert_true(w.cast({0, 100}, {1, 0}, 1e6, &h));
    assert_near(h.dist, 2000.0 - std::sqrt(80000.0), 1e-9);
    assert_near(h.normal.x, -std::sqrt(80000.0) / 300.0, 1e-12);
    assert_near(h.normal.y, 100.0 / 300.0, 1e-12);
    assert_false(w.cast({0, 301}, {1, 0}, 1e6, &h));
}

static void test_cast_nearest_of_many(void **state)
{
    (void)state;
    World w;
    w.segments.push_back({{3000, -1000}, {3000, 1000}});
    w.circles.push_back({{1500, 0}, 100});
    w.add_box({800, 0}, 200, 200, 0.0);  // faces at x = 700 .. 900
    Hit h;
    assert_true(w.cast({0, 0}, {1, 0}, 1e6, &h));
    assert_near(h.dist, 700.0, 1e-9);
    assert_near(w.clearance({0, 0}), 700.0, 1e-9);
}

static void expect_error(const char *text, const char *message)
{
    World w;
    std::string err;
    assert_false(w.parse(text, "t.world", &err));
    assert_string_equal(err.c_str(), message);
    assert_true(w.segments.empty() && w.circles.empty() && w.positions.empty());
}

static void test_parser_rejects(void **state)
{
    (void)state;
    expect_error("segment 0 0 1\n", "t.world:1: segment needs 4 numbers, got 3");
    expect_error("# fine\ncircle 0 0 abc\n", "t.world:2: 'abc' is not a finite number");
    expect_error("segment 0 0 nan 1\n", "t.world:1: 'nan' is not a finite number");
    expect_error("segment 0 0 1e400 1\n", "t.world:1: '1e400' is not a finite number");
    expect_error("\n\nfoo 1 2\n",
                 "t.world:3: unknown keyword 'foo' (expected segment, polygon, box, rbox, "
                 "circle, position)");
    expect_error("segment 0 0 5000000 0\n", "t.world:1: coordinate 5000000 beyond +-4000000 mm");
    expect_error("circle 0 0 0\n", "t.world:1: circle radius must be at least 1 mm");
    expect_error("segment 5 5 5 5.5\n", "t.world:1: segment shorter than 1 mm");
    expect_error("box 0 0 10 0\n", "t.world:1: box sides must be at least 1 mm");
    expect_error("rbox 0 0 10 10 400\n", "t.world:1: rbox angle must be within +-360 degrees");
    expect_error("polygon 0 0 1000 0\n", "t.world:1: polygon needs at least 3 x y pairs, got 4 numbers");
    expect_error("position A 0 0\n", "t.world:1: position needs NAME x y heading_deg");
    expect_error("position A 0 0 0\nposition A 1 1 0\n", "t.world:2: duplicate position name 'A'");
    expect_error("position A/B 0 0 0\n", "t.world:1: position name 'A/B' must be 1-32 of A-Z a-z 0-9 _ -");
    expect_error("position A 0 -4000001 0\n", "t.world:1: position coordinate beyond +-4000000 mm");
    expect_error("position A 0 0 361\n", "t.world:1: heading must be within +-360 degrees");
    std::string longline(1001, ' ');
    expect_error(("segment 0 0 1 1\n" + longline + "\n").c_str(),
                 "t.world:2: line longer than 1000 characters");
}

static void test_parser_accepts(void **state)
{
    (void)state;
    World w;
    std::string err;
    assert_true(w.parse("# a room\n"
                        "polygon 0 0 1000 0 1000 1000   # a triangle\n"
                        "segment 0 0 -100 0\n"
                        "box 10 10 20 30\n"
                        "rbox 0 0 100 50 45\n"
                        "circle -3999999 0 1\n"
                        "position home 500 100 90\n",
                        "t.world", &err));
    assert_int_equal(w.segments.size(), 3 + 1 + 4 + 4);
    assert_int_equal(w.circles.size(), 1);
    assert_int_equal(w.positions.size(), 1);
    assert_string_equal(w.positions[0].name.c_str(), "home");
    assert_near(w.positions[0].pose.theta, kPi / 2, 1e-12);
    assert_non_null(w.find("home"));
    assert_null(w.find("away"));
}

static void test_default_lab(void **state)
{
    (void)state;
    World w;
    std::string err;
    assert_true(w.parse(World::lab_text(), "lab.world", &err));
    assert_int_equal(w.positions.size(), 28);
    Vec2 lo, hi;
    assert_true(w.bounds(&lo, &hi));
    assert_in_range(static_cast<long>(hi.x - lo.x), 9500, 11500);  // about 10 m x 8 m
    assert_in_range(static_cast<long>(hi.y - lo.y), 7500, 9000);
    int in_leg = 0;
    for (const Position &p : w.positions) {
        // Tile intersections, clear of obstacles by at least half a metre.
        double i = p.pose.x / kTileMm, j = p.pose.y / kTileMm;
        assert_near(i, std::round(i), 1e-3);
        assert_near(j, std::round(j), 1e-3);
        assert_true(w.clearance(p.pose.pos()) >= 500.0);
        if (p.pose.x > 6036 && p.pose.y < 2990)
            in_leg++;
    }
    assert_in_range(in_leg, 4, 10);
    // The sparse leg has few objects: the L's corner at (6036, 2990) bounds it.
    int leg_circles = 0;
    for (const Circle &c : w.circles)
        leg_circles += c.c.x > 6036 && c.c.y < 2990;
    assert_int_equal(leg_circles, 0);
    // An L: a point outside the notch is not inside the room, so a ray from the
    // north-east notch toward the room hits the room's outer wall first.
    Hit h;
    assert_true(w.cast({8000, 5000}, {0, -1}, 1e6, &h));
    assert_near(h.dist, 5000.0 - 2990.0, 1e-6);
}

static void test_tour(void **state)
{
    (void)state;
    World w = World::lab();
    std::vector<TourStop> t = tour_order(w, lab_tour_start(), kTileMm, kTourClearanceMm);
    assert_true(t.size() >= 100);
    assert_near(t[0].at.x, lab_tour_start().x, 1e-9);
    Vec2 prev = t[0].at;
    std::size_t leg_first = 0;
    for (std::size_t k = 1; k < t.size(); k++) {
        for (Vec2 v : t[k].via) {
            assert_near((v - prev).norm(), kTileMm, 1e-6);
            prev = v;
        }
        assert_near((t[k].at - prev).norm(), kTileMm, 1e-6);  // 0.61 m hops
        assert_true(w.clearance(t[k].at) >= kTourClearanceMm);
        prev = t[k].at;
        if (leg_first == 0 && t[k].at.x > 6036 && t[k].at.y < 2990)
            leg_first = k;
    }
    // It grows outward from the dense corner: the sparse leg comes late.
    assert_true(leg_first > t.size() / 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cast_segment_exact),
        cmocka_unit_test(test_cast_circle_exact),
        cmocka_unit_test(test_cast_nearest_of_many),
        cmocka_unit_test(test_parser_rejects),
        cmocka_unit_test(test_parser_accepts),
        cmocka_unit_test(test_default_lab),
        cmocka_unit_test(test_tour),
    };
    return cmocka_run_group_tests_name("sim/world", tests, NULL, NULL);
}
