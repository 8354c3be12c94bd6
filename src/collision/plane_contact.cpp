// collideWithPlane(): every vertex of the polytope within the margin of the plane is a candidate;
// the reduction keeps four. Worked in the body frame, like collide().

#include "plane_contact.h"

#include "af/collision/narrowphase.h"

#include "manifold_reduction.h"
#include "shape_features.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace af {

using namespace collision_detail;

Manifold collideWithPlane(const Polytope& a, const RigidPose& poseA, const Plane& plane, Real margin) {
    margin = std::max(margin, Real(0));
    const Vec3 normal = poseA.rotation.transpose() * plane.normal;
    const Real offset = plane.offset - plane.normal.dot(poseA.position);

    std::vector<Candidate>& candidates = scratch().candidates;
    candidates.clear();
    for (int i = 0; i < int(a.vertices.size()); ++i) {
        const Vec3& v = a.vertices[i];
        const Real separation = normal.dot(v) - offset;
        if (separation <= margin) {
            candidates.push_back({v - Real(0.5) * separation * normal, -separation, std::uint32_t(i)});
        }
    }
    Manifold m = toWorldManifold(candidates, normal, poseA);
    m.normal = plane.normal;
    return m;
}

namespace {

// Candidates whose separations lie within `spread` of each other are apart across the plane by at
// least sqrt(gap² − spread²): two vertices are `gap` apart at least, and the normal takes no more
// than the difference of their separations from that. With spread < gap / 2 that is above
// 0.86 gap; with gap ≥ 1e-5 and the vertices and the plane within 1e6 units of the body's origin
// (so that rounding stays near 1e-9) it is far above the 1e-6 within which the reduction merges
// points: four candidates or fewer would all be kept, the deepest first.
bool apartAcross(const ShapeFeatures& f, Real spread, Real offset) {
    constexpr Real kMinGap = 1e-5, kNear = 1e6;
    return f.vertexGap >= kMinGap && spread < Real(0.5) * f.vertexGap && f.vertexReach <= kNear &&
           std::abs(offset) <= kNear;
}

}  // namespace

bool collision_detail::smallPlaneContact(const ConvexShape& a, const RigidPose& poseA, const Plane& plane,
                                         Real margin, Manifold& out) {
    const std::vector<Vec3>& vertices = a.polytope().vertices;
    assert(vertices.size() <= std::size_t(kSmallPolytope));
    margin = std::max(margin, Real(0));
    const Vec3 normal = poseA.rotation.transpose() * plane.normal;
    const Real offset = plane.offset - plane.normal.dot(poseA.position);

    std::array<Candidate, kSmallPolytope> candidates;
    int n = 0, deepest = 0;
    Real lowest = 0, highest = 0;
    for (int i = 0; i < int(vertices.size()); ++i) {
        const Vec3& v = vertices[i];
        const Real separation = dot3(normal, v) - offset;
        if (separation <= margin) {
            if (n == 0 || separation < lowest) {
                deepest = n;
                lowest = separation;
            }
            highest = n == 0 ? separation : std::max(highest, separation);
            candidates[n++] = {v - Real(0.5) * separation * normal, -separation, std::uint32_t(i)};
        }
    }
    std::array<int, 4> picked;
    if (n > 0 && n <= 4 && apartAcross(a.features(), highest - lowest, offset)) {
        picked[0] = deepest;
        for (int i = 0, k = 1; i < n; ++i) {
            if (i != deepest) {
                picked[k++] = i;
            }
        }
        out.count = n;
    } else {
        out.count = reduceToFour({candidates.data(), std::size_t(n)}, normal, picked);
    }
    out.normal = plane.normal;
    for (int k = 0; k < Manifold::kMaxPoints; ++k) {
        if (k < out.count) {
            const Candidate& c = candidates[picked[k]];
            out.points[k] = {poseA.apply(c.point), c.depth, c.id};
        } else {
            out.points[k] = {};
        }
    }
    return out.count > 0;
}

}  // namespace af
