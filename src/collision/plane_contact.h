#pragma once
// The polytope–plane contact of collideWithPlane() for prepared shapes of at most kSmallPolytope
// vertices (a box), written straight into the caller's manifold: the collision world asks it for
// every body lying on the ground in every search, so it keeps its candidates on the stack, returns
// no manifold by value, and where the shape's vertex gap shows its few candidates to be apart
// across the plane, takes them as they are instead of reducing them. Same arithmetic in the same
// order as collideWithPlane(), hence the same manifold bit for bit (the points past `count` zero,
// as in a new Manifold).

#include "af/collision/narrowphase.h"

namespace af::collision_detail {

// `a` has at most kSmallPolytope vertices. Returns whether `out` has points.
bool smallPlaneContact(const ConvexShape& a, const RigidPose& poseA, const Plane& plane, Real margin, Manifold& out);

}  // namespace af::collision_detail
