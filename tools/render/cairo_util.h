#pragma once
// Ownership of cairo objects and the few drawing helpers the pictures share.

#include "render.h"

#include <cairo.h>

#include <memory>
#include <string>

namespace af::render::detail {

struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
    void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using Context = std::unique_ptr<cairo_t, ContextDeleter>;

/// An ARGB image of the given size and a context drawing on it. Throws std::invalid_argument
/// for a non-positive size, std::runtime_error when cairo cannot allocate it.
struct Canvas {
    Surface surface;
    Context cr;
};
Canvas makeCanvas(int width, int height);

/// Writes the surface as PNG; throws std::runtime_error naming `path` and the reason on failure.
void savePng(cairo_surface_t* surface, const std::string& path);

inline void setColour(cairo_t* cr, const Colour& c, double alpha = 1.0) {
    cairo_set_source_rgba(cr, c[0], c[1], c[2], alpha);
}

/// Selects the sans-serif face used for every label, at `size` pixels.
void useFont(cairo_t* cr, double size, bool bold = false);

enum class Align { Left, Centre, Right };

/// Draws `text` with its baseline at y and aligned on x as asked.
void drawText(cairo_t* cr, const std::string& text, double x, double y, Align align = Align::Left);

}  // namespace af::render::detail
