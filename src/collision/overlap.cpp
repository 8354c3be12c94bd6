// deepestOverlap (narrowphase.h): every shape against every static whose bounding box its own
// box meets, through the same narrowphase as the step's contacts.

#include "af/collision/narrowphase.h"

#include <algorithm>
#include <limits>

namespace af {

namespace {

struct Box {
    Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity()), hi = -lo;
    void add(const Vec3& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    bool meets(const Box& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

Box boxOf(const Polytope& shape, const RigidPose& pose) {
    Box box;
    for (const Vec3& v : shape.vertices) box.add(pose.position + pose.rotation * v);
    return box;
}

}  // namespace

Real deepestOverlap(std::span<const Polytope> shapes, std::span<const RigidPose> poses, std::span<const Polytope> statics) {
    std::vector<Box> staticBoxes;
    staticBoxes.reserve(statics.size());
    for (const Polytope& s : statics) staticBoxes.push_back(boxOf(s, RigidPose{}));
    Real deepest = 0;
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Box box = boxOf(shapes[i], poses[i]);
        for (std::size_t k = 0; k < statics.size(); ++k) {
            if (!box.meets(staticBoxes[k])) continue;
            const Manifold m = collide(shapes[i], poses[i], statics[k], RigidPose{}, 0);
            for (int p = 0; p < m.count; ++p) deepest = std::max(deepest, m.points[static_cast<std::size_t>(p)].depth);
        }
    }
    return deepest;
}

}  // namespace af
