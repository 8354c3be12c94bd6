#pragma once
// Reduction of contact candidates to the at most four points a manifold keeps: the deepest
// first (so the depth the solver sees is the true one), then the point farthest from it across the
// contact plane, then the one spanning the largest triangle with those two, then the one adding
// the most area outside that triangle. Area, not count, is what keeps a resting body from rocking.

#include "placed_shape.h"

#include <array>
#include <span>

namespace af::collision_detail {

// Indices into `candidates` in `picked`; returns how many (0 only when `candidates` is empty).
// Points closer than 1e-6 units across the plane count as one. `normal` is unit.
int reduceToFour(std::span<const Candidate> candidates, const Vec3& normal, std::array<int, 4>& picked);
// The same answer worked out in the contact plane's tangent coordinates for any set of candidates:
// what reduceToFour does unless it can see at once that all points are kept.
int reduceByArea(std::span<const Candidate> candidates, const Vec3& normal, std::array<int, 4>& picked);

// The manifold of the picked candidates, mapped from the working frame to the world by `pose`.
Manifold toWorldManifold(std::span<const Candidate> candidates, const Vec3& normal, const RigidPose& pose);

}  // namespace af::collision_detail
