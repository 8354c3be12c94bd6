// Cone and pyramid limits on a shaft (ball and socket; universal on shaft 1), docs/figures.md §3.8,
// docs/doom-physics.md §4.3.
//
// b = RA·limitShaft is the limited shaft (carried by A); the limit's axes are carried by B.
// Every vector here is carried by one body, so its rate is ω × vector of that body, and for a
// vector b on A and a vector k on B:  d(b·k)/dt = (ωA − ωB)·(b × k).
//
// Cone (axis k, half angle α): θ = angle(b, k) = atan2(|b × k|, b·k).
//     C = α − θ ≥ 0
//     Rotating b about n = unit(b × k) turns it towards k, so dθ/dt = −(ωA − ωB)·n and
//     Cdot = (ωA − ωB)·n,   J = [0 │ n │ 0 │ −n]
// Doom instead writes a linear row at a point 32 units up the cone surface, with a bias towards
// the surface; the angular row is the same constraint without the arbitrary lever arm.
//
// Pyramid (basis e0, e1, e2 = axis; half angles α0, α1): for i = 0, 1 the shaft's projection onto
// the plane (e_i, e2) makes the angle ψ_i = atan2(x, z), x = b·e_i, z = b·e2, with e2.
//     C_i = α_i − |ψ_i| ≥ 0
//     dψ/dt = (z ẋ − x ż)/(x² + z²) = (ωA − ωB)·g,  g = b × (z e_i − x e2) / (x² + z²)
//     Cdot_i = −sign(ψ_i)·(ωA − ωB)·g,   J = [0 │ −sign(ψ_i) g │ 0 │ sign(ψ_i) g]
// Doom checks both planes the same way but merges the violated ones into one row; two rows,
// one per face, keep each face's constraint exact and let the solver handle the corner.
//
// A row is written once C < settings.limitMargin (before penetration), one-sided: lo = 0.

#include "joint_parts.h"

#include <algorithm>

namespace af::joint_detail {
namespace {


// θ = atan2(|b × k|, b·k), made (as the row's normal) only when a row may be written.
struct ConeState {
    Vec3 cross = Vec3::Zero();  // b × k
    Real sine = 0;              // |b × k|
    Real cosine = 0;            // b·k

    Real angle() const { return std::atan2(sine, cosine); }
    Real roughAngle() const { return roughAtan2(sine, cosine); }
    // At θ = 0 or π the plane of turning is undefined; any normal of the axis will do.
    Vec3 normal(const Vec3& axis) const { return sine > Real(1e-12) ? Vec3(cross / sine) : perpendicular(axis); }
};

ConeState coneState(const Vec3& shaft, const Vec3& axis) {
    ConeState s;
    s.cross = shaft.cross(axis);
    s.sine = s.cross.norm();
    s.cosine = shaft.dot(axis);
    return s;
}

// ψ_i = atan2(x, z), made (as its gradient) only when a row may be written.
struct FaceState {
    Real x = 0, z = 0, r2 = 0;  // x = b·e_i, z = b·e2, r2 = x² + z²
    bool defined = false;       // false when b is ⟂ the face's plane

    Real angle() const { return std::atan2(x, z); }
    Real roughAngle() const { return roughAtan2(x, z); }
    // g: dψ/dt = (ωA − ωB)·g.
    Vec3 gradient(const Vec3& shaft, const Vec3& side, const Vec3& axis) const {
        return shaft.cross(z * side - x * axis) / r2;
    }
};

FaceState faceState(const Vec3& shaft, const Vec3& side, const Vec3& axis) {
    FaceState s;
    s.x = shaft.dot(side);
    s.z = shaft.dot(axis);
    s.r2 = s.x * s.x + s.z * s.z;
    s.defined = s.r2 >= Real(1e-18);
    return s;
}

void writeAngleLimitRow(const Pair& pair, Real error, const Vec3& gradient, Real relativeCfm, RowOut out) {
    addAngularRow(pair, [&] { return gradient; }, error, 0, kInfinity, relativeCfm, out);
}

}  // namespace

int writeShaftLimitRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    if (!settings.limits) return 0;
    const Vec3 shaft = pair.a.direction(joint.limitShaft);
    int written = 0;
    if (joint.limit == LimitType::Cone) {
        if (joint.cone.halfAngle >= kPi) return 0;
        const Vec3 axis = pair.b.direction(joint.cone.axis);
        const ConeState s = coneState(shaft, axis);
        // Most writes find the shaft far inside its cone and need no exact angle.
        if (surelyInside(s.roughAngle(), joint.cone.halfAngle - settings.limitMargin)) return 0;
        const Real c = joint.cone.halfAngle - s.angle();
        if (c < settings.limitMargin) {
            writeAngleLimitRow(pair, c, s.normal(axis), settings.limitCfm, out);
            ++written;
        }
    } else if (joint.limit == LimitType::Pyramid) {
        const Mat3 basis = pair.b.rotation * joint.pyramid.basis;
        for (int i = 0; i < 2; ++i) {
            if (joint.pyramid.halfAngles[i] >= kPi) continue;
            const FaceState s = faceState(shaft, basis.col(i), basis.col(2));
            if (!s.defined || surelyInside(s.roughAngle(), joint.pyramid.halfAngles[i] - settings.limitMargin)) continue;
            const Real angle = s.angle();
            const Real c = joint.pyramid.halfAngles[i] - std::fabs(angle);
            if (c >= settings.limitMargin) continue;
            const Real sign = angle < 0 ? -1 : 1;
            writeAngleLimitRow(pair, c, -sign * s.gradient(shaft, basis.col(i), basis.col(2)), settings.limitCfm, out);
            ++written;
        }
    }
    return written;
}

Real shaftLimitViolation(const Joint& joint, const Pair& pair) {
    const Vec3 shaft = pair.a.direction(joint.limitShaft);
    Real worst = 0;
    if (joint.limit == LimitType::Cone) {
        const ConeState s = coneState(shaft, pair.b.direction(joint.cone.axis));
        worst = std::max(worst, s.angle() - joint.cone.halfAngle);
    } else if (joint.limit == LimitType::Pyramid) {
        const Mat3 basis = pair.b.rotation * joint.pyramid.basis;
        for (int i = 0; i < 2; ++i) {
            const FaceState s = faceState(shaft, basis.col(i), basis.col(2));
            if (s.defined) worst = std::max(worst, std::fabs(s.angle()) - joint.pyramid.halfAngles[i]);
        }
    }
    return worst;
}

}  // namespace af::joint_detail
