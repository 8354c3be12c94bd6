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
// area nor a pair of non-parallel edges. Two boxes take findBestBoxAxis, everything else
// findBestPolytopeAxis.
std::optional<SeparatingAxis> findBestAxis(const PlacedShape& a, const PlacedShape& b, Real margin);

// The search over any two polytopes, projecting vertices.
std::optional<SeparatingAxis> findBestPolytopeAxis(const PlacedShape& a, const PlacedShape& b, Real margin);

// The same answer for two boxes (features->box valid) from the closed forms of the box–box test:
// a face's separation from the other box's centre and radius, an edge pair's from the 3 × 3
// rotation between the boxes, its features as the support edges along the axis. Equal to
// findBestPolytopeAxis up to rounding wherever the best axis is unique.
std::optional<SeparatingAxis> findBestBoxAxis(const PlacedShape& a, const PlacedShape& b, Real margin);

// The tie rules above applied to the best face of A, the best face of B and the best edge pair
// (each kind none when absent); an edge pair's axis and separation are recomputed from its own
// two edges.
SeparatingAxis chooseAxis(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& faceA,
                          const SeparatingAxis& faceB, const SeparatingAxis& edges);

}  // namespace af::collision_detail
