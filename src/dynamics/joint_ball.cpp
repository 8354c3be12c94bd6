// Ball-and-socket joint: the point part (joint_parts.cpp), a cone or pyramid limit on the shaft
// (joint_shaft_limits.cpp), a twist limit (joint_twist_limit.cpp) and joint friction.
//
//     C = pA − pB (3 rows),  J_i = [ e_i │ rA × e_i │ −e_i │ e_i × rB ]
//
// Joint friction: three rows on the relative angular velocity, J_k = [0 │ e_k │ 0 │ −e_k],
// boxed by ±f·|λ_prev|. Doom writes +e_k on body2 (docs/doom-physics.md §4.7, docs/doom-quirks.md item 6),
// which damps ωA + ωB: it brakes two bodies spinning together and pushes on two bodies turning against each
// other. We damp ωA − ωB, the motion of the joint itself, as for the universal joint and the hinge.

#include "joint_parts.h"

namespace af::joint_detail {

JointRowRange writeBallRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    JointRowRange range;
    writePointRows(pair, pair.a.point(joint.anchorA), pair.b.point(joint.anchorB), settings.jointCfm, out);
    range.equalityRows = 3;
    range.limitRows = writeShaftLimitRows(joint, pair, settings, out);
    range.limitRows += writeTwistLimitRows(joint, pair, settings, out);
    if (const Real bound = frictionBound(joint, settings); bound > 0) {
        for (int k = 0; k < 3; ++k) writeAngularFrictionRow(pair, Vec3::Unit(k), bound, settings.frictionCfm, out);
        range.frictionRows = 3;
    }
    return range;
}

}  // namespace af::joint_detail
