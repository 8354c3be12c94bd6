// Cardan (Hooke) universal joint, our extension (Doom's universalJoint is the homokinetic one of
// joint_universal.cpp): the point part, one row keeping the cross's arms ⟂, a one-sided row on
// each of its two angles near the ends of their ranges, and joint friction about the arms. The
// benchmark ragdoll's hips are such joints (docs/bench-scene.md §2), as ODE's and Bullet's are.
//
// Arms. a (on A) and b (on B), ⟂ at spawn, stay ⟂:
//     C = a·b,   Cdot = (ωA × a)·b + a·(ωB × b) = (ωA − ωB)·(a × b)
//     J = [0 │ a × b │ 0 │ −a × b]
//
// Angles. A's rotation relative to B is q = R(b, θ0)·R(a, θ1), with a, b and c = b × a taken at
// spawn. Seen from B, A's arm is q a = cos θ0 a + sin θ0 c; seen from A, B's arm is
// q⁻¹ b = cos θ1 b + sin θ1 c. With aB, cB the copies of a and c carried by B, and bA, cA those of
// b and c carried by A (all in world space now):
//     θ0 = atan2(y0, x0),  y0 = a·cB,  x0 = a·aB,   ẏ0 = (ωA − ωB)·(a × cB),  ẋ0 = (ωA − ωB)·(a × aB)
//     θ1 = atan2(y1, x1),  y1 = b·cA,  x1 = b·bA,   ẏ1 = (ωA − ωB)·(cA × b),  ẋ1 = (ωA − ωB)·(bA × b)
//     dθ/dt = (x ẏ − y ẋ)/(x² + y²) = (ωA − ωB)·g,
//     g0 = a × (x0 cB − y0 aB)/(x0² + y0²),   g1 = (x1 cA − y1 bA) × b/(x1² + y1²)
// These are docs/bench-scene.md's θ1 and θ2 of a universal joint (its a1 = b on the parent B, a2 = a
// on the child A). Each range [lower, upper] is a V limit as the hinge's (joint_hinge.cpp): with
// d = wrap(θ − centre), C = halfWidth − |d| ≥ 0, written once C < settings.limitMargin.
//
// Friction: two rows (ωA − ωB)·b and (ωA − ωB)·a, about the arms the cross turns on, boxed by
// ±f·|λ_prev|.

#include "joint_parts.h"

#include <algorithm>

namespace af::joint_detail {
namespace {


struct CrossState {
    Vec3 a, b;    // the arms
    Vec3 aB, cB;  // B's copies of A's arm and of b × a
    Vec3 bA, cA;  // A's copies of B's arm and of b × a
    Real x[2] = {0, 0}, y[2] = {0, 0};

    Real angle(int k) const { return std::atan2(y[k], x[k]); }
    // g of angle k, dθk/dt = (ωA − ωB)·g; zero where the angle is undefined (an arm along the
    // other's axis: the arms row is far off then, and the limit waits).
    Vec3 gradient(int k) const {
        const Real r2 = x[k] * x[k] + y[k] * y[k];
        if (!(r2 > Real(1e-18))) return Vec3::Zero();
        return k == 0 ? Vec3(a.cross(x[0] * cB - y[0] * aB) / r2) : Vec3((x[1] * cA - y[1] * bA).cross(b) / r2);
    }
};

CrossState crossState(const Joint& joint, const Pair& pair) {
    CrossState s;
    s.a = pair.a.direction(joint.axisA);
    s.b = pair.b.direction(joint.axisB);
    s.aB = pair.b.direction(joint.referenceB);
    s.cB = pair.b.direction(joint.cardan.crossB);
    s.bA = pair.a.direction(joint.referenceA);
    s.cA = pair.a.direction(joint.cardan.crossA);
    s.x[0] = s.a.dot(s.aB);
    s.y[0] = s.a.dot(s.cB);
    s.x[1] = s.b.dot(s.bA);
    s.y[1] = s.b.dot(s.cA);
    return s;
}

// Angle k's range as a V: its centre and half width; false when it has none.
bool rangeOf(const Joint& joint, int k, Real& centre, Real& halfWidth) {
    const Real lower = joint.cardan.lower[k], upper = joint.cardan.upper[k];
    if (!(lower < upper) || upper - lower >= 2 * kPi) return false;
    centre = (lower + upper) / 2;
    halfWidth = (upper - lower) / 2;
    return true;
}

}  // namespace

JointRowRange writeCardanRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    JointRowRange range;
    writePointRows(pair, pair.a.point(joint.anchorA), pair.b.point(joint.anchorB), settings.jointCfm, out);
    const CrossState s = crossState(joint, pair);
    addAngularRow(pair, [&] { return Vec3(s.a.cross(s.b)); }, s.a.dot(s.b), -kInfinity, kInfinity, settings.jointCfm, out);
    range.equalityRows = 4;
    for (int k = 0; k < 2; ++k) {
        Real centre = 0, halfWidth = 0;
        if (!settings.limits || !rangeOf(joint, k, centre, halfWidth)) continue;
        // As the hinge's: most writes find the angle far inside its range, without libm's atan2.
        if (surelyInside(wrapAngle(roughAtan2(s.y[k], s.x[k]) - centre), halfWidth - settings.limitMargin)) continue;
        const Real d = wrapAngle(s.angle(k) - centre);
        const Real c = halfWidth - std::fabs(d);
        if (c >= settings.limitMargin) continue;
        addAngularRow(pair, [&] { return Vec3((d < 0 ? 1 : -1) * s.gradient(k)); }, c, 0, kInfinity, settings.limitCfm, out);
        ++range.limitRows;
    }
    if (const Real bound = frictionBound(joint, settings); bound > 0) {
        writeAngularFrictionRow(pair, s.b, bound, settings.frictionCfm, out);
        writeAngularFrictionRow(pair, s.a, bound, settings.frictionCfm, out);
        range.frictionRows = 2;
    }
    return range;
}

std::array<Real, 2> cardanAnglesOf(const Joint& joint, const Pair& pair) {
    const CrossState s = crossState(joint, pair);
    return {s.angle(0), s.angle(1)};
}

Real cardanArmsError(const Joint& joint, const Pair& pair) {
    const CrossState s = crossState(joint, pair);
    return std::fabs(std::asin(std::clamp(s.a.dot(s.b), Real(-1), Real(1))));
}

Real cardanLimitViolation(const Joint& joint, const Pair& pair) {
    const std::array<Real, 2> angles = cardanAnglesOf(joint, pair);
    Real worst = 0;
    for (int k = 0; k < 2; ++k) {
        Real centre = 0, halfWidth = 0;
        if (rangeOf(joint, k, centre, halfWidth))
            worst = std::max(worst, std::fabs(wrapAngle(angles[static_cast<std::size_t>(k)] - centre)) - halfWidth);
    }
    return worst;
}

}  // namespace af::joint_detail
