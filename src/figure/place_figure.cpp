// Placing a figure and building one from resolved resources (figure.h). A figure is built once in
// model space and placed for each instance (docs/figures.md §3.9: Doom rotates the whole figure
// about the world origin, then translates it); placing moves every world-space vector it holds.

#include "af/figure/figure.h"
#include "af/text/resource_index.h"

#include <algorithm>
#include <limits>

namespace af {

Figure placeFigure(const Figure& figure, const RigidPose& placement) {
    Figure placed = figure;
    placed.placement = placement * figure.placement;
    for (FigureBody& b : placed.bodies) b.pose = placement * b.pose;
    const Mat3& r = placement.rotation;
    for (FigureConstraint& c : placed.constraints) {
        c.anchor = placement.apply(c.anchor);
        c.anchor2 = placement.apply(c.anchor2);
        c.axis = r * c.axis;
        c.shafts[0] = r * c.shafts[0];
        c.shafts[1] = r * c.shafts[1];
        c.limitAxis = r * c.limitAxis;
    }
    return placed;
}

Skeleton afPoseSkeleton(const AFResources& resources) {
    Vec3 offset = Vec3::Zero();
    if (resources.model && resources.model->offset) {
        const Real3& o = *resources.model->offset;
        offset = Vec3(o[0], o[1], o[2]);
    }
    return skeletonFromMd5Anim(*resources.afPose.anim, 0, offset);
}

FigureResult buildFigure(const AFResources& resources) {
    return buildFigure(resources.figure->decl, afPoseSkeleton(resources), resources.figure->file);
}

HeightRange heightRange(const Figure& figure, const RigidPose& placement) {
    HeightRange range{std::numeric_limits<Real>::infinity(), -std::numeric_limits<Real>::infinity()};
    for (const FigureBody& b : figure.bodies) {
        const RigidPose pose = placement * b.pose;
        for (const Vec3& v : b.shape.vertices) {
            const Real z = pose.apply(v).z();
            range.lowest = std::min(range.lowest, z);
            range.highest = std::max(range.highest, z);
        }
    }
    return range;
}

}  // namespace af
