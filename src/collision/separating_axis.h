#pragma once
// The separating-axis search of two convex polytopes: the candidate axes are the face normals of
// both and the cross products of their edges, which is complete for polytopes with volume (the
// minimum-translation direction of two overlapping ones is always among them). Each candidate is
// scored by the actual separation of the two shapes along it; the best one wins.
//
// Edge pairs are pruned on the Gauss map: an edge pair yields a face of the Minkowski difference
// only when the arcs of their normal cones cross (shape_features.h), and parallel edges share the
// crossing direction, so the search runs over pairs of edge directions and costs O(groups × edges)
// dot products rather than O(edges²) projections. Only edges without any face with area (a
// segment) are scored by projecting both shapes.

#include "placed_shape.h"

#include <limits>
#include <optional>

namespace af::collision_detail {

enum class AxisKind { none, faceA, faceB, edges, free };

struct SeparatingAxis {
    AxisKind kind = AxisKind::none;
    Vec3 normal = Vec3::UnitZ();                              // working frame, unit, from B towards A
    Real separation = -std::numeric_limits<Real>::infinity();  // along normal; > 0 separated
    int featureA = -1;  // face of A (faceA) or edge of A (edges)
    int featureB = -1;  // face of B (faceB) or edge of B (edges)
};

// The best axis. Within kLengthTolerance, a face beats an edge pair and the larger of two
// faces wins (A's on equal areas), so that near-ties resolve the same way every step. std::nullopt as soon as some axis
// separates the shapes by more than `margin`. kind == none when neither shape has a face with
// area nor a pair of non-parallel edges.
std::optional<SeparatingAxis> findBestAxis(const PlacedShape& a, const PlacedShape& b, Real margin);

}  // namespace af::collision_detail
