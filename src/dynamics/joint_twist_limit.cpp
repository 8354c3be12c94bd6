// Twist limit of a ball-and-socket joint (our extension; Doom's decl has none): how far the
// shaft body (A) has turned about its own shaft relative to B, once the swing is taken out.
//
// b = RA·limitShaft is A's shaft and c = RB·twistAxisB B's axis (the cone axis, or B's copy of
// the shaft at spawn). The swing is the shortest arc S(b→c); rA = RA·twistReferenceA ⟂ b and
// rB = RB·twistReferenceB ⟂ c are references that agree at spawn (rA = S(c→b)·rB). The twist is
// the angle from rB to S(b→c)·rA about c (the swing-twist decomposition's twist):
//     θ = atan2((rB × r')·c, rB·r'),   r' = S(b→c)·rA.
// Its rate is the relative angular velocity along the bisector-weighted axis
//     dθ/dt = (ωA − ωB)·k,   k = (b + c)/(1 + b·c),
// (along b and c alike when b = c, and no rate from a pure swing, ⟂ both); undefined only at
// b = −c, which a cone limit keeps away from.
//
// Rows, one-sided, written within the margin of a limit as the others are:
//     upper: C = α − θ ≥ 0,  J = [0 │ −k │ 0 │ k];   lower: C = α + θ ≥ 0,  J = [0 │ k │ 0 │ −k]

#include "joint_parts.h"

#include <algorithm>

namespace af::joint_detail {
namespace {


// The rotation taking unit `from` to unit `to` by the shortest arc, applied to v.
Vec3 alongShortestArc(const Vec3& from, const Vec3& to, const Vec3& v) {
    return Quat::FromTwoVectors(from, to) * v;
}

// θ = atan2(y, x), made (as its rate) only when a row may be written.
struct TwistState {
    Vec3 b, c;  // A's shaft and B's axis
    Real y = 0, x = 0;

    Real angle() const { return std::atan2(y, x); }
    Real roughAngle() const { return roughAtan2(y, x); }
    // k: dθ/dt = (ωA − ωB)·k.
    Vec3 rate() const { return (b + c) / std::max(Real(1e-9), 1 + b.dot(c)); }
};

TwistState twistState(const Joint& joint, const Pair& pair) {
    TwistState s;
    s.b = pair.a.direction(joint.limitShaft).normalized();
    s.c = pair.b.direction(joint.twistAxisB);
    const Vec3 swungBack = alongShortestArc(s.b, s.c, pair.a.direction(joint.twistReferenceA));
    const Vec3 reference = pair.b.direction(joint.twistReferenceB);
    s.y = reference.cross(swungBack).dot(s.c);
    s.x = reference.dot(swungBack);
    return s;
}

bool limited(const Joint& joint) { return joint.twistHalfAngle > 0 && joint.twistHalfAngle < kPi; }

}  // namespace

int writeTwistLimitRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    if (!settings.limits || !limited(joint)) return 0;
    const TwistState s = twistState(joint, pair);
    // Most writes find the twist far inside its limits and need no exact angle.
    if (surelyInside(s.roughAngle(), joint.twistHalfAngle - settings.limitMargin)) return 0;
    const Real angle = s.angle();
    int written = 0;
    const Real upper = joint.twistHalfAngle - angle;
    if (upper < settings.limitMargin) {
        addAngularRow(pair, [&] { return Vec3(-s.rate()); }, upper, 0, kInfinity, settings.limitCfm, out);
        ++written;
    }
    const Real lower = joint.twistHalfAngle + angle;
    if (lower < settings.limitMargin) {
        addAngularRow(pair, [&] { return s.rate(); }, lower, 0, kInfinity, settings.limitCfm, out);
        ++written;
    }
    return written;
}

Real twistLimitViolation(const Joint& joint, const Pair& pair) {
    if (!limited(joint)) return 0;
    return std::max(Real(0), std::fabs(twistState(joint, pair).angle()) - joint.twistHalfAngle);
}

Real twistAngleOf(const Joint& joint, const Pair& pair) { return twistState(joint, pair).angle(); }

}  // namespace af::joint_detail
