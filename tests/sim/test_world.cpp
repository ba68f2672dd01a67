// test_world.cpp - ray casting, the world file parser (shapes, surfaces, layout
// directives), enclosure, the default lab, the corridor world, the tour.
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
                 "circle, position, tiles, open, orientation, tour, start)");
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
    // Surfaces and the layout directives.
    expect_error("segment 0 0 1 1 roguh\n",
                 "t.world:1: unknown surface 'roguh' (expected smooth, rough or thin)");
    expect_error("polygon 0 0 9 0 9 9 glass\n",
                 "t.world:1: unknown surface 'glass' (expected smooth, rough or thin)");
    expect_error("circle 0 0 5 rough thin\n", "t.world:1: more than one surface word");
    expect_error("segment 0 0 1 rough\n", "t.world:1: segment needs 4 numbers, got 3");
    expect_error("tiles 50\n", "t.world:1: tile size 50 outside 100..2000 mm");
    expect_error("tiles 2000.5\n", "t.world:1: tile size 2000.5 outside 100..2000 mm");
    expect_error("tiles\n", "t.world:1: tiles needs 1 number (the tile size in mm)");
    expect_error("tiles 600\ntiles 600\n", "t.world:2: tiles given twice");
    expect_error("open 0 0 1000\n", "t.world:1: open needs X0 Y0 X1 Y1");
    expect_error("open 0 0 -5 10\n", "t.world:1: open rectangle needs X0 < X1 and Y0 < Y1");
    expect_error("open 0 10 5 10\n", "t.world:1: open rectangle needs X0 < X1 and Y0 < Y1");
    expect_error("open 0 0 5000000 1\n", "t.world:1: coordinate 5000000 beyond +-4000000 mm");
    expect_error("open 0 0 x 1\n", "t.world:1: 'x' is not a finite number");
    expect_error("orientation 1\n", "t.world:1: orientation needs X Y");
    expect_error("orientation 1 2\norientation 1 2\n", "t.world:2: orientation given twice");
    expect_error("tour 1 2 3\n", "t.world:1: tour needs X Y");
    expect_error("tour 0 0\n\ntour 5 5\n", "t.world:3: tour given twice");
    expect_error("tour 0 -4000001\n", "t.world:1: coordinate -4000001 beyond +-4000000 mm");
    expect_error("start 1 2\n", "t.world:1: start needs X Y HEADING_DEG");
    expect_error("start 1 2 3 4\n", "t.world:1: start needs X Y HEADING_DEG");
    expect_error("start 1 2 x\n", "t.world:1: 'x' is not a finite number");
    expect_error("start 1 inf 0\n", "t.world:1: 'inf' is not a finite number");
    expect_error("start 4000001 0 0\n", "t.world:1: start coordinate beyond +-4000000 mm");
    expect_error("start 0 0 -361\n", "t.world:1: heading must be within +-360 degrees");
    expect_error("start 0 0 0\nsegment 0 0 1 1\nstart 5 5 90\n", "t.world:3: start given twice");
    {
        World w;
        std::string err;
        assert_false(w.parse("start 100 200 90\nfoo\n", "t.world", &err));
        assert_false(w.has_start);   // a failed load leaves no start behind
    }
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
    // Without directives: the defaults.
    assert_near(w.tile_mm, 609.6, 0.0);
    assert_true(w.open.empty());
    assert_false(w.has_orientation);
    assert_false(w.has_tour);
    assert_false(w.has_start);
}

static void test_parser_surfaces_and_layout(void **state)
{
    (void)state;
    World w;
    std::string err;
    assert_true(w.parse("segment 0 0 1000 0\n"                 // smooth by default
                        "segment 0 100 1000 100 rough\n"
                        "polygon 0 0 10 0 10 10 thin\n"
                        "box 0 0 10 10 smooth\n"
                        "rbox 0 0 10 10 45 rough\n"
                        "circle 5 5 2 thin\n"
                        "circle 50 50 20\n"
                        "tiles 600\n"
                        "open 0 0 3000 1200\n"
                        "open -600 -600 0 0\n"
                        "orientation 600 -1200.5\n"
                        "tour 1200 0\n"
                        "start 1500.5 -300 -90\n",
                        "t.world", &err));
    assert_int_equal(w.segments.size(), 1 + 1 + 3 + 4 + 4);
    assert_int_equal(static_cast<int>(w.segments[0].surface), static_cast<int>(Surface::Smooth));
    assert_int_equal(static_cast<int>(w.segments[1].surface), static_cast<int>(Surface::Rough));
    for (int i = 2; i < 5; i++)
        assert_int_equal(static_cast<int>(w.segments[i].surface), static_cast<int>(Surface::Thin));
    for (int i = 5; i < 9; i++)
        assert_int_equal(static_cast<int>(w.segments[i].surface), static_cast<int>(Surface::Smooth));
    for (int i = 9; i < 13; i++)
        assert_int_equal(static_cast<int>(w.segments[i].surface), static_cast<int>(Surface::Rough));
    assert_int_equal(static_cast<int>(w.circles[0].surface), static_cast<int>(Surface::Thin));
    assert_int_equal(static_cast<int>(w.circles[1].surface), static_cast<int>(Surface::Smooth));
    assert_near(w.tile_mm, 600.0, 0.0);
    assert_int_equal(w.open.size(), 2);
    assert_near(w.open[0].hi.x, 3000.0, 0.0);
    assert_near(w.open[1].lo.y, -600.0, 0.0);
    assert_true(w.has_orientation);
    assert_near(w.orientation_corner.y, -1200.5, 0.0);
    assert_true(w.has_tour);
    assert_near(w.tour_start.x, 1200.0, 0.0);
    assert_true(w.has_start);
    assert_near(w.start.x, 1500.5, 0.0);
    assert_near(w.start.y, -300.0, 0.0);
    assert_near(w.start.theta, -kPi / 2, 1e-12);
    // The ray reports the surface (and radius) of what it hit.
    Hit h;
    assert_true(w.cast({500, 500}, {0, -1}, 1e6, &h));
    assert_near(h.dist, 400.0, 1e-9);
    assert_int_equal(static_cast<int>(h.surface), static_cast<int>(Surface::Rough));
    assert_near(h.radius, 0.0, 0.0);
    assert_true(w.cast({50, 0}, {0, 1}, 1e6, &h));
    assert_int_equal(static_cast<int>(h.surface), static_cast<int>(Surface::Smooth));
    assert_near(h.radius, 20.0, 0.0);
}

static void test_enclosed(void **state)
{
    (void)state;
    World lab = World::lab();
    std::string err;
    for (const Position &p : lab.positions)
        assert_true(lab.enclosed(p.pose.pos(), &err));
    assert_true(lab.enclosed(lab.tour_start, &err));
    // A room with its east wall missing: the ray at 0 degrees escapes.
    World w;
    assert_true(w.parse("polygon 0 0 1000 0 1000 1000 0 1000\n", "t.world", &err));
    assert_true(w.enclosed({500, 500}, &err));
    w.segments.erase(w.segments.begin() + 1);  // (1000, 0) - (1000, 1000)
    assert_false(w.enclosed({500, 250.5}, &err));
    assert_string_equal(err.c_str(), "the world is not closed around (500.0, 250.5): a ray at 0 "
                                     "degrees meets nothing");
    // Outside the lab's L, in the notch: the rays toward the north-east meet nothing.
    assert_false(lab.enclosed({8000, 5000}, &err));
}

static void test_default_lab(void **state)
{
    (void)state;
    World w;
    std::string err;
    assert_true(w.parse(World::lab_text(), "lab.world", &err));
    assert_int_equal(w.positions.size(), 28);
    // The experiments' layout, as the data sets used it before it was declared.
    assert_near(w.tile_mm, kTileMm, 0.0);
    assert_true(w.has_orientation && w.has_tour);
    assert_near(w.orientation_corner.x, 8 * kTileMm, 1e-9);
    assert_near(w.orientation_corner.y, 0.0, 0.0);
    assert_near(w.tour_start.x, lab_tour_start().x, 1e-9);
    assert_near(w.tour_start.y, lab_tour_start().y, 1e-9);
    // houghloc-sim's default start: the open south-east leg (where make demo starts),
    // clear of every surface by far more than the robot's radius, closed in.
    assert_true(w.has_start);
    assert_near(w.start.x, 5400.0, 0.0);
    assert_near(w.start.y, 1500.0, 0.0);
    assert_near(w.start.theta, 0.0, 0.0);
    assert_true(w.clearance(w.start.pos()) > 1000.0);
    assert_true(w.enclosed(w.start.pos(), &err));
    // The open floor is the west part only, and holds enough clear tile intersections.
    int clear = 0;
    for (const Rect &r : w.open) {
        assert_true(r.hi.x <= 6036);
        for (int i = -2; i <= 12; i++)
            for (int j = -2; j <= 14; j++) {
                Vec2 p{i * kTileMm, j * kTileMm};
                if (p.x >= r.lo.x && p.x <= r.hi.x && p.y >= r.lo.y && p.y <= r.hi.y &&
                    w.clearance(p) >= 500.0)
                    clear++;
            }
    }
    assert_in_range(clear, 28, 200);
    // Surfaces: cardboard and books are rough, walls smooth.
    int rough = 0;
    for (const Segment &s : w.segments)
        rough += s.surface == Surface::Rough;
    assert_int_equal(rough, 4 * 9);  // 3 chairs, a bookshelf, 5 boxes
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

static void test_corridor_world(void **state)
{
    (void)state;
    World w;
    std::string err;
    assert_true(w.load("tools/sim/worlds/corridor.world", &err));
    assert_int_equal(w.positions.size(), 28);
    assert_near(w.tile_mm, 600.0, 0.0);
    assert_true(w.has_orientation && w.has_tour && w.open.size() >= 2);
    Vec2 lo, hi;
    assert_true(w.bounds(&lo, &hi));
    assert_in_range(static_cast<long>(hi.x - lo.x), 25000, 30000);  // a long corridor
    assert_true(w.enclosed(w.tour_start, &err));
    for (const Position &p : w.positions) {
        double i = p.pose.x / w.tile_mm, j = p.pose.y / w.tile_mm;
        assert_near(i, std::round(i), 1e-9);
        assert_near(j, std::round(j), 1e-9);
        assert_true(w.clearance(p.pose.pos()) >= 500.0);
        assert_true(w.enclosed(p.pose.pos(), &err));
    }
    // The orientation test's square and centre are clear; the tour is long enough.
    for (Vec2 d : {Vec2{0, 0}, Vec2{1500, 0}, Vec2{1500, 1500}, Vec2{0, 1500}, Vec2{750, 750}})
        assert_true(w.clearance(w.orientation_corner + d) >= 500.0);
    assert_true(tour_order(w, w.tour_start, w.tile_mm, kTourClearanceMm).size() >= 128);
    int kinds[3] = {0, 0, 0};
    for (const Segment &s : w.segments)
        kinds[static_cast<int>(s.surface)]++;
    for (const Circle &c : w.circles)
        kinds[static_cast<int>(c.surface)]++;
    assert_true(kinds[0] > 0 && kinds[1] > 0 && kinds[2] > 0);
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
        cmocka_unit_test(test_parser_surfaces_and_layout),
        cmocka_unit_test(test_enclosed),
        cmocka_unit_test(test_default_lab),
        cmocka_unit_test(test_corridor_world),
        cmocka_unit_test(test_tour),
    };
    return cmocka_run_group_tests_name("sim/world", tests, NULL, NULL);
}
