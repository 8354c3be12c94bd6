// Rows shared by several joint types.
//
// Point part (ball, universal, hinge, fixed). pA = xA + rA and pB = xB + rB are the two bodies'
// copies of the anchor, rA = RA·anchorA, rB = RB·anchorB.
//     C = pA − pB  (three rows, one per world axis e_i; e_i is constant, so the rows are exact)
//     Cdot_i = e_i·(vA + ωA × rA − vB − ωB × rB)
//     J_i = [ e_i │ rA × e_i │ −e_i │ e_i × rB ]        (using e·(ω × r) = ω·(r × e))
//
// Orientation part (fixed, slider). With `relative` A's spawn orientation in B's frame, the
// error rotation E = qA ⊗ relative⁻¹ ⊗ qB⁻¹ is the identity when A keeps its spawn orientation
// relative to B. Write E = (w, v). With q̇ = ½ ω ⊗ q (ω world) for A and d(qB⁻¹)/dt =
// −½ qB⁻¹ ⊗ ωB, Ė = ½ ωA ⊗ E − ½ E ⊗ ωB, whose vector part is
//     v̇ = ½ (w I − [v]×) ωA − ½ (w I + [v]×) ωB.
//     C = 2 v (≈ the rotation vector for small errors), three rows along the world axes,
//     J_i = [ 0 │ row i of (w I − [v]×) │ 0 │ −row i of (w I + [v]×) ]
// Exact at any error; at E = I it is the familiar [0 │ I │ 0 │ −I]. E and −E are the same
// rotation; w ≥ 0 is kept so the error is the short way round.
//
// Angular friction part: Cdot = (ωA − ωB)·d, J = [0 │ d │ 0 │ −d], boxed by ±f·|λ_prev|, no
// position error.

#include "joint_parts.h"

#include <algorithm>

namespace af::joint_detail {

namespace {

// Every member set once: a side is made twice for every joint every time its rows are written or
// measured.
Side bodySide(int index, const RigidBody& body, const Mat3& rotation, const Mat3& inverseInertia) {
    return Side{index,
                body.position,
                body.orientation,
                rotation,
                body.linearVelocity,
                body.angularVelocity,
                body.inverseMass,
                inverseInertia};
}

// Everything but the inertia, which is `inverseInertia`.
Side kinematicSide(int index, std::span<const RigidBody> bodies, const Mat3& inverseInertia = Mat3::Zero()) {
    if (index == kWorldBody) return Side{};
    const RigidBody& body = bodies[static_cast<std::size_t>(index)];
    return bodySide(index, body, body.rotation(), inverseInertia);
}

}  // namespace

Side sideOf(int index, std::span<const RigidBody> bodies) {
    Side s = kinematicSide(index, bodies);
    if (index != kWorldBody)
        s.inverseInertia = s.rotation * bodies[static_cast<std::size_t>(index)].inverseInertia * s.rotation.transpose();
    return s;
}

Side sideOf(int index, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld) {
    if (index == kWorldBody) return Side{};
    return kinematicSide(index, bodies, inverseInertiaWorld[static_cast<std::size_t>(index)]);
}

Side sideOf(int index, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
           std::span<const Mat3> inverseInertiaWorld) {
    if (index == kWorldBody) return Side{};
    const std::size_t i = static_cast<std::size_t>(index);
    return bodySide(index, bodies[i], rotations[i], inverseInertiaWorld[i]);
}

Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies) {
    return {sideOf(joint.bodyA, bodies), sideOf(joint.bodyB, bodies)};
}

Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld) {
    return {sideOf(joint.bodyA, bodies, inverseInertiaWorld), sideOf(joint.bodyB, bodies, inverseInertiaWorld)};
}

Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
            std::span<const Mat3> inverseInertiaWorld) {
    return {sideOf(joint.bodyA, bodies, rotations, inverseInertiaWorld),
            sideOf(joint.bodyB, bodies, rotations, inverseInertiaWorld)};
}

Pair kinematicPairOf(const Joint& joint, std::span<const RigidBody> bodies) {
    return {kinematicSide(joint.bodyA, bodies), kinematicSide(joint.bodyB, bodies)};
}

Pair kinematicPairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations) {
    const auto side = [&](int index) {
        if (index == kWorldBody) return Side{};
        const std::size_t i = static_cast<std::size_t>(index);
        return bodySide(index, bodies[i], rotations[i], Mat3::Zero());
    };
    return {side(joint.bodyA), side(joint.bodyB)};
}

void addRow(const Pair& pair, const Jacobian& j, Real error, Real lo, Real hi, Real relativeCfm, ConstraintRows& out) {
    const bool againstWorld = pair.b.index == kWorldBody;
    const Vec3 linearB = againstWorld ? Vec3::Zero() : j.linearB;
    const Vec3 angularB = againstWorld ? Vec3::Zero() : j.angularB;
    const Real diagonal = pair.a.inverseMass * j.linearA.squaredNorm() + j.angularA.dot(pair.a.inverseInertia * j.angularA) +
                          pair.b.inverseMass * linearB.squaredNorm() + angularB.dot(pair.b.inverseInertia * angularB);
    out.appendMade(pair.a.index, pair.b.index, j.linearA, j.angularA, linearB, angularB, Real(0), error, lo, hi, -1,
                   Real(0), relativeCfm * diagonal);
}

// addRow's diagonal is (mA·0 + gᵀIA g) + mB·0 + (−g)ᵀIB(−g): the zero terms add nothing, and
// negating g negates IB g exactly.
void addAngularRow(const Pair& pair, const Vec3& g, Real error, Real lo, Real hi, Real relativeCfm,
                   ConstraintRows& out) {
    const bool againstWorld = pair.b.index == kWorldBody;
    const Vec3 angularB = againstWorld ? Vec3::Zero() : Vec3(-g);
    const Real diagonal = g.dot(pair.a.inverseInertia * g) + angularB.dot(pair.b.inverseInertia * angularB);
    out.appendMade(pair.a.index, pair.b.index, Vec3::Zero(), g, Vec3::Zero(), angularB, Real(0), error, lo, hi, -1,
                   Real(0), relativeCfm * diagonal);
}

Vec3 perpendicular(const Vec3& v) {
    // Doom's idVec3::OrthogonalBasis `left`: avoid the axis v is closest to, so the result is
    // well scaled. Doom's |z| > 0.7 branch has the signs of its last two components flipped and
    // is then not ⟂ v (unless v.x = 0); this is the orthogonal version of it.
    if (std::fabs(v.z()) <= Real(0.7)) {
        const Real s = std::sqrt(v.x() * v.x() + v.y() * v.y());
        return Vec3(-v.y(), v.x(), 0) / s;
    }
    const Real s = std::sqrt(v.y() * v.y() + v.z() * v.z());
    return Vec3(s, -v.x() * v.y() / s, -v.x() * v.z() / s);
}

Real wrapAngle(Real angle) {
    constexpr Real pi = std::numbers::pi_v<Real>;
    // Most angles are inside already (a hinge's angle from atan2 less a centre), where remainder
    // would return them unchanged: its libm call is made only for the others.
    if (angle > -pi && angle <= pi) return angle;
    angle = std::remainder(angle, 2 * pi);  // into [−π, π]
    return angle <= -pi ? angle + 2 * pi : angle;
}

Real roughAtan2(Real y, Real x) {
    constexpr Real pi = std::numbers::pi_v<Real>;
    const Real ax = std::fabs(x);
    const Real ay = std::fabs(y);
    const Real larger = std::max(ax, ay);
    if (larger == 0) return std::atan2(y, x);  // 0 or ±π, by the signs of the zeros
    const Real t = std::min(ax, ay) / larger;
    const Real t2 = t * t;
    Real a = t * (0.9998660 + t2 * (-0.3302995 + t2 * (0.1801410 + t2 * (-0.0851330 + t2 * 0.0208351))));
    if (ay > ax) a = pi / 2 - a;
    if (x < 0) a = pi - a;
    return std::signbit(y) ? -a : a;
}

namespace {

// v·(M v) for v with v[Skip] = 0: M v's two other entries and the dot of them, each sum in the
// order of Eigen's product and dot, whose terms with v[Skip] are zeros that change no sum's bits.
template <int Skip>
Real quadraticWithout(const Mat3& m, const Vec3& v) {
    constexpr int j = Skip == 0 ? 1 : 0;
    constexpr int k = Skip == 2 ? 1 : 2;
    const Real mj = m(j, j) * v[j] + m(j, k) * v[k];
    const Real mk = m(k, j) * v[j] + m(k, k) * v[k];
    return v[j] * mj + v[k] * mk;
}

// r × e_I for the world axis e_I, written out: the products with e_I's zeros are left out. The
// entry along e_I is an exact zero, possibly of the other sign than the full cross product's.
template <int I>
Vec3 crossAxis(const Vec3& r) {
    if constexpr (I == 0) return Vec3(0, r.z(), -r.y());
    if constexpr (I == 1) return Vec3(-r.z(), 0, r.x());
    return Vec3(r.y(), -r.x(), 0);
}

// The point row along the world axis e_I: J = [e_I │ rA × e_I │ −e_I │ e_I × rB]. addRow's row,
// with mA·|e|² + mB·|−e|² as mA + mB (|e|² = 1 exactly), which spares it two squared norms.
template <int I>
void writePointRow(const Pair& pair, const Vec3& rA, const Vec3& rB, Real error, Real relativeCfm, RowOut out) {
    out.add(error, -kInfinity, kInfinity, [&](ConstraintRows& rows) {
        const bool againstWorld = pair.b.index == kWorldBody;
        const Vec3 e = Vec3::Unit(I);
        const Vec3 angularA = crossAxis<I>(rA);
        const Vec3 linearB = againstWorld ? Vec3::Zero() : Vec3(-e);
        const Vec3 angularB = againstWorld ? Vec3::Zero() : Vec3(-crossAxis<I>(rB));
        const Real diagonal = pair.a.inverseMass + quadraticWithout<I>(pair.a.inverseInertia, angularA) +
                              pair.b.inverseMass + quadraticWithout<I>(pair.b.inverseInertia, angularB);
        rows.appendMade(pair.a.index, pair.b.index, e, angularA, linearB, angularB, Real(0), error, -kInfinity,
                        kInfinity, -1, Real(0), relativeCfm * diagonal);
    });
}

}  // namespace

void writePointRows(const Pair& pair, const Vec3& pointA, const Vec3& pointB, Real relativeCfm, RowOut out) {
    const Vec3 rA = pointA - pair.a.position;
    const Vec3 rB = pointB - pair.b.position;
    const Vec3 error = pointA - pointB;
    writePointRow<0>(pair, rA, rB, error.x(), relativeCfm, out);
    writePointRow<1>(pair, rA, rB, error.y(), relativeCfm, out);
    writePointRow<2>(pair, rA, rB, error.z(), relativeCfm, out);
}

Quat errorRotation(const Pair& pair, const Quat& relative) {
    Quat e = pair.a.orientation * relative.conjugate() * pair.b.orientation.conjugate();
    if (e.w() < 0) e.coeffs() = -e.coeffs();
    return e;
}

void writeOrientationRows(const Pair& pair, const Quat& relative, Real relativeCfm, RowOut out) {
    const Quat e = errorRotation(pair, relative);
    const Real w = e.w();
    const Vec3 v = e.vec();
    Mat3 skew;
    skew << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    const Mat3 ja = w * Mat3::Identity() - skew;
    const Mat3 jb = -(w * Mat3::Identity() + skew);
    for (int i = 0; i < 3; ++i)
        addRow(
            pair, [&] { return Jacobian{Vec3::Zero(), ja.row(i).transpose(), Vec3::Zero(), jb.row(i).transpose()}; },
            2 * v[i], -kInfinity, kInfinity, relativeCfm, out);
}

Real rotationAngle(const Quat& q) { return 2 * std::atan2(q.vec().norm(), std::fabs(q.w())); }

void writeAngularFrictionRow(const Pair& pair, const Vec3& axis, Real bound, Real relativeCfm, RowOut out) {
    addAngularRow(pair, [&] { return axis; }, 0, -bound, bound, relativeCfm, out);
}

Real frictionBound(const Joint& joint, const JointRowSettings& settings) {
    const Real friction = settings.forcedFriction > 0 ? settings.forcedFriction : joint.friction;
    if (!settings.friction || friction <= 0 || joint.lastImpulse <= 0) return 0;
    return friction * joint.lastImpulse;
}

}  // namespace af::joint_detail
