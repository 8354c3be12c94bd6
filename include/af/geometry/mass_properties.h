#pragma once
// Exact mass properties of convex polytopes, and Doom 3's rules for turning them into a body's
// mass and inertia (docs/figures.md §3.3, §3.4; D3 idTraceModel::GetMassProperties,
// idAFBody::SetDensity, idPhysics_AF::BuildTrees).
//
// Frames and units: results are in the polytope's own frame (for an .af body, its body frame).
// Lengths in file units L; density in mass units M per L³; mass in M; inertia in M·L², about the
// centre of mass, with axes parallel to the polytope frame's axes. Inertia tensors follow the
// usual convention (Ixx = ∫ρ(y²+z²), Ixy = −∫ρxy), as Doom's do.

#include "af/geometry/polytope.h"

#include <span>
#include <vector>

namespace af {

/// Pure geometry: exact integrals over the solid, no fallbacks.
struct VolumeProperties {
    Real volume = 0;                   ///< L³, ≥ 0 for a consistently oriented polytope
    Vec3 centroid = Vec3::Zero();      ///< L; meaningless when volume is 0
    Mat3 unitInertia = Mat3::Zero();   ///< L⁵: inertia for density 1, about the centroid
};

/// Volume, centroid and density-1 inertia of a closed, consistently oriented polyhedron, exact up
/// to rounding. Faces need not be triangles; they are fanned from their first vertex.
VolumeProperties volumeProperties(const Polytope& polytope);

enum class MassStatus {
    ok,
    zeroVolume,       ///< flat shape: Doom's fallback was used
    nonPositiveMass,  ///< density·volume ≤ 0 or NaN: Doom's fallback was used (Doom warns)
};

/// A body's mass properties as Doom uses them.
struct MassProperties {
    Real       mass = 1;                        ///< M
    Vec3       centreOfMass = Vec3::Zero();     ///< L, in the polytope frame
    Mat3       inertia = Mat3::Identity();      ///< M·L², about centreOfMass
    MassStatus status = MassStatus::ok;
};

/// mass = density·volume and the inertia scaled by density. Doom's fallbacks: a flat polytope
/// (volume ≤ 1e-12·(largest bounding-box side)³; Doom tests for exactly 0) or a mass that is
/// ≤ 0 or NaN gives mass 1, centre of mass 0, identity inertia, with `status` saying why.
MassProperties massProperties(const Polytope& polytope, Real density);

/// Doom's inertiaScale: the product I·S (row-major 3×3 matrices, as written in the .af file;
/// for a diagonal S this scales the columns of I). Skipped when S is exactly the identity, as
/// in Doom. The result is not symmetric unless S commutes with I; Doom keeps it so, and so do we.
Mat3 applyInertiaScale(const Mat3& inertia, const Mat3& scale);

/// Factor that makes the masses sum to `totalMass`: totalMass / Σ mass. 1 when totalMass ≤ 0
/// (the .af default, "not forced") or when the sum is not positive.
Real totalMassScale(std::span<const MassProperties> bodies, Real totalMass);

/// Every body's mass and inertia multiplied by totalMassScale(bodies, totalMass); centres of
/// mass unchanged. Doom does this on every tree rebuild when a total mass is forced.
std::vector<MassProperties> rescaledToTotalMass(std::span<const MassProperties> bodies, Real totalMass);

/// Principal moments and axes, for reporting: inertia = axes · diag(moments) · axesᵀ, moments
/// ascending, axes a proper rotation (columns are the principal axes). Only the symmetric part
/// of `inertia` is used, which matters only after a non-commuting inertiaScale.
struct PrincipalInertia {
    Vec3 moments = Vec3::Zero();
    Mat3 axes = Mat3::Identity();
};
PrincipalInertia principalInertia(const Mat3& inertia);

}  // namespace af
