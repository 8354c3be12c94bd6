// Spring: an explicit force (Doom's law, docs/doom-physics.md §4.3) and one-sided rows keeping the length
// within [minLength, maxLength]. No equality rows.
//
// Length. pA = xA + rA and pB = xB + rB are the two anchors, Δ = pB − pA, L = |Δ|, û = Δ/L.
//     L̇ = û·(vB + ωB × rB − vA − ωA × rA)
//       = −û·vA − ωA·(rA × û) + û·vB + ωB·(rB × û)
// Minimum (minLength > 0):  C = L − minLength ≥ 0,  J = [ −û │ −rA × û │ û │ rB × û ]
// Maximum (maxLength > 0):  C = maxLength − L ≥ 0,  J = the negation.
// Written once C < settings.springLimitMargin, lo = 0 (Doom: only when past the limit).
//
// Force (Doom's, kept as it is, docs/doom-quirks.md item 8): with the anchor speeds vA, vB (0 for the world),
//     damp = damping·|(vB − vA)·Δ| / |Δ|²           (damping × |relative speed along û| / L)
//     L > restLength, stretch > 0:   F = û·(stretch·(L − restLength)² − damp)
//     L ≤ restLength, compress > 0:  F = −û·(compress·(restLength − L)² − damp)
// F acts on A at pA and −F on B at pB. The force is quadratic in the displacement and the
// damping term only ever subtracts from its magnitude (it can even flip it); it does not oppose
// the motion as viscous damping would.

#include "joint_parts.h"

namespace af::joint_detail {

Real springLengthOf(const Joint& joint, const Pair& pair) {
    return (pair.b.point(joint.anchorB) - pair.a.point(joint.anchorA)).norm();
}

JointRowRange writeSpringRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    JointRowRange range;
    const Vec3 pA = pair.a.point(joint.anchorA);
    const Vec3 pB = pair.b.point(joint.anchorB);
    const Vec3 delta = pB - pA;
    const Real length = delta.norm();
    if (length <= 0) return range;  // no direction to push along
    const Vec3 u = delta / length;
    const Vec3 rA = pA - pair.a.position;
    const Vec3 rB = pB - pair.b.position;
    const Jacobian lengthening{-u, -rA.cross(u), u, rB.cross(u)};

    const SpringParameters& s = joint.spring;
    if (s.minLength > 0 && length - s.minLength < settings.springLimitMargin) {
        addRow(pair, [&] { return lengthening; }, length - s.minLength, 0, kInfinity, settings.limitCfm, out);
        ++range.limitRows;
    }
    if (s.maxLength > 0 && s.maxLength - length < settings.springLimitMargin) {
        const auto shortening = [&] {
            return Jacobian{-lengthening.linearA, -lengthening.angularA, -lengthening.linearB, -lengthening.angularB};
        };
        addRow(pair, shortening, s.maxLength - length, 0, kInfinity, settings.limitCfm, out);
        ++range.limitRows;
    }
    return range;
}

}  // namespace af::joint_detail

namespace af {

void applySpringForces(const Joint& joint, std::span<RigidBody> bodies) {
    if (joint.type != ConstraintType::Spring) return;
    const joint_detail::Pair pair = joint_detail::pairOf(joint, bodies);
    const Vec3 pA = pair.a.point(joint.anchorA);
    const Vec3 pB = pair.b.point(joint.anchorB);
    const Vec3 delta = pB - pA;
    const Real d2 = delta.squaredNorm();
    if (d2 == 0) return;
    const Real damp = joint.spring.damping * std::fabs((pair.b.velocityAt(pB) - pair.a.velocityAt(pA)).dot(delta)) / d2;
    const Real length = std::sqrt(d2);
    const Vec3 u = delta / length;
    const SpringParameters& s = joint.spring;
    Vec3 force = Vec3::Zero();
    if (length > s.restLength) {
        if (s.stretch > 0) force = u * (s.stretch * (length - s.restLength) * (length - s.restLength) - damp);
    } else if (s.compress > 0) {
        force = -u * (s.compress * (s.restLength - length) * (s.restLength - length) - damp);
    }
    if (joint.bodyA != kWorldBody) {
        RigidBody& a = bodies[static_cast<std::size_t>(joint.bodyA)];
        a.force += force;
        a.torque += (pA - a.position).cross(force);
    }
    if (joint.bodyB != kWorldBody) {
        RigidBody& b = bodies[static_cast<std::size_t>(joint.bodyB)];
        b.force -= force;
        b.torque -= (pB - b.position).cross(force);
    }
}

Real springPotentialEnergy(const Joint& joint, std::span<const RigidBody> bodies) {
    if (joint.type != ConstraintType::Spring) return 0;
    const joint_detail::Pair pair = joint_detail::pairOf(joint, bodies);
    const Real length = joint_detail::springLengthOf(joint, pair);
    const SpringParameters& s = joint.spring;
    const Real x = std::fabs(length - s.restLength);
    return (length > s.restLength ? s.stretch : s.compress) * x * x * x / 3;
}

}  // namespace af
