// draw_world.cpp - hl-sim-draw: a PNG of a simulator world, its named positions, the
// tour, and one simulated sounding, for checking a world by eye.
#include <cairo.h>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "houghloc/calib.h"
#include "houghloc/fixed.h"
#include "robot.hpp"
#include "tour.hpp"
#include "world.hpp"

using namespace hlsim;

namespace {

void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: hl-sim-draw [--world FILE] [--out FILE.png] [--position NAME]\n"
                 "                   [--seed N] [--tour] [--px-per-m N]\n"
                 "Draws the world (default: built-in lab), its positions, one sounding at\n"
                 "NAME (default: the first position) and, with --tour, the tour order.\n"
                 "--seed: the sounding's random draws, 0..18446744073709551615 (default 1);\n"
                 "--px-per-m: the scale, 10..400 (default 80).\n");
}

// One line naming the option and its value, exit status 2.
int bad_value(const char *option, const char *value, const char *want)
{
    std::fprintf(stderr, "hl-sim-draw: %s '%s': expected %s (try --help)\n", option, value, want);
    return 2;
}

// A whole decimal number 0..UINT64_MAX: no sign, no spaces, no trailing characters.
bool parse_seed(const char *s, uint64_t *out)
{
    if (*s < '0' || *s > '9')
        return false;
    char *end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(s, &end, 10);
    if (*end != '\0' || errno == ERANGE)
        return false;
    *out = v;
    return true;
}

// A plain decimal number (no hexadecimal, no spaces, nothing after it) in [lo, hi].
bool parse_decimal(const char *s, double lo, double hi, double *out)
{
    if (!(*s == '-' || *s == '+' || *s == '.' || (*s >= '0' && *s <= '9')) ||
        std::strpbrk(s, "xX") != nullptr)
        return false;
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (*end != '\0' || errno == ERANGE || !(v >= lo && v <= hi))
        return false;
    *out = v;
    return true;
}

}  // namespace

int main(int argc, char **argv)
{
    std::string world_path, out = "world.png", pos_name;
    uint64_t seed = 1;
    bool draw_tour = false;
    double px_per_m = 80.0;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        bool v = i + 1 < argc;
        if (a == "--help" || a == "-h") {
            usage(stdout);
            return 0;
        } else if (a == "--world" && v) {
            world_path = argv[++i];
        } else if (a == "--out" && v) {
            out = argv[++i];
        } else if (a == "--position" && v) {
            pos_name = argv[++i];
        } else if (a == "--seed" && v) {
            if (!parse_seed(argv[++i], &seed))
                return bad_value("--seed", argv[i], "an integer 0..18446744073709551615");
        } else if (a == "--px-per-m" && v) {
            if (!parse_decimal(argv[++i], 10.0, 400.0, &px_per_m))
                return bad_value("--px-per-m", argv[i], "pixels per metre, 10..400");
        } else if (a == "--tour") {
            draw_tour = true;
        } else {
            std::fprintf(stderr, "hl-sim-draw: unknown or incomplete option '%s' (try --help)\n",
                         a.c_str());
            return 2;
        }
    }
    World w;
    std::string err;
    if (!World::load_or_lab(world_path, &w, &err)) {
        std::fprintf(stderr, "hl-sim-draw: %s\n", err.c_str());
        return 1;
    }
    Vec2 lo, hi;
    if (!w.bounds(&lo, &hi)) {
        std::fprintf(stderr, "hl-sim-draw: the world is empty\n");
        return 1;
    }
    const double margin = 300.0, s = px_per_m / 1000.0;
    int width = static_cast<int>((hi.x - lo.x + 2 * margin) * s);
    int height = static_cast<int>((hi.y - lo.y + 2 * margin) * s);
    if (width > 8000 || height > 8000) {
        std::fprintf(stderr, "hl-sim-draw: image would be %dx%d; lower --px-per-m\n", width, height);
        return 1;
    }
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    // World millimetres to pixels, y up.
    auto X = [&](double x) { return (x - lo.x + margin) * s; };
    auto Y = [&](double y) { return height - (y - lo.y + margin) * s; };

    // Floor tiles (the world's `tiles`; two feet in the lab).
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.92);
    cairo_set_line_width(cr, 0.5);
    const double tile = w.tile_mm;
    for (double x = std::floor(lo.x / tile) * tile; x <= hi.x; x += tile) {
        cairo_move_to(cr, X(x), Y(lo.y));
        cairo_line_to(cr, X(x), Y(hi.y));
    }
    for (double y = std::floor(lo.y / tile) * tile; y <= hi.y; y += tile) {
        cairo_move_to(cr, X(lo.x), Y(y));
        cairo_line_to(cr, X(hi.x), Y(y));
    }
    cairo_stroke(cr);

    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 2.0);
    for (const Segment &g : w.segments) {
        cairo_move_to(cr, X(g.a.x), Y(g.a.y));
        cairo_line_to(cr, X(g.b.x), Y(g.b.y));
    }
    cairo_stroke(cr);
    for (const Circle &c : w.circles) {
        cairo_new_sub_path(cr);
        cairo_arc(cr, X(c.c.x), Y(c.c.y), c.r * s, 0, 2 * kPi);
    }
    cairo_stroke(cr);

    if (draw_tour) {
        Vec2 start = w.has_tour ? w.tour_start : lab_tour_start();
        std::vector<TourStop> stops = tour_order(w, start, w.tile_mm, kTourClearanceMm);
        cairo_set_source_rgba(cr, 0.1, 0.6, 0.1, 0.8);
        cairo_set_line_width(cr, 1.5);
        for (std::size_t i = 0; i < stops.size(); i++) {
            if (i == 0)
                cairo_move_to(cr, X(stops[i].at.x), Y(stops[i].at.y));
            for (Vec2 v : stops[i].via)
                cairo_line_to(cr, X(v.x), Y(v.y));
            cairo_line_to(cr, X(stops[i].at.x), Y(stops[i].at.y));
        }
        cairo_stroke(cr);
        std::printf("tour: %zu stops\n", stops.size());
    }

    // Positions: circles at the tile intersections, as in the paper's Figure 2.
    cairo_select_font_face(cr, "sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 10);
    for (const Position &p : w.positions) {
        cairo_set_source_rgb(cr, 0.1, 0.2, 0.8);
        cairo_new_sub_path(cr);
        cairo_arc(cr, X(p.pose.x), Y(p.pose.y), 5, 0, 2 * kPi);
        cairo_move_to(cr, X(p.pose.x), Y(p.pose.y));
        cairo_line_to(cr, X(p.pose.x + 250 * std::cos(p.pose.theta)),
                      Y(p.pose.y + 250 * std::sin(p.pose.theta)));
        cairo_stroke(cr);
        cairo_move_to(cr, X(p.pose.x) + 6, Y(p.pose.y) - 6);
        cairo_show_text(cr, p.name.c_str());
    }

    // One sounding, plotted from the odometry pose at the nominal bearings, as a
    // localizer would see it: valid readings red, invalid ones as grey stubs.
    const Position *at = pos_name.empty() ? (w.positions.empty() ? nullptr : &w.positions[0])
                                          : w.find(pos_name);
    if (!pos_name.empty() && !at) {
        std::fprintf(stderr, "hl-sim-draw: no position named '%s'\n", pos_name.c_str());
        return 1;
    }
    if (at) {
        Rng rng(seed);
        SonarParams sp;
        RobotParams rp;
        Robot robot(w, sp, rp, rng, 0);
        robot.place(at->pose, at->pose);
        Sounding snd = robot.sound();
        int valid = 0;
        for (const RingReading &r : snd.readings) {
            int32_t mm;
            bool ok = hl_calib_apply(&sp.calib, r.sonar.raw, &mm);
            double a = at->pose.theta + hl_bam_to_rad(r.bearing_bam);
            double len = ok ? mm : 300.0;
            Vec2 e = at->pose.pos() + Vec2::polar(a) * len;
            if (ok) {
                valid++;
                cairo_set_source_rgba(cr, 0.9, 0.2, 0.1, 0.25);
            } else {
                cairo_set_source_rgba(cr, 0.5, 0.5, 0.5, 0.6);
            }
            cairo_set_line_width(cr, 0.7);
            cairo_move_to(cr, X(at->pose.x), Y(at->pose.y));
            cairo_line_to(cr, X(e.x), Y(e.y));
            cairo_stroke(cr);
            if (ok) {
                cairo_set_source_rgb(cr, 0.9, 0.1, 0.0);
                cairo_arc(cr, X(e.x), Y(e.y), 2.0, 0, 2 * kPi);
                cairo_fill(cr);
            }
        }
        std::printf("sounding at %s: %d of %zu readings valid\n", at->name.c_str(), valid,
                    snd.readings.size());
    }

    cairo_destroy(cr);
    cairo_status_t st = cairo_surface_write_to_png(surf, out.c_str());
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS) {
        std::fprintf(stderr, "hl-sim-draw: %s: %s\n", out.c_str(), cairo_status_to_string(st));
        return 1;
    }
    return 0;
}
