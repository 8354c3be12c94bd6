// fitCamera: a 3/4 direction from which the statics hide as little of the bodies as possible, then
// the distance and aim that frame the points of interest.

#include "projection.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace af::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kFovYDegrees = 30;
constexpr double kFill        = 0.92;  // fraction of the image the framed points may span

struct ViewDirection {
    double azimuthDegrees, elevationDegrees;
};

// Tried in order; the first that hides the fewest body points wins. The first is the front-right
// view from above (Doom's +X is forward): a figure's visible sides and top read as distinct, and
// the light comes from that side. Then the same from the left, steeper views that see over
// nearby brushes, the far side, and last from almost straight above, which only a ceiling blocks.
constexpr std::array<ViewDirection, 9> kViews = {{
    {-50, 30}, {-130, 30}, {-50, 55}, {-130, 55}, {50, 30}, {130, 30}, {50, 55}, {130, 55}, {-50, 85},
}};

// A sight line that runs this far (units) inside a static is blocked; less is a graze along a
// surface the body rests on.
constexpr double kBlockedLength = 0.25;
// Sight points sit this fraction of the way from a body's vertices to its centre, so that a
// vertex sunk slightly into the floor it rests on does not count as hidden.
constexpr double kSightInset = 0.25;

Vec3 directionToEye(const ViewDirection& view) {
    const double az = view.azimuthDegrees * kDegree;
    const double el = view.elevationDegrees * kDegree;
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

bool finitePose(const RenderShape& s) { return s.pose.position.allFinite() && s.pose.rotation.allFinite(); }

// What the camera is fitted to, in world space, over every scene it must show.
struct Subject {
    std::vector<Vec3>                bodyPoints;   // vertices of every drawable body
    std::vector<Vec3>                sightPoints;  // inside the bodies, where sight lines end
    std::vector<Polytope>            statics;
    std::vector<Eigen::AlignedBox3d> staticBounds;
    std::vector<Real>                floors;
};

bool sameStatics(const RenderScene& a, const RenderScene& b) {
    const auto same = [](const RenderShape& x, const RenderShape& y) {
        return x.shape.vertices == y.shape.vertices && x.pose.position == y.pose.position &&
               x.pose.rotation == y.pose.rotation;
    };
    return std::equal(a.statics.begin(), a.statics.end(), b.statics.begin(), b.statics.end(), same);
}

Subject subjectOf(const std::vector<const RenderScene*>& scenes) {
    Subject subject;
    for (const RenderScene* s : scenes) {
        // An exploded body is not drawn, so not framed.
        for (const RenderShape& b : s->bodies) {
            if (!finitePose(b) || b.shape.vertices.empty()) continue;
            const size_t first = subject.bodyPoints.size();
            Vec3 centre = Vec3::Zero();
            for (const Vec3& v : b.shape.vertices) {
                subject.bodyPoints.push_back(b.pose.apply(v));
                centre += subject.bodyPoints.back();
            }
            centre /= static_cast<double>(b.shape.vertices.size());
            subject.sightPoints.push_back(centre);
            for (size_t i = first; i < subject.bodyPoints.size(); ++i)
                subject.sightPoints.push_back(subject.bodyPoints[i] + kSightInset * (centre - subject.bodyPoints[i]));
        }
        if (s->floorZ) subject.floors.push_back(*s->floorZ);
        // The frames of a contact sheet share one world: its brushes need testing once.
        if (s != scenes.front() && sameStatics(*s, *scenes.front())) continue;
        for (const RenderShape& st : s->statics) {
            if (!finitePose(st)) continue;
            subject.statics.push_back(transformed(st.shape, st.pose.rotation, st.pose.position));
            Eigen::AlignedBox3d& bounds = subject.staticBounds.emplace_back();
            for (const Vec3& v : subject.statics.back().vertices) bounds.extend(v);
        }
    }
    return subject;
}

// The length of segment a–b inside the convex polytope p (Cyrus–Beck against its face planes).
double lengthInside(const Polytope& p, const Vec3& a, const Vec3& b) {
    double t0 = 0, t1 = 1;
    const Vec3 d = b - a;
    bool bounded = false;
    for (const Face& f : p.faces) {
        if (f.normal.squaredNorm() < 0.5) continue;  // a zero-area face has no plane
        bounded = true;
        const double outside = f.normal.dot(a) - f.offset;
        const double rate = f.normal.dot(d);
        if (rate == 0) {
            if (outside > 0) return 0;
            continue;
        }
        const double t = -outside / rate;
        if (rate < 0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 >= t1) return 0;
    }
    return bounded ? (t1 - t0) * d.norm() : 0;  // without a face plane there is no solid to block
}

// How many sight points the statics hide from `eye`; an eye inside a static sees none.
int hiddenCount(const Subject& subject, const Vec3& eye) {
    int hidden = 0;
    for (const Vec3& q : subject.sightPoints) {
        const Eigen::AlignedBox3d sight(eye.cwiseMin(q), eye.cwiseMax(q));
        for (size_t i = 0; i < subject.statics.size(); ++i) {
            if (!subject.staticBounds[i].intersects(sight)) continue;
            if (lengthInside(subject.statics[i], eye, q) > kBlockedLength) {
                ++hidden;
                break;
            }
        }
    }
    return hidden;
}

// Sutherland–Hodgman: the part of a convex polygon inside an axis-aligned box.
std::vector<Vec3> clipToBox(std::vector<Vec3> polygon, const Eigen::AlignedBox3d& box) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const double limit = side == 0 ? box.min()[axis] : box.max()[axis];
            const auto inside = [&](const Vec3& p) { return side == 0 ? p[axis] >= limit : p[axis] <= limit; };
            std::vector<Vec3> out;
            for (size_t i = 0; i < polygon.size(); ++i) {
                const Vec3& a = polygon[i];
                const Vec3& b = polygon[(i + 1) % polygon.size()];
                if (inside(a)) out.push_back(a);
                if (inside(a) != inside(b)) out.push_back(a + (limit - a[axis]) / (b[axis] - a[axis]) * (b - a));
            }
            polygon = std::move(out);
        }
    }
    return polygon;
}

// The points a picture from direction `back` must show: every body, and around the bodies a
// margin of floor, and of the brushes' faces turned towards the camera, so that a lying figure is
// seen on something. Only that margin of a brush counts, since a floor brush may be thousands of
// units wide. Without bodies, the statics are framed whole.
std::vector<Vec3> pointsOfInterest(const Subject& subject, const Vec3& back) {
    std::vector<Vec3> points = subject.bodyPoints;
    if (points.empty()) {
        for (const Polytope& p : subject.statics) points.insert(points.end(), p.vertices.begin(), p.vertices.end());
        return points;
    }
    Eigen::AlignedBox3d bodies;
    for (const Vec3& p : points) bodies.extend(p);
    const double margin = 8 + 0.15 * bodies.sizes().head<2>().maxCoeff();
    const Eigen::AlignedBox3d near(bodies.min() - Vec3::Constant(margin), bodies.max() + Vec3::Constant(margin));
    for (Real z : subject.floors)
        for (double x : {near.min().x(), near.max().x()})
            for (double y : {near.min().y(), near.max().y()}) points.emplace_back(x, y, z);
    std::vector<Vec3> face;
    for (const Polytope& p : subject.statics) {
        for (const Face& f : p.faces) {
            if (f.normal.dot(back) <= 0) continue;  // turned away (or zero area): not seen
            face.clear();
            for (int i : f.loop) face.push_back(p.vertices[i]);
            for (const Vec3& v : clipToBox(face, near)) points.push_back(v);
        }
    }
    return points;
}

Camera frame(const std::vector<Vec3>& points, const Vec3& back, double aspect) {
    Camera camera;
    camera.fovYDegrees = kFovYDegrees;
    if (points.empty()) {
        camera.target = Vec3::Zero();
        camera.eye = camera.target + 200 * back;
        return camera;
    }
    Eigen::AlignedBox3d bounds;
    for (const Vec3& p : points) bounds.extend(p);
    const detail::ViewBasis basis = detail::viewBasis(-back);
    const double tanV = std::tan(0.5 * kFovYDegrees * kDegree) * kFill;
    const double tanH = tanV * aspect;
    const double minDistance = std::max(1.0, 0.5 * bounds.diagonal().norm());
    Vec3 target = bounds.center();
    double distance = minDistance;
    // Each pass: the distance at which every point fits, then re-aim at the centre of the
    // projected points. Perspective makes the two depend on each other; three passes settle it.
    for (int pass = 0; pass < 3; ++pass) {
        distance = minDistance;
        for (const Vec3& p : points) {
            const Vec3 d = p - target;
            const double x = d.dot(basis.right), y = d.dot(basis.up), z = d.dot(basis.forward);
            distance = std::max({distance, std::abs(x) / tanH - z, std::abs(y) / tanV - z});
        }
        const Vec3 eye = target + distance * back;
        double xMin = std::numeric_limits<double>::max(), xMax = -xMin, yMin = xMin, yMax = -xMin;
        for (const Vec3& p : points) {
            const Vec3 d = p - eye;
            const double z = d.dot(basis.forward);
            const double x = d.dot(basis.right) / z, y = d.dot(basis.up) / z;
            xMin = std::min(xMin, x), xMax = std::max(xMax, x);
            yMin = std::min(yMin, y), yMax = std::max(yMax, y);
        }
        target += distance * (0.5 * (xMin + xMax) * basis.right + 0.5 * (yMin + yMax) * basis.up);
    }
    camera.target = target;
    camera.eye = target + distance * back;
    return camera;
}

Camera fit(const std::vector<const RenderScene*>& scenes, double aspect) {
    const Subject subject = subjectOf(scenes);
    Camera best;
    int bestHidden = std::numeric_limits<int>::max();
    for (const ViewDirection& view : kViews) {
        const Vec3 back = directionToEye(view);
        const Camera camera = frame(pointsOfInterest(subject, back), back, aspect);
        const int hidden = subject.sightPoints.empty() ? 0 : hiddenCount(subject, camera.eye);
        if (hidden < bestHidden) {
            best = camera;
            bestHidden = hidden;
        }
        if (hidden == 0) break;
    }
    return best;
}

}  // namespace

Camera fitCamera(const RenderScene& scene, double aspect) { return fit({&scene}, aspect); }

Camera fitCamera(const std::vector<RenderScene>& frames, double aspect) {
    std::vector<const RenderScene*> scenes;
    for (const RenderScene& s : frames) scenes.push_back(&s);
    return fit(scenes, aspect);
}

}  // namespace af::render
