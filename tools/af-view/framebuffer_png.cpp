#include "framebuffer_png.h"

#include "gl_api.h"

#include <cairo.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace af::view {

void writeFramebufferPng(int width, int height, const std::string& path) {
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());

    // OpenGL's rows run bottom up; cairo's RGB24 is one native-endian 0x00RRGGBB word a pixel.
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    const int stride = cairo_image_surface_get_stride(surface);
    cairo_surface_flush(surface);
    unsigned char* pixels = cairo_image_surface_get_data(surface);
    for (int y = 0; y < height; ++y) {
        auto* row = reinterpret_cast<std::uint32_t*>(pixels + std::size_t(y) * std::size_t(stride));
        const std::uint8_t* source = rgba.data() + std::size_t(height - 1 - y) * std::size_t(width) * 4;
        for (int x = 0; x < width; ++x, source += 4) row[x] = std::uint32_t(source[0]) << 16 | std::uint32_t(source[1]) << 8 | source[2];
    }
    cairo_surface_mark_dirty(surface);

    std::filesystem::path temporary = path;
    temporary += ".partial";
    const cairo_status_t status = cairo_surface_write_to_png(surface, temporary.string().c_str());
    cairo_surface_destroy(surface);
    std::error_code ec;
    if (status == CAIRO_STATUS_SUCCESS) std::filesystem::rename(temporary, path, ec);
    if (status != CAIRO_STATUS_SUCCESS || ec) {
        std::filesystem::remove(temporary, ec);
        throw std::runtime_error("cannot write " + path);
    }
}

}  // namespace af::view
