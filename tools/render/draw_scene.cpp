// Flat-shaded convex shapes over a fading checkered floor, painter's order per object.

#include "draw_scene.h"

#include "cairo_util.h"
#include "depth_order.h"
#include "draw_overlay.h"
#include "projection.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <span>

namespace af::render {
namespace detail {
namespace {

constexpr Colour kStaticColour     = {0.62f, 0.64f, 0.67f};
constexpr Colour kFloorLight       = {0.87f, 0.86f, 0.83f};
constexpr Colour kFloorDark        = {0.77f, 0.76f, 0.73f};
constexpr Colour kBackgroundTop    = {0.78f, 0.83f, 0.90f};
constexpr Colour kBackgroundBottom = {0.95f, 0.96f, 0.97f};

// Towards the light: above, a little to the left of the fitted view (which looks from the
// front-right), so its three visible sides of a box are lit brightest, middle and least.
const Vec3& lightDirection() {
    static const Vec3 l = Vec3(0.25, -0.6, 1.0).normalized();
    return l;
}

// Lambert plus a little sky light from above, so faces turned from the light still differ.
double brightness(const Vec3& normal) {
    const double lambert = std::max(0.0, normal.dot(lightDirection()));
    return std::min(1.0, 0.42 + 0.12 * (0.5 + 0.5 * normal.z()) + 0.50 * lambert);
}

Colour scaled(const Colour& c, double k) {
    return {static_cast<float>(c[0] * k), static_cast<float>(c[1] * k), static_cast<float>(c[2] * k)};
}

void tracePolygon(cairo_t* cr, const std::vector<Vec2>& pixels) {
    cairo_new_path(cr);
    for (const Vec2& p : pixels) cairo_line_to(cr, p.x(), p.y());
    cairo_close_path(cr);
}

std::vector<Vec2> projectPolygon(const Projector& proj, const std::vector<Vec3>& world) {
    std::vector<Vec3> view;
    view.reserve(world.size());
    for (const Vec3& p : world) view.push_back(proj.toView(p));
    return proj.polygonToPixels(view);
}

void drawBackground(cairo_t* cr, double width, double height) {
    cairo_pattern_t* sky = cairo_pattern_create_linear(0, 0, 0, height);
    cairo_pattern_add_color_stop_rgb(sky, 0, kBackgroundTop[0], kBackgroundTop[1], kBackgroundTop[2]);
    cairo_pattern_add_color_stop_rgb(sky, 1, kBackgroundBottom[0], kBackgroundBottom[1], kBackgroundBottom[2]);
    cairo_set_source(cr, sky);
    cairo_rectangle(cr, 0, 0, width, height);
    cairo_fill(cr);
    cairo_pattern_destroy(sky);
}

// The size of the picture at the target, in world units: sets tile size and floor extent from
// the camera alone, so every cell of a contact sheet shows the same floor.
double viewSpanAtTarget(const Camera& camera) {
    return 2 * (camera.target - camera.eye).norm() * std::tan(camera.fovYDegrees * std::numbers::pi / 360.0);
}

void drawFloor(cairo_t* cr, const Projector& proj, const Camera& camera, double floorZ) {
    const double span = viewSpanAtTarget(camera);
    const double tile = std::exp2(std::ceil(std::log2(std::max(1.0, span / 10))));
    const double fadeEnd = 1.1 * span;
    const Vec2 centre(camera.target.x(), camera.target.y());
    const double i0 = std::floor((centre.x() - fadeEnd) / tile), i1 = std::ceil((centre.x() + fadeEnd) / tile);
    const double j0 = std::floor((centre.y() - fadeEnd) / tile), j1 = std::ceil((centre.y() + fadeEnd) / tile);

    cairo_push_group(cr);
    setColour(cr, kFloorLight);
    tracePolygon(cr, projectPolygon(proj, {{i0 * tile, j0 * tile, floorZ},
                                           {i1 * tile, j0 * tile, floorZ},
                                           {i1 * tile, j1 * tile, floorZ},
                                           {i0 * tile, j1 * tile, floorZ}}));
    cairo_fill(cr);
    setColour(cr, kFloorDark);
    for (double i = i0; i < i1; ++i) {
        for (double j = j0; j < j1; ++j) {
            if (std::fmod(std::abs(i + j), 2.0) != 0) continue;
            tracePolygon(cr, projectPolygon(proj, {{i * tile, j * tile, floorZ},
                                                   {(i + 1) * tile, j * tile, floorZ},
                                                   {(i + 1) * tile, (j + 1) * tile, floorZ},
                                                   {i * tile, (j + 1) * tile, floorZ}}));
            cairo_fill(cr);
        }
    }
    cairo_pop_group_to_source(cr);

    // Fade out with distance from the centre: a radial gradient on the ellipse that the circle of
    // radius fadeEnd projects to (approximately: perspective makes the true outline egg-shaped).
    const ViewBasis basis = viewBasis(camera.target - camera.eye);
    Vec3 ahead(basis.forward.x(), basis.forward.y(), 0), side(basis.right.x(), basis.right.y(), 0);
    if (ahead.squaredNorm() < 1e-12) ahead = Vec3::UnitX();
    ahead.normalize();
    side.normalize();
    const Vec3 c(centre.x(), centre.y(), floorZ);
    Vec2 near, far, left, right;
    if (!proj.segmentToPixels(proj.toView(c - fadeEnd * ahead), proj.toView(c + fadeEnd * ahead), near, far) ||
        !proj.segmentToPixels(proj.toView(c - fadeEnd * side), proj.toView(c + fadeEnd * side), left, right)) {
        cairo_paint(cr);
        return;
    }
    const double cx = 0.5 * (left.x() + right.x()), cy = 0.5 * (near.y() + far.y());
    const double rx = std::max(1.0, 0.5 * (right - left).norm());
    const double ry = std::max(1.0, 0.5 * std::abs(near.y() - far.y()));
    cairo_pattern_t* fade = cairo_pattern_create_radial(0, 0, 0, 0, 0, 1);
    cairo_pattern_add_color_stop_rgba(fade, 0.0, 0, 0, 0, 1);
    cairo_pattern_add_color_stop_rgba(fade, 0.45, 0, 0, 0, 1);
    cairo_pattern_add_color_stop_rgba(fade, 1.0, 0, 0, 0, 0);
    cairo_matrix_t m;
    cairo_matrix_init_scale(&m, 1 / rx, 1 / ry);
    cairo_matrix_translate(&m, -cx, -cy);
    cairo_pattern_set_matrix(fade, &m);
    cairo_mask(cr, fade);
    cairo_pattern_destroy(fade);
}

// Convex hull of points in the plane (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2> hull2d(std::vector<Vec2> p) {
    std::sort(p.begin(), p.end(),
              [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    if (p.size() < 3) return p;
    const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
        return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
    };
    std::vector<Vec2> h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

// The outline on the non-vertical plane normal · p = offset of the shadow cast straight down
// by the part of `body` above that plane; empty when nothing of it is above.
std::vector<Vec3> shadowOutline(const Polytope& body, const Vec3& normal, double offset) {
    std::vector<Vec2> footprint;
    for (const Vec3& v : body.vertices)
        if (normal.dot(v) >= offset) footprint.emplace_back(v.x(), v.y());
    std::vector<Vec3> outline;
    if (footprint.size() < 3) return outline;
    for (const Vec2& p : hull2d(footprint))
        outline.emplace_back(p.x(), p.y(), (offset - normal.x() * p.x() - normal.y() * p.y()) / normal.z());
    return outline;
}

// Shadows straight down onto a floor or a brush's upward face: they tell how high each body is
// above it. The caller clips to the face.
void drawShadows(cairo_t* cr, const Projector& proj, std::span<const Polytope> bodies, const Vec3& normal,
                 double offset) {
    cairo_push_group(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    for (const Polytope& body : bodies) {
        const std::vector<Vec3> outline = shadowOutline(body, normal, offset);
        if (outline.empty()) continue;
        tracePolygon(cr, projectPolygon(proj, outline));
        cairo_fill(cr);
    }
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, 0.18);
}

bool facesEye(const Polytope& p, const Face& f, const Vec3& eye) {
    return f.normal.squaredNorm() > 0.5 && f.normal.dot(eye - p.vertices[f.loop.front()]) > 0;
}

// A face at most this steep (normal.z ≥ the value) takes shadows: floors, step tops, ramps.
constexpr double kShadowedFaceMinNormalZ = 0.5;

// `shadowCasters`: bodies whose shadows fall on this polytope's upward faces (none for a body).
void drawPolytope(cairo_t* cr, const Projector& proj, const Polytope& p, const Colour& colour, double lineScale,
                  std::span<const Polytope> shadowCasters = {}) {
    std::vector<char> front(p.faces.size());
    std::vector<Vec3> world;
    for (size_t f = 0; f < p.faces.size(); ++f) {
        const Face& face = p.faces[f];
        front[f] = !face.loop.empty() && facesEye(p, face, proj.eye());
        if (!front[f]) continue;
        world.clear();
        for (int i : face.loop) world.push_back(p.vertices[i]);
        const std::vector<Vec2> pixels = projectPolygon(proj, world);
        tracePolygon(cr, pixels);
        setColour(cr, scaled(colour, brightness(face.normal)));
        // A hairline in the fill colour closes the antialiasing seams between adjacent faces.
        cairo_fill_preserve(cr);
        cairo_set_line_width(cr, 0.6 * lineScale);
        cairo_stroke(cr);
        if (!shadowCasters.empty() && face.normal.z() >= kShadowedFaceMinNormalZ) {
            cairo_save(cr);
            tracePolygon(cr, pixels);
            cairo_clip(cr);
            drawShadows(cr, proj, shadowCasters, face.normal, face.offset);
            cairo_restore(cr);
        }
    }
    // Outline the visible edges; an edge between a visible and a hidden face is on the silhouette.
    std::map<std::pair<int, int>, std::array<int, 2>> edgeFaces;
    for (size_t f = 0; f < p.faces.size(); ++f) {
        const std::vector<int>& loop = p.faces[f].loop;
        for (size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i], b = loop[(i + 1) % loop.size()];
            std::array<int, 2>& slot =
                edgeFaces.try_emplace({std::min(a, b), std::max(a, b)}, std::array<int, 2>{-1, -1}).first->second;
            slot[slot[0] < 0 ? 0 : 1] = static_cast<int>(f);
        }
    }
    setColour(cr, scaled(colour, 0.28), 0.9);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (const auto& [edge, faces] : edgeFaces) {
        const bool f0 = faces[0] >= 0 && front[faces[0]], f1 = faces[1] >= 0 && front[faces[1]];
        if (!f0 && !f1) continue;
        Vec2 a, b;
        const Vec3 from = proj.toView(p.vertices[edge.first]), to = proj.toView(p.vertices[edge.second]);
        if (!proj.segmentToPixels(from, to, a, b)) continue;
        cairo_new_path(cr);
        cairo_move_to(cr, a.x(), a.y());
        cairo_line_to(cr, b.x(), b.y());
        cairo_set_line_width(cr, (f0 != f1 ? 1.5 : 0.8) * lineScale);
        cairo_stroke(cr);
    }
}

Eigen::AlignedBox2d screenBox(const Projector& proj, const Polytope& p) {
    Eigen::AlignedBox2d box;
    for (const Vec3& v : p.vertices) {
        const Vec3 view = proj.toView(v);
        // Behind the camera the projection is meaningless; treat the object as covering all.
        if (view.z() < proj.nearDepth()) return Eigen::AlignedBox2d(Vec2(-1e30, -1e30), Vec2(1e30, 1e30));
        box.extend(proj.toPixels(view));
    }
    return box;
}

}  // namespace

void drawScene(cairo_t* cr, const RenderScene& scene, const Camera& camera, double width, double height) {
    const Projector proj(camera, width, height);
    cairo_save(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    drawBackground(cr, width, height);

    // A body of an exploded simulation (non-finite pose) is left out: the rest still shows.
    const auto finite = [](const RenderShape& s) { return s.pose.position.allFinite() && s.pose.rotation.allFinite(); };
    std::vector<Polytope> shapes;
    std::vector<Colour> colours;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const RenderShape& s = scene.bodies[i];
        if (!finite(s)) continue;
        shapes.push_back(transformed(s.shape, s.pose.rotation, s.pose.position));
        colours.push_back(s.colour.value_or(bodyColour(static_cast<int>(i))));
    }
    const size_t bodyCount = shapes.size();
    for (const RenderShape& s : scene.statics) {
        if (!finite(s)) continue;
        shapes.push_back(transformed(s.shape, s.pose.rotation, s.pose.position));
        colours.push_back(s.colour.value_or(kStaticColour));
    }

    const std::span<const Polytope> bodies(shapes.data(), bodyCount);
    // The floor plane is behind everything above it, so it goes first; seen from below it is hidden.
    if (scene.floorZ && camera.eye.z() > *scene.floorZ) {
        drawFloor(cr, proj, camera, *scene.floorZ);
        drawShadows(cr, proj, bodies, Vec3::UnitZ(), *scene.floorZ);
    }

    std::vector<DepthItem> items;
    for (const Polytope& p : shapes) items.push_back({&p, screenBox(proj, p)});
    const double lineScale = std::max(0.75, height / 480);
    // A static's shadows go on right after it, so that whatever is drawn later covers them too.
    for (int i : depthOrder(items, camera.eye)) {
        const bool isStatic = static_cast<size_t>(i) >= bodyCount;
        drawPolytope(cr, proj, shapes[i], colours[i], lineScale, isStatic ? bodies : std::span<const Polytope>{});
    }
    drawOverlay(cr, proj, scene.overlay, lineScale);
    cairo_restore(cr);
}

}  // namespace detail

Colour bodyColour(int index) {
    static constexpr std::array<Colour, 10> palette = {{
        {0.29f, 0.53f, 0.82f},  // blue
        {0.91f, 0.52f, 0.20f},  // orange
        {0.36f, 0.68f, 0.38f},  // green
        {0.84f, 0.33f, 0.38f},  // red
        {0.58f, 0.44f, 0.78f},  // purple
        {0.88f, 0.76f, 0.28f},  // yellow
        {0.27f, 0.71f, 0.74f},  // teal
        {0.86f, 0.49f, 0.69f},  // pink
        {0.56f, 0.64f, 0.28f},  // olive
        {0.66f, 0.46f, 0.34f},  // brown
    }};
    const int n = static_cast<int>(palette.size());
    return palette[((index % n) + n) % n];
}

void writePng(const RenderScene& scene, const Camera& camera, int width, int height, const std::string& path) {
    detail::Canvas canvas = detail::makeCanvas(width, height);
    detail::drawScene(canvas.cr.get(), scene, camera, width, height);
    detail::savePng(canvas.surface.get(), path);
}

}  // namespace af::render
