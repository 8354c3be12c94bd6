// The joint types behind one entry point, and the measurements of joints for tests and summaries.

#include "joint_parts.h"

#include <algorithm>

namespace af {

using namespace joint_detail;

namespace {

JointRowRange writeRows(const Joint& joint, const Pair& pair, const JointRowSettings& settings, RowOut out) {
    const int first = static_cast<int>(out.rows() ? out.rows()->size() : out.errors()->size());
    JointRowRange range;
    switch (joint.type) {
    case ConstraintType::Fixed: range = writeFixedRows(joint, pair, settings, out); break;
    case ConstraintType::BallAndSocket: range = writeBallRows(joint, pair, settings, out); break;
    case ConstraintType::Universal:
        range = joint.cardan.enabled ? writeCardanRows(joint, pair, settings, out) : writeUniversalRows(joint, pair, settings, out);
        break;
    case ConstraintType::Hinge: range = writeHingeRows(joint, pair, settings, out); break;
    case ConstraintType::Slider: range = writeSliderRows(joint, pair, settings, out); break;
    case ConstraintType::Spring: range = writeSpringRows(joint, pair, settings, out); break;
    }
    range.first = first;
    return range;
}

}  // namespace

JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies, const JointRowSettings& settings,
                             ConstraintRows& out) {
    return writeRows(joint, pairOf(joint, bodies), settings, out);
}

JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies,
                             std::span<const Mat3> inverseInertiaWorld, const JointRowSettings& settings,
                             ConstraintRows& out) {
    return writeRows(joint, pairOf(joint, bodies, inverseInertiaWorld), settings, out);
}

JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
                             std::span<const Mat3> inverseInertiaWorld, const JointRowSettings& settings,
                             ConstraintRows& out) {
    return writeRows(joint, pairOf(joint, bodies, rotations, inverseInertiaWorld), settings, out);
}

JointRowRange writeJointErrors(const Joint& joint, std::span<const RigidBody> bodies, const JointRowSettings& settings,
                               std::vector<RowError>& out) {
    return writeRows(joint, kinematicPairOf(joint, bodies), settings, out);
}

JointRowRange writeJointErrors(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
                               const JointRowSettings& settings, std::vector<RowError>& out) {
    return writeRows(joint, kinematicPairOf(joint, bodies, rotations), settings, out);
}

Real jointError(const Joint& joint, std::span<const RigidBody> bodies) {
    const Pair pair = pairOf(joint, bodies);
    switch (joint.type) {
    case ConstraintType::Slider: return sliderOffAxisDistance(joint, pair);
    case ConstraintType::Spring: {
        const Real length = springLengthOf(joint, pair);
        Real outside = std::max(Real(0), joint.spring.minLength - length);
        if (joint.spring.maxLength > 0) outside = std::max(outside, length - joint.spring.maxLength);
        return outside;
    }
    default: return (pair.a.point(joint.anchorA) - pair.b.point(joint.anchorB)).norm();
    }
}

Real jointAngularError(const Joint& joint, std::span<const RigidBody> bodies) {
    const Pair pair = pairOf(joint, bodies);
    switch (joint.type) {
    case ConstraintType::Fixed:
    case ConstraintType::Slider: return rotationAngle(errorRotation(pair, joint.relative));
    case ConstraintType::Hinge: {
        const Vec3 hA = pair.a.direction(joint.axisA);
        const Vec3 hB = pair.b.direction(joint.axisB);
        return std::atan2(hA.cross(hB).norm(), hA.dot(hB));
    }
    case ConstraintType::Universal:
        return joint.cardan.enabled ? cardanArmsError(joint, pair) : std::fabs(universalTwist(joint, pair));
    default: return 0;
    }
}

Real limitViolationDegrees(const Joint& joint, std::span<const RigidBody> bodies) {
    const Pair pair = pairOf(joint, bodies);
    switch (joint.type) {
    case ConstraintType::BallAndSocket:
        return degrees(std::max(shaftLimitViolation(joint, pair), twistLimitViolation(joint, pair)));
    case ConstraintType::Universal:
        return degrees(joint.cardan.enabled ? cardanLimitViolation(joint, pair) : shaftLimitViolation(joint, pair));
    case ConstraintType::Hinge: return degrees(hingeLimitViolation(joint, pair));
    default: return 0;
    }
}

Real hingeAngle(const Joint& joint, std::span<const RigidBody> bodies) { return hingeAngleOf(joint, pairOf(joint, bodies)); }

std::array<Real, 2> cardanAngles(const Joint& joint, std::span<const RigidBody> bodies) {
    return cardanAnglesOf(joint, pairOf(joint, bodies));
}

Real twistAngle(const Joint& joint, std::span<const RigidBody> bodies) { return twistAngleOf(joint, pairOf(joint, bodies)); }

Real springLength(const Joint& joint, std::span<const RigidBody> bodies) {
    return springLengthOf(joint, pairOf(joint, bodies));
}

}  // namespace af
