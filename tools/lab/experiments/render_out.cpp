// render_out.cpp - frames to PNG files, one frame or a sheet of several (see render.hpp).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>

#include "render_cairo.hpp"
#include "render_geom.hpp"

namespace hlfig {
namespace {

using namespace geom;

struct PngSink {
    FILE *fp;
    int errnum;
};

cairo_status_t png_write(void *closure, const unsigned char *data, unsigned int length)
{
    auto *sink = static_cast<PngSink *>(closure);
    if (std::fwrite(data, 1, length, sink->fp) != length) {
        sink->errnum = errno ? errno : EIO;
        return CAIRO_STATUS_WRITE_ERROR;
    }
    return CAIRO_STATUS_SUCCESS;
}

// Writes through stdio rather than cairo_surface_write_to_png so that a failure can
// name its cause (cairo only says "error while writing to output stream").
bool write_png(cairo_surface_t *s, const std::string &path, std::string *err)
{
    errno = 0;
    FILE *fp = std::fopen(path.c_str(), "wb");
    if (!fp) {
        set_err(err, "cannot write " + path + ": " + std::strerror(errno ? errno : EIO));
        return false;
    }
    PngSink sink{fp, 0};
    cairo_status_t cs = cairo_surface_write_to_png_stream(s, png_write, &sink);
    errno = 0;
    bool closed = std::fclose(fp) == 0;
    if (!closed && !sink.errnum)
        sink.errnum = errno ? errno : EIO;
    if (cs != CAIRO_STATUS_SUCCESS || !closed) {
        std::remove(path.c_str());  // a truncated PNG is worse than none
        set_err(err, "cannot write " + path + ": " +
                         (sink.errnum ? std::strerror(sink.errnum) : cairo_status_to_string(cs)));
        return false;
    }
    return true;
}

bool render_png_impl(const Frame &f, const std::string &path, std::string *err,
                     const Style &st, const double *view_mm)
{
    Layout L;
    if (!layout_for(f, st, view_mm, &L, err))
        return false;
    Surface s = render_surface(f, st, L, err);
    return s && write_png(s.get(), path, err);
}

bool render_sheet_impl(const std::vector<Frame> &frames, int columns, const std::string &path,
                       std::string *err, const Style &st, const double *view_mm)
{
    if (frames.empty()) {
        set_err(err, "no frames for " + path);
        return false;
    }
    if (columns < 1) {
        set_err(err, "columns must be >= 1, got " + std::to_string(columns));
        return false;
    }
    double view[4];
    if (view_mm)
        std::copy(view_mm, view_mm + 4, view);
    else
        view_box(frames, view);

    std::vector<Surface> tiles;
    int tile_h = 0;
    for (const Frame &f : frames) {
        Layout L;
        if (!layout_from_view(f, st, view, &L, err))
            return false;
        tiles.push_back(render_surface(f, st, L, err));
        if (!tiles.back())
            return false;
        tile_h = std::max(tile_h, L.height_px);
    }
    int n = static_cast<int>(frames.size());
    int cols = std::min(columns, n);
    int rows = (n + cols - 1) / cols;
    long w = static_cast<long>(cols) * st.width_px, h = static_cast<long>(rows) * tile_h;
    if (w > kMaxSurfacePx || h > kMaxSurfacePx) {
        set_err(err, "sheet too large: " + std::to_string(w) + " x " + std::to_string(h) + " px");
        return false;
    }
    Surface sheet(cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(w),
                                             static_cast<int>(h)));
    if (cairo_surface_status(sheet.get()) != CAIRO_STATUS_SUCCESS) {
        set_err(err, "cannot create a " + std::to_string(w) + " x " + std::to_string(h) + " sheet");
        return false;
    }
    Context cr(cairo_create(sheet.get()));
    cairo_t *c = cr.get();
    grey(c, 1.0);
    cairo_paint(c);
    for (int i = 0; i < n; i++) {
        cairo_set_source_surface(c, tiles[static_cast<size_t>(i)].get(),
                                 (i % cols) * st.width_px, (i / cols) * tile_h);
        cairo_paint(c);
    }
    // Hairlines between tiles, so neighbouring white margins do not merge.
    grey(c, 0.6);
    cairo_set_line_width(c, 1.0);
    for (int k = 1; k < cols; k++) {
        cairo_move_to(c, k * st.width_px + 0.5, 0);
        cairo_line_to(c, k * st.width_px + 0.5, static_cast<double>(h));
    }
    for (int k = 1; k < rows; k++) {
        cairo_move_to(c, 0, k * tile_h + 0.5);
        cairo_line_to(c, static_cast<double>(w), k * tile_h + 0.5);
    }
    cairo_stroke(c);
    cr.reset();
    cairo_surface_flush(sheet.get());
    return write_png(sheet.get(), path, err);
}

// Building the message may itself run out of memory; then the message is lost, but
// the caller still gets false instead of std::terminate.
void report_exception(std::string *err, const std::string &path, const char *what) noexcept
{
    try {
        set_err(err, "cannot render " + path + ": " + what);
    } catch (...) {
    }
}

}  // namespace


bool render_png(const Frame &f, const std::string &path, std::string *err, const Style &st,
                const double *view_mm)
{
    try {
        return render_png_impl(f, path, err, st, view_mm);
    } catch (const std::exception &e) {
        report_exception(err, path, e.what());
    } catch (...) {
        report_exception(err, path, "unknown exception");
    }
    return false;
}

bool render_sheet(const std::vector<Frame> &frames, int columns, const std::string &path,
                  std::string *err, const Style &st, const double *view_mm)
{
    try {
        return render_sheet_impl(frames, columns, path, err, st, view_mm);
    } catch (const std::exception &e) {
        report_exception(err, path, e.what());
    } catch (...) {
        report_exception(err, path, "unknown exception");
    }
    return false;
}
}  // namespace hlfig
