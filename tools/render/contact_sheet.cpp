// A grid of labelled views of several frames under one camera.

#include "cairo_util.h"
#include "draw_scene.h"

#include <algorithm>
#include <stdexcept>

namespace af::render {

PixelRect contactSheetCell(int index, int columns, const SheetOptions& o) {
    const int column = index % columns, row = index / columns;
    return {o.gap + column * (o.cellWidth + o.gap), o.gap + row * (o.cellHeight + o.gap), o.cellWidth, o.cellHeight};
}

PixelRect contactSheetSize(int count, int columns, const SheetOptions& o) {
    const int rows = (count + columns - 1) / columns;
    const int used = std::min(count, columns);
    return {0, 0, o.gap + used * (o.cellWidth + o.gap), o.gap + rows * (o.cellHeight + o.gap)};
}

void writeContactSheet(const std::vector<RenderScene>& frames, const std::vector<std::string>& labels, int columns,
                       const std::string& path, const SheetOptions& options) {
    if (frames.empty()) throw std::invalid_argument("contact sheet: no frames");
    if (labels.size() != frames.size()) {
        throw std::invalid_argument("contact sheet: " + std::to_string(frames.size()) + " frames but " +
                                    std::to_string(labels.size()) + " labels");
    }
    if (columns < 1) throw std::invalid_argument("contact sheet: columns must be at least 1");
    if (options.cellWidth < 1 || options.cellHeight < 1 || options.gap < 0) {
        throw std::invalid_argument("contact sheet: cell size must be positive and the gap not negative");
    }
    const int count = static_cast<int>(frames.size());
    const PixelRect sheet = contactSheetSize(count, columns, options);
    detail::Canvas canvas = detail::makeCanvas(sheet.width, sheet.height);
    cairo_t* cr = canvas.cr.get();
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);

    const Camera camera = fitCamera(frames, static_cast<double>(options.cellWidth) / options.cellHeight);
    const double fontSize = std::max(10.0, options.cellHeight / 16.0);
    for (int i = 0; i < count; ++i) {
        const PixelRect cell = contactSheetCell(i, columns, options);
        cairo_save(cr);
        cairo_translate(cr, cell.x, cell.y);
        cairo_rectangle(cr, 0, 0, cell.width, cell.height);
        cairo_clip(cr);
        detail::drawScene(cr, frames[i], camera, cell.width, cell.height);

        // The label on a light plate, so it reads over any part of the picture.
        detail::useFont(cr, fontSize, true);
        cairo_text_extents_t extents;
        cairo_text_extents(cr, labels[i].c_str(), &extents);
        const double pad = 0.4 * fontSize;
        cairo_rectangle(cr, 0, 0, extents.x_advance + 2 * pad, fontSize + 2 * pad);
        cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
        cairo_fill(cr);
        cairo_set_source_rgb(cr, 0.12, 0.13, 0.15);
        detail::drawText(cr, labels[i], pad, pad + 0.85 * fontSize);
        cairo_restore(cr);

        cairo_rectangle(cr, cell.x - 0.5, cell.y - 0.5, cell.width + 1, cell.height + 1);
        cairo_set_source_rgb(cr, 0.55, 0.57, 0.60);
        cairo_set_line_width(cr, 1);
        cairo_stroke(cr);
    }
    detail::savePng(canvas.surface.get(), path);
}

}  // namespace af::render
