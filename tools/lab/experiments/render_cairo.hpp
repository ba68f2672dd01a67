// render_cairo.hpp - between render.cpp (drawing a frame onto a cairo surface) and
// render_out.cpp (writing surfaces as PNG, one frame or a sheet of them).
#ifndef HLFIG_RENDER_CAIRO_HPP
#define HLFIG_RENDER_CAIRO_HPP

#include <memory>
#include <string>

#include <cairo.h>

#include "render.hpp"

namespace hlfig {
namespace geom {

struct SurfaceDeleter {
    void operator()(cairo_surface_t *s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
    void operator()(cairo_t *c) const { cairo_destroy(c); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using Context = std::unique_ptr<cairo_t, ContextDeleter>;

/** Sets a grey source: 0 black, 1 white. */
inline void grey(cairo_t *cr, double g, double alpha = 1)
{
    cairo_set_source_rgba(cr, g, g, g, alpha);
}

/** Frame @p f drawn at layout @p L; null with a reason in @p err on failure. */
Surface render_surface(const Frame &f, const Style &st, const Layout &L, std::string *err);

}  // namespace geom
}  // namespace hlfig
#endif
