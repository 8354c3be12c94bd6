// SHAKE with a held limit (ShakeCorrection::capture's `hold`): a pendulum on a ball joint, its
// cone limit at C = 0, swinging along the cone's edge. The step's rotation opens the joint by
// O(dt²) and moves the shaft off the cone; SHAKE along the point rows alone closes the joint but
// leaves the limit where the motion took it, with the limit held both close.

#include "dynamics/row_system.h"
#include "dynamics/shake.h"
#include "joint_test_util.h"

namespace af::test {
namespace {

constexpr Real kDt = Real(1) / 60;

struct Pendulum {
    Joint joint;
    std::vector<RigidBody> bodies;
};

// Body A hangs 10 below the world anchor, tilted to its 30° cone, turning at 4 rad/s about the
// cone's axis (the shaft sweeps the cone's edge: Cdot = 0) and at 1 rad/s about the shaft.
Pendulum pendulumOnItsCone() {
    Pendulum p{hangingBall(LimitType::Cone, {60, 0, 0}), {bodyAt(kHanging), bodyAt({})}};
    p.bodies.resize(1);
    turnBodyAbout(p.bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(30), Vec3::UnitX())), Vec3::Zero());
    RigidBody& a = p.bodies[0];
    a.angularVelocity = Vec3(0, 0, 4) + (a.position.normalized() * 1);
    a.linearVelocity = a.angularVelocity.cross(a.position);  // the anchor's point at rest
    return p;
}

struct Shaken {
    Real limitBefore = 0;  // the limit row's C after the free move
    Real limitAfter = 0;   // and after two Newton steps
    Real jointAfter = 0;   // the largest point row error after them
};

Shaken shake(bool holdLimit) {
    Pendulum p = pendulumOnItsCone();
    ConstraintRows rows;
    std::vector<JointRowRange> ranges{writeJointRows(p.joint, p.bodies, JointRowSettings{}, rows)};
    EXPECT_EQ(ranges[0].limitRows, 1);
    EXPECT_NEAR(rows[3].error, 0, 1e-12);
    RowSystem system;
    system.buildResponses(rows, p.bodies);
    const std::vector<char> hold{0, 0, 0, static_cast<char>(holdLimit)};
    ShakeCorrection correction;
    correction.capture(rows, ranges, system, hold);

    for (RigidBody& b : p.bodies) integratePosition(b, kDt);
    Shaken out;
    for (int newton = 0; newton < 2; ++newton) {
        rows.clear();
        ranges = {writeJointRows(p.joint, p.bodies, JointRowSettings{}, rows)};
        if (newton == 0) out.limitBefore = rows[3].error;
        correction.apply(rows, ranges, p.bodies, kDt, 0);
    }
    rows.clear();
    ranges = {writeJointRows(p.joint, p.bodies, JointRowSettings{}, rows)};
    out.limitAfter = rows[3].error;
    for (int i = 0; i < 3; ++i) out.jointAfter = std::max(out.jointAfter, std::abs(rows[static_cast<std::size_t>(i)].error));
    return out;
}

TEST(ShakeLimit, AHeldLimitEndsTheStepWhereTheVelocitySolveLeftIt) {
    const Shaken held = shake(true);
    const Shaken free = shake(false);
    // Without the hold the point rows' move turns the shaft: the cone's row ends far from 0.
    EXPECT_GT(std::abs(free.limitAfter), 1e-4);
    EXPECT_LT(free.jointAfter, 1e-9);
    EXPECT_GT(std::abs(held.limitBefore), 1e-4);
    EXPECT_LT(std::abs(held.limitAfter), 1e-9);
    EXPECT_LT(held.jointAfter, 1e-9);
}

}  // namespace
}  // namespace af::test
