#pragma once
// Contact manifolds: where two convex shapes touch, as the narrowphase reports it and the
// solver consumes it.
//
// Frames and units: every point and normal is in world space, lengths in file units (Doom
// units). A shape is a Polytope in its body frame placed by a RigidPose (body → world).
//
// Sign conventions: the normal points from shape B towards shape A (the direction in which A
// must move to separate), and `depth` is the penetration along it: > 0 overlapping, 0 touching,
// < 0 separated by −depth. Separated points are reported only within the query's margin, so
// that the solver can hold a gap closing within one step (speculative contacts).

#include "af/geometry/math.h"

#include <array>
#include <cstdint>

namespace af {

// A contact point of a manifold. `id` names the pair of features that made the point (for
// example the reference face and the incident vertex or clipped edge), so that the same point
// found again in the next step has the same id and its impulse can warm-start the solver.
struct ManifoldPoint {
    Vec3 point = Vec3::Zero();  // world, midway between the two surfaces
    Real depth = 0;             // penetration along the manifold normal (see above)
    std::uint32_t id = 0;
};

// Up to four points sharing one normal: a box lying flat on a face gets four, an edge two, a
// vertex one.
struct Manifold {
    static constexpr int kMaxPoints = 4;

    Vec3 normal = Vec3::UnitZ();  // world, unit, from B towards A
    int count = 0;
    std::array<ManifoldPoint, kMaxPoints> points{};

    bool empty() const { return count == 0; }
};

// An infinite plane n·p = offset; the solid side is n·p < offset (below a floor with n = +Z).
struct Plane {
    Vec3 normal = Vec3::UnitZ();  // unit
    Real offset = 0;
};

}  // namespace af
