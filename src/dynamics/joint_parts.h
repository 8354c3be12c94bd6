#pragma once
// Parts shared by the joint files: a body as a joint sees it, appending a row with relative
// softness, and the rows several joint types have in common (point, orientation, the cone and
// pyramid limits on a shaft, angular friction). Each part is derived where it is defined.

#include "joint_errors.h"

#include <array>
#include <cmath>
#include <concepts>
#include <numbers>
#include <vector>

namespace af::joint_detail {

// Where a joint's rows go: whole rows, or only each row's error and bounds (all that measuring
// a violation or a drift needs), which skips the Jacobians and the softness, most of a row's cost.
class RowOut {
public:
    RowOut(ConstraintRows& rows) : rows_(&rows) {}
    RowOut(std::vector<RowError>& errors) : errors_(&errors) {}
    ConstraintRows* rows() const { return rows_; }
    std::vector<RowError>* errors() const { return errors_; }
    // A row made whole by write(rows) when rows are written, otherwise only its error and bounds
    // (whatever write would compute for the Jacobian is never computed then).
    template <class Write>
    void add(Real error, Real lo, Real hi, Write&& write) const {
        if (rows_)
            write(*rows_);
        else
            errors_->push_back({error, lo, hi});
    }

private:
    ConstraintRows* rows_ = nullptr;
    std::vector<RowError>* errors_ = nullptr;
};

// A body's state as a joint needs it; the world is an immovable body at the origin.
struct Side {
    int index = kWorldBody;
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Mat3 rotation = Mat3::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    Real inverseMass = 0;
    Mat3 inverseInertia = Mat3::Zero();  // world frame

    Vec3 point(const Vec3& local) const { return position + rotation * local; }
    Vec3 direction(const Vec3& local) const { return rotation * local; }
    Vec3 velocityAt(const Vec3& worldPoint) const {
        return linearVelocity + angularVelocity.cross(worldPoint - position);
    }
};

Side sideOf(int index, std::span<const RigidBody> bodies);
// The same with the body's world inverse inertia given (see writeJointRows).
Side sideOf(int index, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld);
// The same with the body's rotation() given too.
Side sideOf(int index, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
           std::span<const Mat3> inverseInertiaWorld);

// The two bodies of a joint.
struct Pair {
    Side a, b;
};
Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies);
Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld);
Pair pairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
            std::span<const Mat3> inverseInertiaWorld);
// Without the inertias (zero), for what reads only poses: the rows' errors.
Pair kinematicPairOf(const Joint& joint, std::span<const RigidBody> bodies);
// The same with each body's rotation() given.
Pair kinematicPairOf(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations);

// The Jacobian of one row: Cdot = linearA·vA + angularA·ωA + linearB·vB + angularB·ωB.
struct Jacobian {
    Vec3 linearA = Vec3::Zero();
    Vec3 angularA = Vec3::Zero();
    Vec3 linearB = Vec3::Zero();
    Vec3 angularB = Vec3::Zero();
};

// Appends a row; B's blocks are dropped against the world. cfm = relativeCfm · J M⁻¹ Jᵀ.
void addRow(const Pair& pair, const Jacobian& jacobian, Real error, Real lo, Real hi, Real relativeCfm,
            ConstraintRows& out);
// The same with the Jacobian made by jacobianOf() only when whole rows are written.
template <std::invocable JacobianOf>
void addRow(const Pair& pair, JacobianOf&& jacobianOf, Real error, Real lo, Real hi, Real relativeCfm, RowOut out) {
    out.add(error, lo, hi, [&](ConstraintRows& rows) { addRow(pair, jacobianOf(), error, lo, hi, relativeCfm, rows); });
}

// Appends a row J = [0 │ g │ 0 │ −g] on the relative angular velocity (limits, friction, the
// hinge's axes, the universal's twist), with the Jacobian's zero blocks left out of its softness:
// addRow's row bit for bit (but for the sign of a zero softness at g = 0), ~20 instructions less.
void addAngularRow(const Pair& pair, const Vec3& g, Real error, Real lo, Real hi, Real relativeCfm, ConstraintRows& out);
// The same with g made by gradientOf() only when whole rows are written.
template <std::invocable GradientOf>
void addAngularRow(const Pair& pair, GradientOf&& gradientOf, Real error, Real lo, Real hi, Real relativeCfm, RowOut out) {
    out.add(error, lo, hi,
            [&](ConstraintRows& rows) { addAngularRow(pair, gradientOf(), error, lo, hi, relativeCfm, rows); });
}

// A unit vector ⟂ unit v (the hinge `left` of docs/figures.md §3.8, made orthogonal).
Vec3 perpendicular(const Vec3& v);
// Angle wrapped into (−π, π].
Real wrapAngle(Real angle);
// atan2(y, x) within 1.2e-5 rad, for telling a joint far from its limit at ~25 instructions
// against libm's ~130; a row is always written with the exact angle. The octant's arctangent by
// Abramowitz & Stegun 4.4.49 (largest error 1.15e-5 measured over [0, 1] in 2M samples).
Real roughAtan2(Real y, Real x);
// Whether a limit row written when |angle| > bound (bound = limit − margin) is surely not
// written, from the rough angle: 1e-4 rad leaves room for its error and every rounding.
inline bool surelyInside(Real roughAngle, Real bound) { return std::fabs(roughAngle) < bound - Real(1e-4); }
inline constexpr Real kPi = std::numbers::pi_v<Real>;
inline Real degrees(Real radians) { return radians * (180 / std::numbers::pi_v<Real>); }
inline Real radians(Real degrees) { return degrees * (std::numbers::pi_v<Real> / 180); }

// Point rows: C = pA − pB along the world axes, pA and pB world points carried by A and B.
void writePointRows(const Pair& pair, const Vec3& pointA, const Vec3& pointB, Real relativeCfm, RowOut out);

// The error rotation qA ⊗ relative⁻¹ ⊗ qB⁻¹ (identity when A sits in B's frame as `relative`
// says), with w ≥ 0.
Quat errorRotation(const Pair& pair, const Quat& relative);
// Orientation rows: C = 2·vec(errorRotation) along the world axes.
void writeOrientationRows(const Pair& pair, const Quat& relative, Real relativeCfm, RowOut out);
// The angle of the error rotation, radians.
Real rotationAngle(const Quat& q);

// Cone or pyramid limit rows on joint.limitShaft (A) against B; returns how many were written.
int writeShaftLimitRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out);
// How far the shaft is past its cone or pyramid, radians (0 inside).
Real shaftLimitViolation(const Joint& joint, const Pair& pair);

// Twist limit rows of a ball-and-socket joint (joint_twist_limit.cpp); returns how many were
// written. The twist angle, radians, and how far it is past the limit (0 inside or unlimited).
int writeTwistLimitRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out);
Real twistAngleOf(const Joint& joint, const Pair& pair);
Real twistLimitViolation(const Joint& joint, const Pair& pair);

// A friction row on the relative angular velocity (ωA − ωB)·axis, boxed by ±bound.
void writeAngularFrictionRow(const Pair& pair, const Vec3& axis, Real bound, Real relativeCfm, RowOut out);
// The friction bound f·|λ_previous|, 0 when the joint has no friction this step (f: the
// settings' forced friction, if any, else the joint's own).
Real frictionBound(const Joint& joint, const JointRowSettings& settings);

// Per type; each returns its counts, `first` is set by the caller.
JointRowRange writeFixedRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeSliderRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeBallRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeUniversalRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeCardanRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeHingeRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);
JointRowRange writeSpringRows(const Joint&, const Pair&, const JointRowSettings&, RowOut);

Real sliderOffAxisDistance(const Joint&, const Pair&);
Real universalTwist(const Joint&, const Pair&);
std::array<Real, 2> cardanAnglesOf(const Joint&, const Pair&);
Real cardanArmsError(const Joint&, const Pair&);  // radians from ⟂
Real cardanLimitViolation(const Joint&, const Pair&);
Real hingeAngleOf(const Joint&, const Pair&);
Real hingeLimitViolation(const Joint&, const Pair&);
Real springLengthOf(const Joint&, const Pair&);

}  // namespace af::joint_detail
