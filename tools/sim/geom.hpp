// geom.hpp - the simulator's small 2-D vocabulary: points, poses, angles.
//
// The simulator works in double-precision millimetres and radians; it converts to the
// project's fixed-point formats (int32 mm, 16-bit binary angles) only at its output.
#ifndef HLSIM_GEOM_HPP
#define HLSIM_GEOM_HPP

#include <cmath>

namespace hlsim {

constexpr double kPi = 3.14159265358979323846;

inline double deg2rad(double d) { return d * (kPi / 180.0); }
inline double rad2deg(double r) { return r * (180.0 / kPi); }

/** Wraps an angle to [-pi, pi). */
inline double wrap_pi(double a)
{
    a = std::fmod(a + kPi, 2.0 * kPi);
    if (a < 0.0)
        a += 2.0 * kPi;
    return a - kPi;
}

struct Vec2 {
    double x = 0.0, y = 0.0;
    Vec2() = default;
    Vec2(double x_, double y_) : x(x_), y(y_) {}
    Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    Vec2 operator*(double s) const { return {x * s, y * s}; }
    double dot(Vec2 o) const { return x * o.x + y * o.y; }
    double cross(Vec2 o) const { return x * o.y - y * o.x; }
    double norm() const { return std::hypot(x, y); }
    static Vec2 polar(double angle) { return {std::cos(angle), std::sin(angle)}; }
};

/** A robot pose: position in mm, heading in radians counter-clockwise from +x. */
struct Pose {
    double x = 0.0, y = 0.0, theta = 0.0;
    Vec2 pos() const { return {x, y}; }
};

}  // namespace hlsim
#endif
