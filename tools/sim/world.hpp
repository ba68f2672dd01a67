// world.hpp - the simulated 2-D world: wall and obstacle segments, round obstacles,
// and named sounding positions, loaded from a line-based text file (docs/manual/houghloc-sim.md).
#ifndef HLSIM_WORLD_HPP
#define HLSIM_WORLD_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geom.hpp"

namespace hlsim {

/** How a surface returns sound (docs/manual/houghloc-sim.md, "Echo model"). A shape line in a
 *  world file may end with one of the words smooth, rough, thin; the default is smooth. */
enum class Surface : uint8_t {
    Smooth,  // painted wall, desk side, metal cabinet: a mirror at sonar wavelengths
    Rough,   // cardboard, books on a shelf, fabric: scatters some sound back at any angle
    Thin,    // a chair or table leg, a pipe: a weak, point-like target
};

struct Segment {
    Vec2 a, b;
    Surface surface = Surface::Smooth;
};

struct Circle {
    Vec2 c;
    double r = 0.0;
    Surface surface = Surface::Smooth;
};

/** An axis-aligned rectangle, lo <= hi. */
struct Rect {
    Vec2 lo, hi;
};

/** A named place where the robot is set down (heading in radians). */
struct Position {
    std::string name;
    Pose pose;
};

/** The first surface a ray meets. */
struct Hit {
    double dist = 0.0;  // mm along the ray
    Vec2 point;         // where it hit
    Vec2 normal;        // unit surface normal, facing back toward the ray's origin
    Surface surface = Surface::Smooth;  // of the shape hit
    double radius = 0.0;  // of the circle hit; 0 for a segment
};

/** Limits the parser enforces, so a hostile file cannot exhaust memory or overflow. */
constexpr double kWorldCoordMax = 4000000.0;  // |coordinate| in mm (fits hl_mm_t)
constexpr std::size_t kWorldMaxShapes = 20000;  // segments + circles
constexpr std::size_t kWorldMaxPositions = 1000;
constexpr std::size_t kWorldMaxOpen = 1000;     // open rectangles
constexpr std::size_t kWorldMaxLine = 1000;     // characters per line

class World {
public:
    std::vector<Segment> segments;
    std::vector<Circle> circles;
    std::vector<Position> positions;

    /* The experiments' layout, declared in the world file (docs/manual/houghloc-sim.md), so that
     * hl-sim-logs works for any world: */
    double tile_mm = 609.6;     // `tiles MM`: floor tiles; positions are drawn on their
                                // intersections (multiples of tile_mm on both axes)
    std::vector<Rect> open;     // `open X0 Y0 X1 Y1` (repeatable): the open floor where
                                // Table 1's positions are drawn
    bool has_orientation = false;
    Vec2 orientation_corner;    // `orientation X Y`: south-west corner of the orientation
                                // test's 1.5 m square
    bool has_tour = false;
    Vec2 tour_start;            // `tour X Y`: where the tour starts
    bool has_start = false;
    Pose start;                 // `start X Y HEADING_DEG`: houghloc-sim's default start
                                // pose (heading in radians); at most one

    /**
     * Parses world text. On failure returns false and sets @p err to one line,
     * "NAME:LINE: what was wrong"; the world is then left empty.
     */
    bool parse(const std::string &text, const std::string &name, std::string *err);
    /** Reads and parses a file; errors as for parse(). */
    bool load(const std::string &path, std::string *err);
    /** The world file at @p path, or the built-in lab when @p path is empty. */
    static bool load_or_lab(const std::string &path, World *out, std::string *err);
    /** The built-in lab (tools/sim/worlds/lab.world, compiled in). */
    static World lab();
    /** The text of the built-in lab world. */
    static const char *lab_text();

    /**
     * Casts a ray from @p origin along the unit vector @p dir.
     * @return true and the nearest hit within @p max_dist, false if none.
     */
    bool cast(Vec2 origin, Vec2 dir, double max_dist, Hit *hit) const;

    /** Distance from @p p to the nearest surface (infinity in an empty world). */
    double clearance(Vec2 p) const;

    /**
     * Whether @p p is enclosed: every ray from it (one per degree) meets a surface.
     * @return false and one line in @p err ("the world is not closed around (x, y): a
     * ray at D degrees meets nothing") otherwise.
     */
    bool enclosed(Vec2 p, std::string *err) const;

    /** The named position, or nullptr. */
    const Position *find(const std::string &name) const;

    /** Axis-aligned bounding box of all shapes; false if the world is empty. */
    bool bounds(Vec2 *lo, Vec2 *hi) const;

    /** Adds the four sides of a rectangle centred at @p c, size w x h, rotated by @p angle. */
    void add_box(Vec2 c, double w, double h, double angle);

private:
    bool seen_tiles_ = false;  // `tiles` may be given once
    bool parse_line(const std::string &line, std::string *what);
    bool parse_layout(const std::vector<std::string> &words, std::string *what);
    bool parse_start(const std::vector<std::string> &words, std::string *what);
};

}  // namespace hlsim
#endif
