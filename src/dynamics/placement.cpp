// Placing a figure clear of the static world (placement.h).

#include "af/dynamics/placement.h"

#include "af/collision/narrowphase.h"

#include <vector>

namespace af {

Real staticOverlap(const Figure& figure, const RigidPose& placement, std::span<const Polytope> statics) {
    const Figure placed = placeFigure(figure, placement);
    std::vector<Polytope> shapes;
    std::vector<RigidPose> poses;
    for (const FigureBody& b : placed.bodies) {
        shapes.push_back(b.shape);
        poses.push_back(b.pose);
    }
    return deepestOverlap(shapes, poses, statics);
}

std::optional<RigidPose> liftedClear(const Figure& figure, RigidPose placement, std::span<const Polytope> statics,
                                     Real clearance, int tries) {
    for (int i = 0; i < tries; ++i) {
        const Real depth = staticOverlap(figure, placement, statics);
        if (depth <= 0) return placement;
        placement.position.z() += depth + clearance;
    }
    return std::nullopt;
}

}  // namespace af
