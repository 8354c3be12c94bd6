#pragma once
// Eigen vocabulary of the geometry stage and the one bridge from Doom's angles to our rotations.
//
// Convention (see also af/types.h and docs/conventions.md §0.2): column vectors. A rotation R maps
// body-local vectors to world (or model) vectors, p_world = origin + R * p_local, so the columns of
// R are the body's local X, Y, Z axes written in world coordinates. Doom stores the transpose: its
// "axis" matrix A has the local axes as rows and multiplies row vectors, p_world = origin + p_local·A.
// Hence A = Rᵀ; convert exactly once, where a Doom value enters the library.

#include "af/types.h"

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace af {

using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;

// A rigid transform: p_outer = position + rotation * p_local.
struct RigidPose {
    Vec3 position = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();

    Vec3 apply(const Vec3& p) const { return position + rotation * p; }
    RigidPose operator*(const RigidPose& inner) const {
        return {position + rotation * inner.position, rotation * inner.rotation};
    }
    RigidPose inverse() const { return {-(rotation.transpose() * position), rotation.transpose()}; }
};

/// Rotation R (body-local → world, columns = local axes) of Doom's idAngles(pitch, yaw, roll).
/// Angles in degrees. Equals the transpose of Doom's `idAngles::ToMat3()`: column 0 is forward
/// (cp·cy, cp·sy, −sp), column 1 is left, column 2 is up. Positive pitch points the nose down
/// (−Z), positive yaw turns counter-clockwise seen from above, positive roll lifts the left axis
/// towards +Z. As a product of right-handed rotations: R = Rz(yaw) · Ry(pitch) · Rx(roll).
Mat3 rotationFromAngles(Real pitchDeg, Real yawDeg, Real rollDeg);

/// The inverse: (pitch, yaw, roll) in degrees of a rotation, as Doom's idMat3::ToAngles reads
/// them (docs/conventions.md §0.2), including its choice near gimbal lock (yaw from the left axis, roll 0).
Vec3 anglesFromRotation(const Mat3& rotation);

/// (pitch, yaw, roll) in degrees from which rotationFromAngles rebuilds `rotation` to rounding,
/// for writing orientations into files. Away from gimbal lock these are anglesFromRotation's
/// angles (to rounding). Near it Doom's reading drops roll while cos(pitch) is still up to
/// 8192 × FLT_EPSILON, which turns the rebuilt rotation by up to about 0.1°; here yaw keeps
/// coming from the forward axis down to a cosine of 1e-12, and roll is read from what pitch and
/// yaw leave, so it absorbs their rounding. Pitch in [−90°, 90°], yaw and roll in [−180°, 180°].
Vec3 anglesFromRotationPrecise(const Mat3& rotation);

}  // namespace af
