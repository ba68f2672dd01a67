// test_render.cpp - the figure renderer: layout arithmetic, pixels where things are drawn,
// degenerate input and error reporting. Pictures are read back with cairo.
#include <cairo.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "render.hpp"

// cmocka last: its macros clash with standard headers included after it; its header has
// no extern "C" of its own.
#include <cstdarg>
#include <cstddef>
#include <csetjmp>
extern "C" {
#include <cmocka.h>
}

using hlfig::Frame;
using hlfig::Layout;
using hlfig::Style;

namespace {

std::string g_dir;  // scratch directory, removed at the end

std::string out_path(const char *name)
{
    return g_dir + "/" + name;
}

// A PNG read back into memory; width 0 if it could not be read.
struct Png {
    int width = 0, height = 0;
    std::vector<uint32_t> px;  // 0x??RRGGBB, row-major
    explicit Png(const std::string &path)
    {
        cairo_surface_t *s = cairo_image_surface_create_from_png(path.c_str());
        if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
            width = cairo_image_surface_get_width(s);
            height = cairo_image_surface_get_height(s);
            int stride = cairo_image_surface_get_stride(s);
            const unsigned char *data = cairo_image_surface_get_data(s);
            px.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
            for (int y = 0; y < height; y++)
                std::memcpy(&px[static_cast<size_t>(y) * static_cast<size_t>(width)],
                            data + static_cast<size_t>(y) * static_cast<size_t>(stride),
                            static_cast<size_t>(width) * 4);
        }
        cairo_surface_destroy(s);
    }
    // Mean of the three channels at a pixel, 0 (black) .. 255 (white).
    int level(int x, int y) const
    {
        uint32_t p = px[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
        return static_cast<int>(((p >> 16) & 255) + ((p >> 8) & 255) + (p & 255)) / 3;
    }
    // Darkest level in the (2r+1)^2 block around a pixel: antialiased lines spread.
    int darkest(int x, int y, int r = 1) const
    {
        int m = 255;
        for (int dy = -r; dy <= r; dy++)
            for (int dx = -r; dx <= r; dx++)
                m = std::min(m, level(x + dx, y + dy));
        return m;
    }
    // The pixel under world point (x, y) mm.
    int at(const Layout &L, double x, double y) const
    {
        return level(static_cast<int>(L.px(x)), static_cast<int>(L.py(y)));
    }
    int darkest_at(const Layout &L, double x, double y) const
    {
        return darkest(static_cast<int>(L.px(x)), static_cast<int>(L.py(y)));
    }
};

hl_vector_t vec(int x, int y, double normal_deg, int range)
{
    hl_vector_t v{};
    v.x_mm = x;
    v.y_mm = y;
    v.normal = hl_bam_from_deg(normal_deg);
    v.range_mm = static_cast<uint16_t>(range);
    return v;
}

Style no_grid()
{
    Style st;
    st.grid_tiles = false;
    return st;
}

}  // namespace

static void test_one_vector(void **state)
{
    (void)state;
    Frame f;
    f.map.push_back(vec(1000, 2000, 0, 500));  // normal along +x: tick to (1120, 2000)
    std::string err;
    Layout L;
    assert_true(hlfig::layout_for(f, Style{}, nullptr, &L, &err));
    // Bounding box 1000..1120 x 2000 is widened to 1 m about its centre (1060, 2000).
    assert_true(L.x0 == 560 && L.x1 == 1560 && L.y0 == 1500 && L.y1 == 2500);
    assert_true(L.scale == 0.84);  // (900 - 2 * 30) px / 1000 mm
    assert_int_equal(L.top_px, 0);
    assert_int_equal(L.height_px, 30 + 840 + 30 + 24);

    std::string path = out_path("one.png");
    assert_true(hlfig::render_png(f, path, &err, Style{}));
    Png png(path);
    assert_int_equal(png.width, 900);
    assert_int_equal(png.height, L.height_px);
    assert_true(png.at(L, 1000, 2000) < 60);   // the surface point
    // The tick along the normal: a 1 px line on a pixel edge, so two half-covered rows.
    assert_true(png.darkest_at(L, 1080, 2000) < 160);
    assert_true(png.at(L, 1000, 2200) > 250);  // beside it: nothing drawn
    assert_int_equal(png.level(png.width - 2, 1), 255);  // far corner
    assert_int_equal(png.level(1, 1), 255);
}

static void test_fig3_full_length_and_star(void **state)
{
    (void)state;
    Frame f;
    f.map.push_back(vec(0, 0, 90, 2000));  // seen from (0, 2000)
    f.map_full_length = true;
    hl_scan_t scan;
    hl_scan_clear(&scan);
    assert_int_equal(hl_scan_add(&scan, 0, 1000, 0, true), HL_OK);
    assert_int_equal(hl_scan_add(&scan, hl_bam_from_deg(90), 1500, 1, false), HL_OK);
    f.scan = &scan;
    f.scan_pose = {3000, 1000, hl_bam_from_deg(90)};  // reading 0 ends at (3000, 2000)
    double view[4];
    hlfig::view_box({f}, view);
    // The vector, its sensor, the star's pose and its one valid end; the invalid reading
    // (which would end at (1500, 1000)) does not count.
    assert_true(view[0] == 0 && view[1] == 0 && view[2] == 3000 && view[3] == 2000);

    std::string err, path = out_path("fig3.png");
    Style st = no_grid();
    assert_true(hlfig::render_png(f, path, &err, st));
    Layout L;
    assert_true(hlfig::layout_for(f, st, nullptr, &L, &err));
    Png png(path);
    assert_int_equal(png.height, L.height_px);
    // The map vector runs all the way back to its sensor: translucent dark grey.
    // (A 0.6 px line on a pixel edge covers two columns by 0.3: about 232.)
    int mid = png.darkest_at(L, 0, 1000);
    assert_true(mid < 245 && mid > 150);
    // The star: light grey, and only toward the valid reading.
    int star = png.darkest_at(L, 3000, 1500);
    assert_true(star < 235 && star > 150);
    assert_int_equal(png.darkest_at(L, 2250, 1000), 255);
    assert_int_equal(png.darkest_at(L, 1500, 500), 255);
}

static void test_empty_frame(void **state)
{
    (void)state;
    Frame f;
    std::string err, path = out_path("empty.png");
    assert_true(hlfig::render_png(f, path, &err));
    Layout L;
    assert_true(hlfig::layout_for(f, Style{}, nullptr, &L, &err));
    assert_true(L.x0 == -500 && L.x1 == 500 && L.y0 == -500 && L.y1 == 500);
    Png png(path);
    assert_int_equal(png.width, 900);
    assert_int_equal(png.height, 924);
    assert_true(png.at(L, 250, 250) > 250);  // blank between the tile lines
    assert_true(png.darkest_at(L, 0, 250) < 250);  // the faint tile line through x = 0
    // The scale bar (100 mm here: 1 m would be wider than a third of the picture)
    // ends a margin from the right edge, in the bottom band.
    assert_true(png.darkest(870 - 42, 924 - 6) < 60);
}

static void test_vote_surface(void **state)
{
    (void)state;
    const int nx = 10, ny = 8, nt = 2;
    std::vector<uint32_t> cells(nx * ny * nt, 0);
    hl_loc_surface_t s{};
    s.cells = cells.data();
    s.nx = nx;
    s.ny = ny;
    s.nt = nt;
    s.x0_mm = 0;
    s.y0_mm = 0;
    s.cell_mm = 100;
    Frame f;
    f.votes = &s;
    Style st = no_grid();
    Layout L;
    std::string err;
    assert_true(hlfig::layout_for(f, st, nullptr, &L, &err));
    assert_true(L.x0 == 0 && L.x1 == 1000 && L.y0 == -100 && L.y1 == 900);

    // All zero: white, not NaN-black.
    std::string path = out_path("votes0.png");
    assert_true(hlfig::render_png(f, path, &err, st));
    {
        Png png(path);
        assert_int_equal(png.at(L, 250, 350), 255);
        assert_int_equal(png.at(L, 950, 50), 255);
    }

    // Slice 1: the peak cell (2, 3) black, a quarter of it at (7, 1) mid grey (sqrt).
    cells[nx * ny + 3 * nx + 2] = 4000;
    cells[nx * ny + 1 * nx + 7] = 1000;
    cells[0 * nx * ny + 5 * nx + 5] = 8000;  // slice 0 only
    f.vote_slice = 1;
    path = out_path("votes1.png");
    assert_true(hlfig::render_png(f, path, &err, st));
    {
        Png png(path);
        assert_true(png.at(L, 250, 350) < 3);
        int g = png.at(L, 750, 150);
        assert_true(g >= 125 && g <= 131);  // 255 * (1 - sqrt(1/4))
        assert_int_equal(png.at(L, 550, 550), 255);  // slice 0's cell not shown
    }

    // Max over slices: slice 0's 8000 is the new maximum.
    f.vote_slice = -1;
    path = out_path("votes_max.png");
    assert_true(hlfig::render_png(f, path, &err, st));
    {
        Png png(path);
        assert_true(png.at(L, 550, 550) < 3);
        int g = png.at(L, 250, 350);  // 255 * (1 - sqrt(1/2)) = 74.7
        assert_true(g >= 72 && g <= 78);
    }

    f.vote_slice = 2;
    assert_false(hlfig::render_png(f, out_path("bad.png"), &err, st));
    assert_string_equal(err.c_str(), "vote_slice 2 out of range -1..1");
}

static void test_unwritable_path(void **state)
{
    (void)state;
    Frame f;
    f.map.push_back(vec(0, 0, 0, 100));
    std::string err;
    std::string path = out_path("no-such-dir/out.png");
    assert_false(hlfig::render_png(f, path, &err));
    assert_string_equal(err.c_str(), ("cannot write " + path + ": No such file or directory").c_str());
    err.clear();
    assert_false(hlfig::render_sheet({f, f}, 2, path, &err));
    assert_true(err.find("cannot write " + path + ": ") == 0);
    // A null err is allowed.
    assert_false(hlfig::render_png(f, path, nullptr));
}

static void test_bad_arguments(void **state)
{
    (void)state;
    Frame f;
    std::string err;
    Style st;
    st.width_px = 50;
    assert_false(hlfig::render_png(f, out_path("x.png"), &err, st));
    assert_string_equal(err.c_str(), "bad style: width_px 50, margin_px 30");
    const double flat[4] = {0, 0, 1000, 0};
    assert_false(hlfig::render_png(f, out_path("x.png"), &err, Style{}, flat));
    assert_string_equal(err.c_str(), "view box is empty: x1 <= x0 or y1 <= y0");
    const double nan_view[4] = {0, 0, std::nan(""), 10};
    assert_false(hlfig::render_png(f, out_path("x.png"), &err, Style{}, nan_view));
    assert_string_equal(err.c_str(), "view box is not finite");
    assert_false(hlfig::render_sheet({}, 2, out_path("x.png"), &err));
    assert_false(hlfig::render_sheet({f}, 0, out_path("x.png"), &err));
    assert_string_equal(err.c_str(), "columns must be >= 1, got 0");
    struct stat sb;
    assert_int_equal(stat(out_path("x.png").c_str(), &sb), -1);  // nothing half-written
}

static void test_fixed_view_and_bands(void **state)
{
    (void)state;
    Frame f;
    f.path_truth = {{0, 0, 0}, {4000, 0, 0}};
    f.path_estimate = {{0, 100, 0}, {4000, 100, 0}};
    f.title = "a title";
    f.legend = "a legend";
    const double view[4] = {-1000, -2000, 3000, 2000};
    Layout L;
    std::string err;
    assert_true(hlfig::layout_for(f, no_grid(), view, &L, &err));
    assert_int_equal(L.top_px, 26);
    assert_true(L.scale == 0.21);  // 840 px / 4000 mm
    assert_int_equal(L.height_px, 26 + 60 + 840 + 24);
    std::string path = out_path("bands.png");
    assert_true(hlfig::render_png(f, path, &err, no_grid(), view));
    Png png(path);
    assert_int_equal(png.height, L.height_px);
    // Truth is black; the estimate blue; the path past the view's right edge is clipped
    // at the picture (no crash, nothing in the bands).
    uint32_t p = png.px[static_cast<size_t>(L.py(100)) * 900 + static_cast<size_t>(L.px(1000))];
    int b = p & 255, r = (p >> 16) & 255;
    assert_true(b > 150 && r < 120);
    assert_true(png.darkest_at(L, 1000, 0) < 100);
}

static void test_sheet(void **state)
{
    (void)state;
    std::vector<Frame> frames(5);
    for (size_t i = 0; i < frames.size(); i++) {
        frames[i].robot_positions.push_back({static_cast<int>(i) * 1000, 0, 0});
        frames[i].position_labels.push_back(std::to_string(i));
    }
    frames[0].title = "first";  // one titled tile: rows take the tallest height
    double view[4];
    hlfig::view_box(frames, view);
    assert_true(view[0] == -150 && view[2] == 4150 && view[1] == -500 && view[3] == 500);
    Style st = no_grid();
    st.width_px = 300;
    st.margin_px = 10;
    std::string err, path = out_path("sheet.png");
    assert_true(hlfig::render_sheet(frames, 3, path, &err, st));
    Layout L;
    assert_true(hlfig::layout_for(frames[0], st, view, &L, &err));
    Png png(path);
    assert_int_equal(png.width, 900);
    assert_int_equal(png.height, 2 * L.height_px);
    // Row 1 holds tiles 3 and 4; untitled, so 26 px higher in their cells than tile 0.
    int y = L.height_px + static_cast<int>(L.py(0)) - 26;
    // Tile 4 (column 1) has its robot at x = 4000 of the common view, tile 3 (column 0)
    // at x = 3000; each tile shows only its own.
    assert_true(png.darkest(300 + static_cast<int>(L.px(4000)), y, 6) < 140);
    assert_true(png.darkest(static_cast<int>(L.px(3000)), y, 6) < 140);
    assert_int_equal(png.darkest(300 + static_cast<int>(L.px(3000)), y, 6), 255);
}

// fontconfig (under cairo's text) keeps a pattern cache for the life of the process
// that cairo_debug_reset_static_data does not release; it is not ours to fix.
extern "C" const char *__lsan_default_suppressions(void);
extern "C" const char *__lsan_default_suppressions(void)
{
    return "leak:libfontconfig.so\n";
}

static int setup(void **state)
{
    (void)state;
    char tmpl[] = "/tmp/hlfig-test-XXXXXX";
    if (!mkdtemp(tmpl))
        return -1;
    g_dir = tmpl;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    // Frees cairo's font caches, which LeakSanitizer would otherwise report.
    cairo_debug_reset_static_data();
    std::string cmd = "rm -rf '" + g_dir + "'";
    return std::system(cmd.c_str()) == 0 ? 0 : -1;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_vector),
        cmocka_unit_test(test_fig3_full_length_and_star),
        cmocka_unit_test(test_empty_frame),
        cmocka_unit_test(test_vote_surface),
        cmocka_unit_test(test_unwritable_path),
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_fixed_view_and_bands),
        cmocka_unit_test(test_sheet),
    };
    return cmocka_run_group_tests_name("experiments/render", tests, setup, teardown);
}
