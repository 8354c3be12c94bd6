#include "placed_shape.h"

#include <algorithm>

namespace af::collision_detail {

int supportIndex(const PlacedShape& shape, const Vec3& dir) {
    const Vec3 d = shape.toOwn(dir);
    const std::vector<Vec3>& v = shape.polytope->vertices;
    int best = 0;
    Real bestDot = dot3(v[0], d);
    for (int i = 1; i < int(v.size()); ++i) {
        const Real x = dot3(v[i], d);
        if (x > bestDot) {
            best = i;
            bestDot = x;
        }
    }
    return best;
}

Real maxAlong(const PlacedShape& shape, const Vec3& dir) {
    const Vec3 d = shape.toOwn(dir);
    const std::vector<Vec3>& v = shape.polytope->vertices;
    Real best = dot3(v[0], d);
    for (size_t i = 1; i < v.size(); ++i) {
        best = std::max(best, dot3(v[i], d));
    }
    return best + dir.dot(shape.translation);
}

std::pair<Real, Real> interval(const PlacedShape& shape, const Vec3& dir) {
    const Vec3 d = shape.toOwn(dir);
    const std::vector<Vec3>& v = shape.polytope->vertices;
    Real lo = dot3(v[0], d), hi = lo;
    for (size_t i = 1; i < v.size(); ++i) {
        const Real x = dot3(v[i], d);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    const Real shift = dir.dot(shape.translation);
    return {lo + shift, hi + shift};
}

Real separationAlong(const PlacedShape& a, const PlacedShape& b, const Vec3& normal) {
    return -maxAlong(a, -normal) - maxAlong(b, normal);
}

Scratch& scratch() {
    thread_local Scratch buffers;
    return buffers;
}

}  // namespace af::collision_detail
