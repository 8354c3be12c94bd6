#include "body_picker.h"

#include <limits>

namespace af::view {

namespace {

// The ray parameter at which it enters `shape`, or none.
std::optional<Real> enter(const render::RenderShape& body, const Ray& ray) {
    // Into the hull's frame, where its planes are written.
    const Vec3 origin = body.pose.rotation.transpose() * (ray.origin - body.pose.position);
    const Vec3 direction = body.pose.rotation.transpose() * ray.direction;
    Real lo = 0, hi = std::numeric_limits<Real>::infinity();
    bool faces = false;
    for (const Face& f : body.shape.faces) {
        if (f.normal.isZero()) continue;
        faces = true;
        const Real along = f.normal.dot(direction), gap = f.offset - f.normal.dot(origin);  // inside: gap ≥ 0
        if (std::abs(along) < 1e-12) {
            if (gap < 0) return std::nullopt;
        } else if (along < 0) {
            lo = std::max(lo, gap / along);
        } else {
            hi = std::min(hi, gap / along);
        }
        if (lo > hi) return std::nullopt;
    }
    if (!faces) return std::nullopt;
    return lo;
}

}  // namespace

std::optional<BodyHit> pickBody(const std::vector<render::RenderShape>& bodies, const Ray& ray) {
    std::optional<BodyHit> best;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const std::optional<Real> t = enter(bodies[i], ray);
        if (t && (!best || *t < best->distance)) best = BodyHit{int(i), ray.origin + *t * ray.direction, *t};
    }
    return best;
}

}  // namespace af::view
