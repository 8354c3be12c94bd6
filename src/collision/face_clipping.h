#pragma once
// Face contacts: an incident face clipped against the side planes of a reference face
// (Sutherland–Hodgman), every surviving point within the margin kept.
//
// Separations are measured along a given axis out of the reference shape. For a face axis that
// is the reference face's normal. For an edge-pair axis whose two shapes each have a face nearly
// square to it (a box tilted over a ledge: the exact axis is an edge pair, the touching region
// is the face), it is the edge-pair axis itself: the side planes then contain the axis, each
// point is paired with the point of the reference plane straight along the axis, and the deepest
// pair is the edge pair's own. One point would let such a box rock about it.

#include "placed_shape.h"

#include <vector>

namespace af::collision_detail {

// Among the faces with area around `vertex`, the one whose normal is most opposed to `direction`;
// −1 when there is none.
int mostOpposedFaceAround(const PlacedShape& shape, int vertex, const Vec3& direction);

// Appends the points of `incidentFace` clipped by `referenceFace`'s side planes to `out`: each
// midway between the incident face and the reference plane along `outward` (unit, pointing out of
// the reference shape, not square to the reference face), depth = how far it lies below that
// plane along `outward`. Nothing when the clipped polygon is empty or no point is within `margin`.
void clipFaces(const PlacedShape& reference, int referenceFace, const PlacedShape& incident, int incidentFace,
               const Vec3& outward, bool referenceIsB, Real margin, std::vector<Candidate>& out);

}  // namespace af::collision_detail
