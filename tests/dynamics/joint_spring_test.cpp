// Doom's spring force (docs/doom-physics.md §4.3): quadratic in the stretch or compression, damped by a term
// that only subtracts from the magnitude whichever way the anchors move, equal and opposite on the two
// bodies along the line of the anchors. Forces exact to 1e-9 relative.

#include "joint_test_util.h"

namespace af::test {
namespace {

constexpr Real kStretch = 3, kCompress = 5, kDamping = 2, kRest = 4;

// A at the origin with its anchor 1 unit up its local Y; B at x = d with its anchor at its centre.
struct SpringScene {
    Joint joint;
    std::vector<RigidBody> bodies;
};

SpringScene scene(Real length, int body2 = 1) {
    FigureConstraint c = constraintOf(ConstraintType::Spring, body2);
    c.anchor = Vec3(0, 1, 0);
    c.anchor2 = Vec3(length, 1, 0);
    c.stretch = kStretch;
    c.compress = kCompress;
    c.damping = kDamping;
    c.restLength = kRest;
    const RigidPose a{}, b{Vec3(length, 1, 0), Mat3::Identity()};
    SpringScene s;
    s.joint = makeJoints(twoBodyFigure(a, b, c)).at(0);
    s.bodies = {bodyAt(a), bodyAt(b)};
    return s;
}

void expectForce(const Vec3& actual, const Vec3& expected) {
    EXPECT_LT((actual - expected).norm(), 1e-9 * (1 + expected.norm())) << actual.transpose() << " vs " << expected.transpose();
}

TEST(JointSpring, StretchedSpringPullsWithTheSquareOfTheExtension) {
    for (const Real extension : {0.5, 1.0, 3.0}) {
        SpringScene s = scene(kRest + extension);
        applySpringForces(s.joint, s.bodies);
        const Vec3 pull(kStretch * extension * extension, 0, 0);
        expectForce(s.bodies[0].force, pull);
        expectForce(s.bodies[1].force, -pull);
        expectForce(s.bodies[0].torque, Vec3(0, 1, 0).cross(pull));  // at the anchor, 1 up Y
        expectForce(s.bodies[1].torque, Vec3::Zero());
    }
}

TEST(JointSpring, CompressedSpringPushesWithTheSquareOfTheCompression) {
    SpringScene s = scene(kRest - 1.5);
    applySpringForces(s.joint, s.bodies);
    expectForce(s.bodies[0].force, Vec3(-kCompress * 1.5 * 1.5, 0, 0));
    expectForce(s.bodies[1].force, Vec3(kCompress * 1.5 * 1.5, 0, 0));
}

TEST(JointSpring, AtRestLengthThereIsNoForce) {
    SpringScene s = scene(kRest);
    applySpringForces(s.joint, s.bodies);
    expectForce(s.bodies[0].force, Vec3::Zero());
}

TEST(JointSpring, DampingSubtractsSpeedOverLengthWhicheverWayTheAnchorsMove) {
    // damp = damping·|relative speed along the spring| / L, taken off the magnitude: the same
    // force whether the spring is stretching or recoiling (Doom's law, not viscous damping).
    const Real length = kRest + 2;
    for (const Real speed : {1.5, -1.5}) {
        SpringScene s = scene(length);
        s.bodies[1].linearVelocity = Vec3(speed, 0, 0);
        s.bodies[1].angularVelocity = Vec3(0, 0, 7);  // spins about its own anchor: no anchor speed
        applySpringForces(s.joint, s.bodies);
        const Real damp = kDamping * std::fabs(speed) / length;
        expectForce(s.bodies[0].force, Vec3(kStretch * 4 - damp, 0, 0));
    }
    // Enough damping flips the force.
    SpringScene s = scene(kRest + 0.1);
    s.bodies[0].linearVelocity = Vec3(-10, 0, 0);
    applySpringForces(s.joint, s.bodies);
    EXPECT_LT(s.bodies[0].force.x(), 0);
}

TEST(JointSpring, CompressionIsDampedTheSameWay) {
    const Real length = kRest - 1;
    SpringScene s = scene(length);
    s.bodies[0].linearVelocity = Vec3(0.5, 0, 0);
    applySpringForces(s.joint, s.bodies);
    const Real damp = kDamping * 0.5 / length;
    expectForce(s.bodies[0].force, Vec3(-(kCompress * 1 - damp), 0, 0));
}

TEST(JointSpring, WorldAnchorHasNoVelocityAndTakesNoForce) {
    SpringScene s = scene(kRest + 1, kWorld);
    s.bodies[1].linearVelocity = Vec3(100, 0, 0);  // not part of the spring
    applySpringForces(s.joint, s.bodies);
    expectForce(s.bodies[0].force, Vec3(kStretch, 0, 0));
    expectForce(s.bodies[1].force, Vec3::Zero());
}

TEST(JointSpring, ForcesAddToWhatIsThereAndConserveMomentum) {
    Random random(9);
    FigureConstraint c = constraintOf(ConstraintType::Spring);
    c.anchor = random.vector(3);
    c.anchor2 = random.vector(3) + Vec3(8, 0, 0);
    c.stretch = c.compress = 2;
    c.damping = 1;
    c.restLength = 3;
    const RigidPose a = random.pose(2), b = random.pose(2);
    const Joint j = makeJoints(twoBodyFigure(a, b, c)).at(0);
    std::vector<RigidBody> bodies = {bodyAt(a), bodyAt(b)};
    bodies[0].force = Vec3(1, 2, 3);
    bodies[0].linearVelocity = random.vector(1);
    bodies[1].angularVelocity = random.vector(1);
    applySpringForces(j, bodies);
    const Vec3 f = bodies[0].force - Vec3(1, 2, 3);
    expectForce(f + bodies[1].force, Vec3::Zero());
    // Zero net torque about the origin: the forces act along the line through both anchors.
    const Vec3 torque = bodies[0].position.cross(f) + bodies[0].torque + bodies[1].position.cross(bodies[1].force) +
                        bodies[1].torque;
    expectForce(torque, Vec3::Zero());
    EXPECT_GT(f.norm(), 0);
}

TEST(JointSpring, OtherJointTypesGetNoSpringForce) {
    FigureConstraint c = constraintOf(ConstraintType::BallAndSocket);
    const Joint j = makeJoints(twoBodyFigure({}, {Vec3(9, 0, 0), Mat3::Identity()}, c)).at(0);
    std::vector<RigidBody> bodies = {bodyAt({}), bodyAt({Vec3(9, 0, 0), Mat3::Identity()})};
    applySpringForces(j, bodies);
    expectForce(bodies[0].force, Vec3::Zero());
}

}  // namespace
}  // namespace af::test
