// test_layout.cpp - Table 1's positions drawn per seed, and the checks hl-sim-logs makes
// before it writes a data set (tools/sim/layout.cpp).
#include "test_support.hpp"

#include <set>
#include <utility>

#include "layout.hpp"

using namespace hlsim;

namespace {

World lab()
{
    return World::lab();
}

// Chebyshev distance in tiles from p to the nearest other position.
double nearest_other_tiles(const std::vector<Position> &ps, std::size_t i, double tile)
{
    double best = 1e300;
    for (std::size_t j = 0; j < ps.size(); j++)
        if (j != i)
            best = std::min(best, std::max(std::fabs(ps[i].pose.x - ps[j].pose.x),
                                           std::fabs(ps[i].pose.y - ps[j].pose.y)) / tile);
    return best;
}

}  // namespace

// 28 distinct positions on tile intersections of the open floor, clear of every surface,
// facing a tile direction, named P01..P28; packed (each next to another one); the same
// for the same seed and a different layout for another.
static void test_draw_positions(void **state)
{
    (void)state;
    World w = lab();
    std::vector<Position> a, b, c;
    std::string err;
    Rng r1(7), r2(7), r3(8);
    assert_true(draw_positions(w, 28, r1, &a, &err));
    assert_true(draw_positions(w, 28, r2, &b, &err));
    assert_true(draw_positions(w, 28, r3, &c, &err));
    assert_int_equal(a.size(), 28);
    std::set<std::pair<long, long>> seen;
    bool same_as_c = true;
    for (std::size_t i = 0; i < a.size(); i++) {
        const Pose &p = a[i].pose;
        double ti = p.x / w.tile_mm, tj = p.y / w.tile_mm;
        assert_near(ti, std::round(ti), 1e-9);
        assert_near(tj, std::round(tj), 1e-9);
        assert_true(w.clearance(p.pos()) >= kPositionClearanceMm);
        bool in_open = false;
        for (const Rect &r : w.open)
            in_open = in_open || (p.x >= r.lo.x && p.x <= r.hi.x && p.y >= r.lo.y && p.y <= r.hi.y);
        assert_true(in_open);
        double q = p.theta / (kPi / 2.0);
        assert_near(q, std::round(q), 1e-9);
        assert_true(seen.insert({std::lround(ti), std::lround(tj)}).second);
        char name[32];
        std::snprintf(name, sizeof name, "P%02d", static_cast<int>(i + 1));
        assert_string_equal(a[i].name.c_str(), name);
        assert_true(nearest_other_tiles(a, i, w.tile_mm) <= 2.0 + 1e-9);
        assert_near(a[i].pose.x, b[i].pose.x, 0);
        assert_near(a[i].pose.y, b[i].pose.y, 0);
        assert_near(a[i].pose.theta, b[i].pose.theta, 0);
        same_as_c = same_as_c && a[i].pose.x == c[i].pose.x && a[i].pose.y == c[i].pose.y;
    }
    assert_false(same_as_c);
    assert_true(check_layout(w, a, &err));
    // Grown towards the first: the second is one of its 8 neighbours.
    assert_true(std::max(std::fabs(a[1].pose.x - a[0].pose.x), std::fabs(a[1].pose.y - a[0].pose.y)) <=
                w.tile_mm + 1e-6);
}

// Worlds that cannot hold the experiments are refused with one line saying why.
static void test_refusals(void **state)
{
    (void)state;
    std::string err;
    std::vector<Position> ps;
    Rng rng(1);
    World bare;
    assert_true(bare.parse("polygon 0 0 10000 0 10000 10000 0 10000\n", "bare", &err));
    assert_false(draw_positions(bare, 28, rng, &ps, &err));
    assert_string_equal(err.c_str(), "the world declares no open floor ('open' lines) to draw positions on");

    World small;
    assert_true(small.parse("polygon 0 0 3000 0 3000 3000 0 3000\nopen 0 0 3000 3000\n", "small", &err));
    assert_false(draw_positions(small, 28, rng, &ps, &err));
    assert_true(err.find("fewer than the 28 positions") != std::string::npos);

    // An unclosed room: three walls of four. The layout check names the point.
    World open_room;
    assert_true(open_room.parse("segment 0 0 10000 0\nsegment 10000 0 10000 10000\n"
                                "segment 0 10000 10000 10000\nopen 1000 1000 9000 9000\n"
                                "orientation 3000 3000\ntour 5000 5000\n", "open", &err));
    assert_true(draw_positions(open_room, 28, rng, &ps, &err));
    assert_false(check_layout(open_room, ps, &err));
    assert_true(err.find("not closed") != std::string::npos);

    // Closed, but no orientation square or tour start declared.
    World closed;
    assert_true(closed.parse("polygon 0 0 10000 0 10000 10000 0 10000\nopen 1000 1000 9000 9000\n",
                             "closed", &err));
    assert_true(draw_positions(closed, 28, rng, &ps, &err));
    assert_false(check_layout(closed, ps, &err));
    assert_string_equal(err.c_str(), "the world declares no orientation square ('orientation X Y')");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_draw_positions),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests_name("sim/layout", tests, NULL, NULL);
}
