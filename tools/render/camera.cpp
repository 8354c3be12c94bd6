// fitCamera: a fixed 3/4 direction, then the distance and aim that frame the points of interest.

#include "projection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace af::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Front-right of a figure facing +X, from above: both visible sides and the top read as distinct.
constexpr double kAzimuthDegrees   = -50;
constexpr double kElevationDegrees = 30;
constexpr double kFovYDegrees      = 30;
constexpr double kFill             = 0.92;  // fraction of the image the framed points may span

Vec3 directionToEye() {
    const double az = kAzimuthDegrees * kDegree;
    const double el = kElevationDegrees * kDegree;
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

void addShapePoints(const RenderShape& s, std::vector<Vec3>& points) {
    for (const Vec3& v : s.shape.vertices) {
        const Vec3 p = s.pose.apply(v);
        if (p.allFinite()) points.push_back(p);  // an exploded body is not drawn, so not framed
    }
}

// The points a picture of these scenes must show: every body, and around the bodies a margin of
// floor so that a lying figure is seen on something. Statics are framed only when there are no
// bodies, since a floor brush may be thousands of units wide.
std::vector<Vec3> pointsOfInterest(const std::vector<const RenderScene*>& scenes) {
    std::vector<Vec3> points;
    for (const RenderScene* s : scenes)
        for (const RenderShape& b : s->bodies) addShapePoints(b, points);
    if (points.empty()) {
        for (const RenderScene* s : scenes)
            for (const RenderShape& b : s->statics) addShapePoints(b, points);
        return points;
    }
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double margin = 8 + 0.15 * (hi - lo).head<2>().maxCoeff();
    for (const RenderScene* s : scenes) {
        if (!s->floorZ) continue;
        for (double x : {lo.x() - margin, hi.x() + margin})
            for (double y : {lo.y() - margin, hi.y() + margin}) points.emplace_back(x, y, *s->floorZ);
    }
    return points;
}

Camera frame(const std::vector<Vec3>& points, double aspect) {
    Camera camera;
    camera.fovYDegrees = kFovYDegrees;
    const Vec3 back = directionToEye();
    if (points.empty()) {
        camera.target = Vec3::Zero();
        camera.eye = camera.target + 200 * back;
        return camera;
    }
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const detail::ViewBasis basis = detail::viewBasis(-back);
    const double tanV = std::tan(0.5 * kFovYDegrees * kDegree) * kFill;
    const double tanH = tanV * aspect;
    const double minDistance = std::max(1.0, 0.5 * (hi - lo).norm());
    Vec3 target = 0.5 * (lo + hi);
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

}  // namespace

Camera fitCamera(const RenderScene& scene, double aspect) {
    return frame(pointsOfInterest({&scene}), aspect);
}

Camera fitCamera(const std::vector<RenderScene>& frames, double aspect) {
    std::vector<const RenderScene*> scenes;
    for (const RenderScene& s : frames) scenes.push_back(&s);
    return frame(pointsOfInterest(scenes), aspect);
}

}  // namespace af::render
