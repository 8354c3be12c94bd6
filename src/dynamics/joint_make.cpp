// Joints from a figure (docs/figures.md §3.8): every world-space spawn vector goes into the frame of the
// body that carries it, using the bodies' spawn poses, so it follows that body from then on.
// Limits are converted once: angles to radians, Doom's full angles to half angles, the pyramid's
// roll into a basis, the hinge's three V angles into an interval of the hinge angle.

#include "joint_parts.h"

namespace af {

using namespace joint_detail;

namespace {

static_assert(kWorld == kWorldBody, "figure and dynamics name the world alike");

// A body's frame at spawn; the world's is the identity.
struct SpawnFrame {
    RigidPose pose;
    Quat orientation = Quat::Identity();

    Vec3 localPoint(const Vec3& world) const { return pose.rotation.transpose() * (world - pose.position); }
    Vec3 localDirection(const Vec3& world) const { return pose.rotation.transpose() * world.normalized(); }
};

SpawnFrame spawnFrame(const Figure& figure, int body) {
    SpawnFrame f;
    if (body == kWorld) return f;
    f.pose = figure.bodies[static_cast<std::size_t>(body)].pose;
    f.orientation = Quat(f.pose.rotation);
    return f;
}

// The pyramid basis (docs/figures.md §3.8) in world space: Doom takes the angles of the limit axis as it was
// written (model space, before the spawn placement), sets the roll to a3 and uses the rows of the
// resulting matrix, which are our columns: axis = forward, base = left rolled by a3.
Mat3 pyramidBasis(const Figure& figure, const Vec3& worldAxis, Real rollDegrees) {
    const Mat3& placement = figure.placement.rotation;
    const Vec3 modelAxis = placement.transpose() * worldAxis.normalized();
    const Real yaw = degrees(std::atan2(modelAxis.y(), modelAxis.x()));
    const Real pitch = -degrees(std::atan2(modelAxis.z(), std::hypot(modelAxis.x(), modelAxis.y())));
    const Mat3 frame = placement * rotationFromAngles(pitch, yaw, rollDegrees);
    const Vec3 axis = frame.col(0);
    const Vec3 base = (frame.col(1) - frame.col(1).dot(axis) * axis).normalized();
    Mat3 basis;
    basis.col(0) = base;
    basis.col(1) = base.cross(axis);
    basis.col(2) = axis;
    return basis;
}

void setShaftLimit(const Figure& figure, const FigureConstraint& c, const SpawnFrame& b, Joint& j) {
    j.limit = c.limit;
    if (c.limit == LimitType::Cone) {
        j.cone.axis = b.localDirection(c.limitAxis);
        j.cone.halfAngle = radians(c.limitAngles[0] / 2);
        j.cone.cosHalfAngle = std::cos(j.cone.halfAngle);
        j.cone.sinHalfAngle = std::sin(j.cone.halfAngle);
    } else if (c.limit == LimitType::Pyramid) {
        j.pyramid.basis = b.pose.rotation.transpose() * pyramidBasis(figure, c.limitAxis, c.limitAngles[2]);
        j.pyramid.halfAngles[0] = radians(c.limitAngles[0] / 2);
        j.pyramid.halfAngles[1] = radians(c.limitAngles[1] / 2);
    }
}

// Twist references that agree at spawn (joint_twist_limit.cpp): one ⟂ B's axis, and its image
// on A's shaft by the shortest arc.
void setTwistLimit(const FigureConstraint& c, const SpawnFrame& a, const SpawnFrame& b, Joint& j) {
    if (c.twistLimit <= 0) return;
    const Vec3 shaft = c.shafts[0].normalized();
    const Vec3 axis = c.limit == LimitType::Cone ? Vec3(c.limitAxis.normalized()) : shaft;
    const Vec3 referenceB = perpendicular(axis);
    j.twistHalfAngle = radians(c.twistLimit);
    j.twistAxisB = b.localDirection(axis);
    j.twistReferenceB = b.localDirection(referenceB);
    j.twistReferenceA = a.localDirection(Quat::FromTwoVectors(axis, shaft) * referenceB);
}

// Cardan cross (joint_cardan.cpp): each arm in its body's frame, and each body's spawn copies of
// the other arm and of armB × armA, from which the angles are read. Arm A is made ⟂ to arm B, so
// that the joint starts where it holds.
void setCardan(const FigureConstraint& c, const SpawnFrame& a, const SpawnFrame& b, Joint& j) {
    const Vec3 armB = c.shafts[1].normalized();
    const Vec3 armA = (c.shafts[0] - c.shafts[0].dot(armB) * armB).normalized();
    const Vec3 cross = armB.cross(armA);
    j.axisA = a.localDirection(armA);
    j.axisB = b.localDirection(armB);
    j.referenceA = a.localDirection(armB);
    j.referenceB = b.localDirection(armA);
    j.cardan.enabled = true;
    j.cardan.crossA = a.localDirection(cross);
    j.cardan.crossB = b.localDirection(cross);
    for (std::size_t k = 0; k < 2; ++k) {
        j.cardan.lower[k] = radians(c.cardanLower[k]);
        j.cardan.upper[k] = radians(c.cardanUpper[k]);
    }
    j.limit = LimitType::None;
}

// Fixed and slider: where B holds A's centre of mass, and A's orientation in B's frame.
void setRelativePose(const SpawnFrame& a, const SpawnFrame& b, Joint& j) {
    j.anchorA = Vec3::Zero();
    j.anchorB = b.localPoint(a.pose.position);
    j.relative = (b.orientation.conjugate() * a.orientation).normalized();
}

Joint makeJoint(const Figure& figure, const FigureConstraint& c) {
    Joint j;
    j.type = c.type;
    j.name = c.name;
    j.bodyA = c.body1;
    j.bodyB = c.body2;
    const SpawnFrame a = spawnFrame(figure, c.body1);
    const SpawnFrame b = spawnFrame(figure, c.body2);
    switch (c.type) {
    case ConstraintType::Fixed: setRelativePose(a, b, j); break;
    case ConstraintType::BallAndSocket:
        j.anchorA = a.localPoint(c.anchor);
        j.anchorB = b.localPoint(c.anchor);
        j.limitShaft = a.localDirection(c.shafts[0]);
        setShaftLimit(figure, c, b, j);
        setTwistLimit(c, a, b, j);
        j.friction = c.friction;
        break;
    case ConstraintType::Universal: {
        j.anchorA = a.localPoint(c.anchor);
        j.anchorB = b.localPoint(c.anchor);
        j.friction = c.friction;
        if (c.cardan) {
            setCardan(c, a, b, j);
            break;
        }
        const Vec3 s1 = c.shafts[0].normalized();
        const Vec3 s2 = c.shafts[1].normalized();
        j.axisA = a.localDirection(s1);
        j.axisB = b.localDirection(s2);
        // The cardan axis ⟂ both shafts (any normal of shaft 1 when they are parallel), and the
        // constant factor of the twist rotation, see joint_universal.cpp.
        const Vec3 cross = s1.cross(s2);
        const Vec3 k = cross.norm() > Real(1e-9) ? Vec3(cross.normalized()) : perpendicular(s1);
        Mat3 frameA, frameB;
        frameA << s1, k, s1.cross(k);
        frameB << -s2, k, (-s2).cross(k);
        const Mat3 localA = a.pose.rotation.transpose() * frameA;
        const Mat3 localB = b.pose.rotation.transpose() * frameB;
        j.relative = Quat(Mat3(localB * localA.transpose())).normalized();
        j.limitShaft = j.axisA;
        setShaftLimit(figure, c, b, j);
        break;
    }
    case ConstraintType::Hinge: {
        j.anchorA = a.localPoint(c.anchor);
        j.anchorB = b.localPoint(c.anchor);
        const Vec3 h = c.axis.normalized();
        j.axisA = a.localDirection(h);
        j.axisB = b.localDirection(h);
        const Vec3 reference = perpendicular(h);
        j.referenceA = a.localDirection(reference);
        j.referenceB = b.localDirection(reference);
        // Doom's shaft (on body1) starts a3 clockwise of `left` and the V's centre (on body2) is
        // a1 clockwise of it: the hinge angle (right-handed) must stay within a2/2 of a3 − a1.
        j.limit = c.limit;
        j.hinge.center = radians(c.limitAngles[2] - c.limitAngles[0]);
        j.hinge.halfWidth = radians(c.limitAngles[1] / 2);
        j.friction = c.friction;
        break;
    }
    case ConstraintType::Slider: {
        setRelativePose(a, b, j);
        const Vec3 n = c.axis.normalized();
        j.axisB = b.localDirection(n);
        j.referenceB = b.localDirection(perpendicular(n));
        break;
    }
    case ConstraintType::Spring:
        j.anchorA = a.localPoint(c.anchor);
        j.anchorB = b.localPoint(c.anchor2);
        j.spring = {c.stretch, c.compress, c.damping, c.restLength, c.minLength, c.maxLength};
        break;
    }
    return j;
}

}  // namespace

std::vector<Joint> makeJoints(const Figure& figure) {
    std::vector<Joint> joints;
    joints.reserve(figure.constraints.size());
    for (const FigureConstraint& c : figure.constraints) joints.push_back(makeJoint(figure, c));
    return joints;
}

}  // namespace af
