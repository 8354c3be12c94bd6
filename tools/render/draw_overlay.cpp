// The overlay layer: projected lines, dots, labels and translucent polygons drawn last, so a
// joint inside a body or behind another still shows. Labels get a pale halo to stay legible on
// any body colour.

#include "draw_overlay.h"

#include "cairo_util.h"

#include <algorithm>

namespace af::render::detail {

namespace {

bool project(const Projector& proj, const Vec3& world, Vec2& pixel) {
    const Vec3 view = proj.toView(world);
    if (view.z() < proj.nearDepth()) return false;
    pixel = proj.toPixels(view);
    return true;
}

void drawArrowHead(cairo_t* cr, const Vec2& from, const Vec2& to, double size) {
    const Vec2 d = to - from;
    if (d.norm() < 1e-9) return;
    const Vec2 back = -d.normalized() * size, side(-back.y() * 0.5, back.x() * 0.5);
    cairo_new_path(cr);
    cairo_move_to(cr, to.x(), to.y());
    cairo_line_to(cr, to.x() + back.x() + side.x(), to.y() + back.y() + side.y());
    cairo_line_to(cr, to.x() + back.x() - side.x(), to.y() + back.y() - side.y());
    cairo_close_path(cr);
    cairo_fill(cr);
}

}  // namespace

void drawOverlay(cairo_t* cr, const Projector& proj, const Overlay& overlay, double lineScale) {
    cairo_save(cr);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const OverlayPolygon& p : overlay.polygons) {
        std::vector<Vec3> view;
        for (const Vec3& v : p.points) view.push_back(proj.toView(v));
        const std::vector<Vec2> pixels = proj.polygonToPixels(view);
        if (pixels.size() < 3) continue;
        cairo_new_path(cr);
        for (const Vec2& q : pixels) cairo_line_to(cr, q.x(), q.y());
        cairo_close_path(cr);
        setColour(cr, p.colour, p.alpha);
        cairo_fill_preserve(cr);
        setColour(cr, p.colour, std::min(1.0, 2 * p.alpha));
        cairo_set_line_width(cr, 0.6 * lineScale);
        cairo_stroke(cr);
    }
    for (const OverlayLine& l : overlay.lines) {
        Vec2 a, b;
        if (!proj.segmentToPixels(proj.toView(l.from), proj.toView(l.to), a, b)) continue;
        setColour(cr, l.colour);
        cairo_set_line_width(cr, l.width * lineScale);
        cairo_new_path(cr);
        cairo_move_to(cr, a.x(), a.y());
        cairo_line_to(cr, b.x(), b.y());
        cairo_stroke(cr);
        if (l.arrow) drawArrowHead(cr, a, b, (4 + 2 * l.width) * lineScale);
    }
    for (const OverlayDot& d : overlay.dots) {
        Vec2 at;
        if (!project(proj, d.at, at)) continue;
        cairo_new_path(cr);
        cairo_arc(cr, at.x(), at.y(), d.radius * lineScale, 0, 6.283185307179586);
        setColour(cr, d.colour);
        cairo_fill_preserve(cr);
        cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
        cairo_set_line_width(cr, 0.6 * lineScale);
        cairo_stroke(cr);
    }
    useFont(cr, 7.5 * lineScale);
    for (const OverlayLabel& l : overlay.labels) {
        Vec2 at;
        if (!project(proj, l.at, at)) continue;
        const double x = at.x() + 3 * lineScale, y = at.y() - 3 * lineScale;
        cairo_new_path(cr);
        cairo_move_to(cr, x, y);
        cairo_text_path(cr, l.text.c_str());
        cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
        cairo_set_line_width(cr, 2.5 * lineScale);
        cairo_stroke(cr);
        setColour(cr, l.colour);
        cairo_move_to(cr, x, y);
        cairo_show_text(cr, l.text.c_str());
    }
    cairo_restore(cr);
}

}  // namespace af::render::detail
