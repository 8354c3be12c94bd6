// Hinge: the point part, two rows keeping the axes aligned, the V-shaped limit as a one-sided row
// on the hinge angle, and joint friction about the axis.
//
// Axis rows. hA (on A) and hB (on B) are the two copies of the axis; u1, u2 (on A) complete hA
// to an orthonormal basis. The axes are aligned when hB ⟂ u1 and hB ⟂ u2:
//     C_k = hB·u_k,   Cdot_k = (ωB × hB)·u_k + hB·(ωA × u_k) = (ωA − ωB)·(u_k × hB)
//     J_k = [0 │ u_k × hB │ 0 │ −u_k × hB]
// (Doom's error (hA × hB)·e_k is the same to first order.)
//
// Hinge angle. rA (on A) and rB (on B) are copies of one vector ⟂ the axis at spawn, tB = hB × rB.
// φ = atan2(x, y) with x = rA·tB, y = rA·rB is the right-handed angle of A relative to B about hB.
//     ẋ = (ωA − ωB)·(rA × tB),  ẏ = (ωA − ωB)·(rA × rB)
//     dφ/dt = (y ẋ − x ẏ)/(x² + y²) = (ωA − ωB)·g,  g = rA × (y tB − x rB)/(x² + y²)
// (g = hB when the axes are aligned.)
//
// V limit (docs/figures.md §3.8): allowed |d| ≤ halfWidth with d = wrap(φ − center).
//     C = halfWidth − |d|,  Cdot = −sign(d)·(ωA − ωB)·g,  J = [0 │ −sign(d) g │ 0 │ sign(d) g]
// written once C < settings.limitMargin, lo = 0. Doom builds the same limit as a cone around a
// limit direction cutting a V out of the plane the body1 shaft sweeps; joints.h gives the
// conversion of its three angles.
//
// Friction: one row (ωA − ωB)·hA, the same axis on both bodies so the friction torques are equal
// and opposite (Doom uses hA on body1 and hB on body2), boxed by ±f·|λ_prev|.

#include "joint_parts.h"

#include <algorithm>

namespace af::joint_detail {
namespace {


// x = rA·tB and y = rA·rB: φ = atan2(x, y).
struct AngleState {
    Vec3 rA, rB, tB;
    Real x = 0, y = 0;

    Real angle() const { return std::atan2(x, y); }
    // g, dφ/dt = (ωA − ωB)·g; made only for a row that is written. rA ∥ hB: the angle is
    // undefined; the axis rows are far off then and the limit waits.
    Vec3 gradient() const {
        const Real r2 = x * x + y * y;
        return r2 > Real(1e-18) ? Vec3(rA.cross(y * tB - x * rB) / r2) : Vec3::Zero();
    }
};

// hB = B's copy of the axis and rA = A's copy of the reference, which the axis rows have made.
AngleState angleState(const Joint& joint, const Pair& pair, const Vec3& hB, const Vec3& rA) {
    AngleState s;
    s.rA = rA;
    s.rB = pair.b.direction(joint.referenceB);
    s.tB = hB.cross(s.rB);
    s.x = s.rA.dot(s.tB);
    s.y = s.rA.dot(s.rB);
    return s;
}

AngleState angleState(const Joint& joint, const Pair& pair) {
    return angleState(joint, pair, pair.b.direction(joint.axisB), pair.a.direction(joint.referenceA));
}

}  // namespace

JointRowRange writeHingeRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    JointRowRange range;
    writePointRows(pair, pair.a.point(joint.anchorA), pair.b.point(joint.anchorB), settings.jointCfm, out);
    const Vec3 hA = pair.a.direction(joint.axisA);
    const Vec3 hB = pair.b.direction(joint.axisB);
    const Vec3 u1 = pair.a.direction(joint.referenceA);
    const Vec3 u2 = hA.cross(u1);
    for (const Vec3& u : {u1, u2}) {
        const Vec3 g = u.cross(hB);
        addAngularRow(pair, [&] { return g; }, hB.dot(u), -kInfinity, kInfinity, settings.jointCfm, out);
    }
    range.equalityRows = 5;

    if (settings.limits && joint.limit != LimitType::None && joint.hinge.halfWidth < kPi) {
        const AngleState s = angleState(joint, pair, hB, u1);
        // Most writes find the hinge far inside its V and need no exact angle (atan2 and wrap:
        // 0.4M of the bench drop's 273M instructions).
        const bool far = surelyInside(wrapAngle(roughAtan2(s.x, s.y) - joint.hinge.center),
                                      joint.hinge.halfWidth - settings.limitMargin);
        const Real d = far ? 0 : wrapAngle(s.angle() - joint.hinge.center);
        const Real c = joint.hinge.halfWidth - std::fabs(d);
        if (!far && c < settings.limitMargin) {
            const Vec3 g = (d < 0 ? 1 : -1) * s.gradient();
            addAngularRow(pair, [&] { return g; }, c, 0, kInfinity, settings.limitCfm, out);
            range.limitRows = 1;
        }
    }
    if (const Real bound = frictionBound(joint, settings); bound > 0) {
        writeAngularFrictionRow(pair, hA, bound, settings.frictionCfm, out);
        range.frictionRows = 1;
    }
    return range;
}

Real hingeAngleOf(const Joint& joint, const Pair& pair) { return angleState(joint, pair).angle(); }

Real hingeLimitViolation(const Joint& joint, const Pair& pair) {
    if (joint.limit == LimitType::None) return 0;
    const Real d = wrapAngle(angleState(joint, pair).angle() - joint.hinge.center);
    return std::max(Real(0), std::fabs(d) - joint.hinge.halfWidth);
}

}  // namespace af::joint_detail
