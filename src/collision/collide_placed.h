#pragma once
// The narrowphase below collide(): the manifold of two shapes already placed in A's body frame
// (narrowphase.h says how it is found). Tests reach the polytope search through it by placing
// shapes whose features say nothing of boxes.

#include "separating_axis.h"

namespace af::collision_detail {

// The manifold in the world: poseA maps the working frame there, poseB is B's own pose (for its
// face normals). `margin` ≥ 0.
Manifold collidePlaced(const PlacedShape& a, const PlacedShape& b, const RigidPose& poseA, const RigidPose& poseB,
                       Real margin);

// Whether the shapes' distance equals the separation along `axis` (> 0), so that no direction
// separates them more and libccd could only confirm what the axis says: the closest vertex of the
// other shape lies over the axis's face (its height above the face plane is the separation), or
// the lines of the axis's two edges are closest within both edges.
bool separationIsDistance(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& axis);

}  // namespace af::collision_detail
