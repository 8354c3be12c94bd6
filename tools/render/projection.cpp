#include "projection.h"

#include <cmath>
#include <numbers>

namespace af::render::detail {

ViewBasis viewBasis(const Vec3& forward) {
    const Vec3 f = forward.normalized();
    // Looking straight up or down leaves +Z no use as "up"; the picture's up is then world +X.
    const Vec3 worldUp = std::abs(f.z()) > 0.999 ? Vec3::UnitX() : Vec3::UnitZ();
    const Vec3 right = f.cross(worldUp).normalized();
    return {right, right.cross(f), f};
}

Projector::Projector(const Camera& camera, double width, double height)
    : eye_(camera.eye), width_(width), height_(height) {
    Vec3 forward = camera.target - camera.eye;
    if (forward.squaredNorm() == 0) forward = -Vec3::UnitZ();
    basis_ = viewBasis(forward);
    const double halfFov = camera.fovYDegrees * std::numbers::pi / 360.0;
    focal_ = 0.5 * height / std::tan(halfFov);
    near_ = std::max(1e-3, 1e-3 * forward.norm());
}

Vec3 Projector::toView(const Vec3& world) const {
    const Vec3 d = world - eye_;
    return {d.dot(basis_.right), d.dot(basis_.up), d.dot(basis_.forward)};
}

Vec2 Projector::toPixels(const Vec3& view) const {
    return {0.5 * width_ + focal_ * view.x() / view.z(), 0.5 * height_ - focal_ * view.y() / view.z()};
}

std::vector<Vec2> Projector::polygonToPixels(const std::vector<Vec3>& view) const {
    std::vector<Vec2> out;
    const size_t n = view.size();
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = view[i];
        const Vec3& b = view[(i + 1) % n];
        const bool aIn = a.z() >= near_;
        const bool bIn = b.z() >= near_;
        if (aIn) out.push_back(toPixels(a));
        if (aIn != bIn) {
            const double s = (near_ - a.z()) / (b.z() - a.z());
            out.push_back(toPixels(a + s * (b - a)));
        }
    }
    return out;
}

bool Projector::segmentToPixels(Vec3 a, Vec3 b, Vec2& pa, Vec2& pb) const {
    if (a.z() < near_ && b.z() < near_) return false;
    if (a.z() < near_) a += (near_ - a.z()) / (b.z() - a.z()) * (b - a);
    if (b.z() < near_) b += (near_ - b.z()) / (a.z() - b.z()) * (a - b);
    pa = toPixels(a);
    pb = toPixels(b);
    return true;
}

}  // namespace af::render::detail
