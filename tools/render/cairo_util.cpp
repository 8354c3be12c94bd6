#include "cairo_util.h"

#include <fontconfig/fontconfig.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace af::render::detail {

Canvas makeCanvas(int width, int height) {
    if (width <= 0 || height <= 0) {
        throw std::invalid_argument("image size must be positive, got " + std::to_string(width) + " x " +
                                    std::to_string(height));
    }
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(std::string("cannot create a ") + std::to_string(width) + " x " +
                                 std::to_string(height) +
                                 " image: " + cairo_status_to_string(cairo_surface_status(surface.get())));
    }
    Context cr(cairo_create(surface.get()));
    return {std::move(surface), std::move(cr)};
}

void savePng(cairo_surface_t* surface, const std::string& path) {
    cairo_surface_flush(surface);
    const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
    if (status != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error("cannot write PNG '" + path + "': " + cairo_status_to_string(status));
    }
}

void useFont(cairo_t* cr, double size, bool bold) {
    // Text loads fontconfig's configuration, which cairo caches for the life of the program and
    // fontconfig never frees on its own: a leak checker (the sanitizer build) would flag every
    // program that draws a label. Release both caches at exit, when no cairo object is left.
    static std::once_flag releaseAtExit;
    std::call_once(releaseAtExit, [] {
        std::atexit([] {
            cairo_debug_reset_static_data();
            FcFini();
        });
    });
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

void drawText(cairo_t* cr, const std::string& text, double x, double y, Align align) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text.c_str(), &extents);
    double dx = 0;
    if (align == Align::Centre) dx = -(extents.x_bearing + extents.width / 2);
    if (align == Align::Right) dx = -(extents.x_bearing + extents.width);
    cairo_move_to(cr, x + dx, y);
    cairo_show_text(cr, text.c_str());
}

}  // namespace af::render::detail
