// collideWithPlane(): every vertex of the polytope within the margin of the plane is a candidate;
// the reduction keeps four. Worked in the body frame, like collide().

#include "af/collision/narrowphase.h"

#include "manifold_reduction.h"

#include <algorithm>

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

}  // namespace af
