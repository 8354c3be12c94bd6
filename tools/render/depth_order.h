#pragma once
// The painter's order of convex objects: which to draw first so that nearer ones cover farther ones.

#include "af/geometry/polytope.h"

#include <Eigen/Core>

#include <vector>

namespace af::render::detail {

/// An object to order: its world-space polytope and the pixel box it covers on the image.
struct DepthItem {
    const Polytope* shape = nullptr;
    Eigen::AlignedBox2d screenBox;
};

/// Indices of `items`, back to front as seen from `eye`.
///
/// Per object rather than per face: once back faces are culled, the front faces of one convex
/// polytope never overlap on screen, so only the order between objects matters. Two objects whose
/// pixel boxes overlap are ordered by a face plane of one that has the other on its outer side
/// (the one on the eye's side of that plane is nearer); that is exact for disjoint and touching
/// convex objects, including a body on a floor brush far larger than itself, where face-centre
/// depths fail. Interpenetrating objects (bodies overlapping at a joint) have no such plane and
/// fall back to centroid distance, as does any cycle.
std::vector<int> depthOrder(const std::vector<DepthItem>& items, const Vec3& eye);

}  // namespace af::render::detail
