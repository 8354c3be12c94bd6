// Universal joint: the point part, one row against relative twist, a cone or pyramid limit on
// shaft 1, and joint friction about two axes ⟂ shaft 1.
//
// Twist row: homokinetic (constant velocity), the constraint Doom's row 3 aims at
// (docs/doom-physics.md §4.3), with an exact Jacobian. Let a = shaft1 (carried by A) and b = −shaft2
// (carried by B); a straight joint has a = b. Let p (on A, ⟂ a) and q (on B, ⟂ b) be the two copies
// of the cardan axis, equal at spawn. R = [a p a×p]·[b q b×q]ᵀ is the rotation taking B's pair
// (b, q) to A's pair (a, p).
// Split R = S·T into a swing S (the shortest rotation taking b to a) after a twist T about b.
// "No relative twist" is T = I. In quaternions, r = (w, v) = s ⊗ t with s's axis ⟂ b and
// t = (cos τ/2, sin τ/2 b), so v·b = cos(σ/2)·sin(τ/2) (σ the swing angle), which vanishes
// exactly at τ = 0 for any swing below 180°:
//     C = v·b
// r = qA ⊗ M ⊗ qB⁻¹ with M = joint.relative⁻¹ a constant; as for the orientation part,
// v̇ = ½ w (ωA − ωB) − ½ v × (ωA + ωB), and ḃ = ωB × b, so
//     Cdot = v̇·b + v·ḃ = (ωA − ωB)·½ (w b − b × v)
//     J = [0 │ ½ (w b − b × v) │ 0 │ −½ (w b − b × v)]
// At spawn with a straight joint (r = I) this is ½·[0 │ b │ 0 │ −b], Doom's [0 │ s1 │ 0 │ s2]
// up to the factor ½. A Cardan (Hooke) cross would be simpler (C = p·(q × b)), but its twist
// varies with the bend (4° at 30°), which a "no relative twist" test would see.
//
// Friction: two rows (ωA − ωB)·d_k with d_1, d_2 ⟂ shaft 1 (Doom's rows), boxed by ±f·|λ_prev|.

#include "joint_parts.h"

namespace af::joint_detail {
namespace {

struct TwistLock {
    Real error = 0;
    Vec3 gradient = Vec3::Zero();
};

TwistLock twistLock(const Joint& joint, const Pair& pair) {
    Quat r = pair.a.orientation * joint.relative.conjugate() * pair.b.orientation.conjugate();
    if (r.w() < 0) r.coeffs() = -r.coeffs();
    const Vec3 b = -pair.b.direction(joint.axisB);
    TwistLock s;
    s.error = r.vec().dot(b);
    s.gradient = Real(0.5) * (r.w() * b - b.cross(r.vec()));
    return s;
}

}  // namespace

JointRowRange writeUniversalRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings,
                                 RowOut out) {
    JointRowRange range;
    writePointRows(pair, pair.a.point(joint.anchorA), pair.b.point(joint.anchorB), settings.jointCfm, out);
    const TwistLock twist = twistLock(joint, pair);
    addAngularRow(pair, [&] { return twist.gradient; }, twist.error, -kInfinity, kInfinity, settings.jointCfm, out);
    range.equalityRows = 4;
    range.limitRows = writeShaftLimitRows(joint, pair, settings, out);
    if (const Real bound = frictionBound(joint, settings); bound > 0) {
        const Vec3 shaft = pair.a.direction(joint.axisA);
        const Vec3 d1 = perpendicular(shaft);
        writeAngularFrictionRow(pair, d1, bound, settings.frictionCfm, out);
        writeAngularFrictionRow(pair, shaft.cross(d1), bound, settings.frictionCfm, out);
        range.frictionRows = 2;
    }
    return range;
}

Real universalTwist(const Joint& joint, const Pair& pair) {
    // τ from v·b = cos(σ/2) sin(τ/2) and w = cos(σ/2) cos(τ/2).
    Quat r = pair.a.orientation * joint.relative.conjugate() * pair.b.orientation.conjugate();
    if (r.w() < 0) r.coeffs() = -r.coeffs();
    const Vec3 b = -pair.b.direction(joint.axisB);
    return 2 * std::atan2(r.vec().dot(b), r.w());
}

}  // namespace af::joint_detail
