// Fixed joint and slider: both hold A's orientation relative to B (the orientation part of
// joint_parts.cpp, 3 rows); the fixed joint also holds A's centre of mass where B had it at spawn
// (the point part with rA = 0), the slider only off its axis.
//
// Fixed:  C = xA − pB (3 rows), pB = xB + RB·anchorB,  J_i = [ e_i │ 0 │ −e_i │ e_i × rB ]
//         C = 2 vec(qA ⊗ relative⁻¹ ⊗ qB⁻¹) (3 rows), see joint_parts.cpp.
//
// Slider: n = RB·axisB is the slide axis, e1 = RB·referenceB and e2 = n × e1 are ⟂ it, all
// carried by B; pA = xA + RA·anchorA (A's centre of mass), pB = xB + RB·anchorB (the point of
// the axis where pA was at spawn), d = pA − pB.
//     C_k = e_k·d
//     Cdot_k = (ωB × e_k)·d + e_k·(vA + ωA × rA − vB − ωB × rB)
//            = e_k·vA + ωA·(rA × e_k) − e_k·vB + ωB·(e_k × (pA − xB))
//     J_k = [ e_k │ rA × e_k │ −e_k │ e_k × (pA − xB) ]
// Doom stores the spawn offset in body1's frame but reads it in body2's (docs/doom-quirks.md item 7), so with
// differently oriented bodies it pulls towards the wrong line; here the offset is stored and
// read in B's frame. Doom's body2 rows also lack the lever arm e_k × (pA − xB), so they are
// exact only while B does not rotate; these are exact. The slider has no friction (docs/figures.md §3.8).

#include "joint_parts.h"

namespace af::joint_detail {

JointRowRange writeFixedRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    writePointRows(pair, pair.a.point(joint.anchorA), pair.b.point(joint.anchorB), settings.jointCfm, out);
    writeOrientationRows(pair, joint.relative, settings.jointCfm, out);
    JointRowRange range;
    range.equalityRows = 6;
    return range;
}

JointRowRange writeSliderRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    writeOrientationRows(pair, joint.relative, settings.jointCfm, out);
    const Vec3 pA = pair.a.point(joint.anchorA);
    const Vec3 d = pA - pair.b.point(joint.anchorB);
    const Vec3 rA = pA - pair.a.position;
    const Vec3 e1 = pair.b.direction(joint.referenceB);
    const Vec3 e2 = pair.b.direction(joint.axisB).cross(e1);
    for (const Vec3& e : {e1, e2})
        addRow(pair, [&] { return Jacobian{e, rA.cross(e), -e, e.cross(pA - pair.b.position)}; }, e.dot(d), -kInfinity,
               kInfinity, settings.jointCfm, out);
    JointRowRange range;
    range.equalityRows = 5;
    return range;
}

Real sliderOffAxisDistance(const Joint& joint, const Pair& pair) {
    const Vec3 d = pair.a.point(joint.anchorA) - pair.b.point(joint.anchorB);
    const Vec3 n = pair.b.direction(joint.axisB);
    return (d - d.dot(n) * n).norm();
}

}  // namespace af::joint_detail
