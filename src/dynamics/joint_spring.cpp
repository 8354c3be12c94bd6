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

namespace {

// Doom's force on A at pA (−force on B at pB).
Vec3 doomSpringForce(const Joint& joint, const joint_detail::Pair& pair, const Vec3& pA, const Vec3& pB) {
    const Vec3 delta = pB - pA;
    const Real d2 = delta.squaredNorm();
    if (d2 == 0) return Vec3::Zero();
    const Real damp = joint.spring.damping * std::fabs((pair.b.velocityAt(pB) - pair.a.velocityAt(pA)).dot(delta)) / d2;
    const Real length = std::sqrt(d2);
    const Vec3 u = delta / length;
    const SpringParameters& s = joint.spring;
    if (length > s.restLength) {
        if (s.stretch > 0) return u * (s.stretch * (length - s.restLength) * (length - s.restLength) - damp);
    } else if (s.compress > 0) {
        return -u * (s.compress * (s.restLength - length) * (s.restLength - length) - damp);
    }
    return Vec3::Zero();
}

// 1 / (u·M⁻¹u) of the two anchors along u: the mass the spring moves.
Real massAlong(const Joint& joint, std::span<const RigidBody> bodies, const Vec3& pA, const Vec3& pB, const Vec3& u) {
    Real inverse = 0;
    const auto add = [&](int body, const Vec3& anchor) {
        if (body == kWorldBody) return;
        const RigidBody& b = bodies[static_cast<std::size_t>(body)];
        const Vec3 arm = (anchor - b.position).cross(u);
        inverse += b.inverseMass + arm.dot(b.inverseInertiaWorld() * arm);
    };
    add(joint.bodyA, pA);
    add(joint.bodyB, pB);
    return inverse > 0 ? 1 / inverse : 0;
}

void applyForce(const Joint& joint, std::span<RigidBody> bodies, const Vec3& pA, const Vec3& pB, const Vec3& force) {
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

}  // namespace

// Doom's law uncapped: the capped one's dt of 0.
void applySpringForces(const Joint& joint, std::span<RigidBody> bodies) { applySpringForces(joint, bodies, 0); }

// Doom integrates the force explicitly, which holds while the spring's stiffness at its
// displacement x, dF/dx = 2·k·x for F = k·x², stays below 4·m/dt² (m the mass it moves along
// its line: ω·dt < 2 for the step's symplectic Euler). Past that each swing overshoots the last
// and the energy grows without bound (the soak's lamps, springs stiffened up to a million times:
// kinetic energy 11 to 26 times what the start and gravity could supply). The cap F ≤ m·x/dt²
// keeps Doom's law at most at 2·m/dt² (ω·dt = √2, room for the mass and lever changing within
// the step) and the capped force itself at m/dt² (ω·dt = 1). Such a spring pulls as hard as the
// step can follow and sags further than Doom's law says; Doom's own lamp at 1/60 s reaches 0.74
// of the cap.
void applySpringForces(const Joint& joint, std::span<RigidBody> bodies, Real dt) {
    if (joint.type != ConstraintType::Spring) return;
    const joint_detail::Pair pair = joint_detail::pairOf(joint, bodies);
    const Vec3 pA = pair.a.point(joint.anchorA);
    const Vec3 pB = pair.b.point(joint.anchorB);
    Vec3 force = doomSpringForce(joint, pair, pA, pB);
    const Real magnitude = force.norm();
    if (magnitude == 0 || !(dt > 0)) return applyForce(joint, bodies, pA, pB, force);
    const Real x = std::fabs((pB - pA).norm() - joint.spring.restLength);
    const Real cap = massAlong(joint, bodies, pA, pB, force / magnitude) * x / (dt * dt);
    if (magnitude > cap) force *= cap / magnitude;
    applyForce(joint, bodies, pA, pB, force);
}

// Doom's law uncapped, as for the force.
Real springPotentialEnergy(const Joint& joint, std::span<const RigidBody> bodies) {
    return springPotentialEnergy(joint, bodies, 0);
}

// ∫₀ˣ min(k·s², c·s) ds with c = m/dt² at the current pose: k·x³/3 up to the crossing s* = c/k,
// the capped force's c·s²/2 beyond it.
Real springPotentialEnergy(const Joint& joint, std::span<const RigidBody> bodies, Real dt) {
    if (joint.type != ConstraintType::Spring) return 0;
    const joint_detail::Pair pair = joint_detail::pairOf(joint, bodies);
    const Vec3 pA = pair.a.point(joint.anchorA);
    const Vec3 pB = pair.b.point(joint.anchorB);
    const Real length = (pB - pA).norm();
    const SpringParameters& s = joint.spring;
    const Real k = length > s.restLength ? s.stretch : s.compress;
    const Real x = std::fabs(length - s.restLength);
    if (!(dt > 0) || length == 0 || k <= 0) return k > 0 ? k * x * x * x / 3 : 0;
    const Real c = massAlong(joint, bodies, pA, pB, (pB - pA) / length) / (dt * dt);
    const Real crossing = c / k;
    if (x <= crossing) return k * x * x * x / 3;
    return k * crossing * crossing * crossing / 3 + c * (x * x - crossing * crossing) / 2;
}

}  // namespace af
