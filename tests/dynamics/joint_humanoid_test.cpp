// Our humanoid (af/humanoid.af on its af_pose) at spawn: every joint holds exactly, no limit is
// near, and where the figure is placed does not change its joints relative to their bodies.

#include "../figure/figure_test_util.h"
#include "joint_test_util.h"

namespace af::test {
namespace {

Figure humanoid(const RigidPose& placement = {}) {
    const FigureResult r = buildFigure(humanoidDecl(), humanoidPose(), "af/humanoid.af", placement);
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    return r.figure.value_or(Figure{});
}

TEST(JointHumanoid, EveryJointHoldsExactlyAndNoLimitRowIsWrittenAtSpawn) {
    const Figure figure = humanoid();
    const std::vector<Joint> joints = makeJoints(figure);
    ASSERT_EQ(joints.size(), figure.constraints.size());
    ASSERT_GE(joints.size(), 15u);
    const std::vector<RigidBody> bodies = spawnBodies(figure);
    for (const Joint& j : joints) {
        SCOPED_TRACE(j.name);
        ConstraintRows rows;
        const JointRowRange range = writeJointRows(j, bodies, JointRowSettings{}, rows);
        EXPECT_EQ(range.first, 0);
        EXPECT_GT(range.equalityRows, 0);
        EXPECT_EQ(range.limitRows, 0);
        EXPECT_EQ(range.frictionRows, 0);  // lastImpulse is 0 before the first step
        for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i].error, 0, 1e-9) << "row " << i;
        EXPECT_LT(jointError(j, bodies), 1e-9);
        EXPECT_LT(jointAngularError(j, bodies), 1e-9);
        EXPECT_EQ(limitViolationDegrees(j, bodies), 0);
        if (j.type == ConstraintType::Hinge) {
            EXPECT_NEAR(hingeAngle(j, bodies), 0, 1e-12);
        }
    }
}

TEST(JointHumanoid, KneeAndAnkleIntervalsAreTheFilesVs) {
    const Figure figure = humanoid();
    const std::vector<Joint> joints = makeJoints(figure);
    for (const Joint& j : joints) {
        // Doom's clockwise angle θ = −hingeAngle lies in [a1 − a3 − a2/2, a1 − a3 + a2/2].
        const Real lo = -(j.hinge.center + j.hinge.halfWidth) * 180 / kPi;
        const Real hi = -(j.hinge.center - j.hinge.halfWidth) * 180 / kPi;
        if (j.name == "lknee" || j.name == "lelbow") {  // limit 70, 150, 0
            EXPECT_NEAR(lo, -5, 1e-9) << j.name;
            EXPECT_NEAR(hi, 145, 1e-9) << j.name;
        }
        if (j.name == "lankle") {  // limit -12.5, 65, 0
            EXPECT_NEAR(lo, -45, 1e-9);
            EXPECT_NEAR(hi, 20, 1e-9);
        }
    }
}

void expectSame(const Vec3& a, const Vec3& b, const std::string& what) {
    EXPECT_LT((a - b).norm(), 1e-9) << what << ": (" << a.transpose() << ") vs (" << b.transpose() << ")";
}

TEST(JointHumanoid, PlacementLeavesJointsUnchangedInTheirBodiesFrames) {
    const RigidPose placed{Vec3(100, -40, 25), rotationFromAngles(20, 75, -10)};
    const std::vector<Joint> here = makeJoints(humanoid());
    const std::vector<Joint> there = makeJoints(humanoid(placed));
    ASSERT_EQ(here.size(), there.size());
    for (std::size_t i = 0; i < here.size(); ++i) {
        const Joint& a = here[i];
        const Joint& b = there[i];
        SCOPED_TRACE(a.name);
        expectSame(a.anchorA, b.anchorA, "anchorA");
        expectSame(a.anchorB, b.anchorB, "anchorB");
        expectSame(a.axisA, b.axisA, "axisA");
        expectSame(a.axisB, b.axisB, "axisB");
        expectSame(a.limitShaft, b.limitShaft, "limitShaft");
        expectSame(a.cone.axis, b.cone.axis, "cone axis");
        for (int c = 0; c < 3; ++c) expectSame(a.pyramid.basis.col(c), b.pyramid.basis.col(c), "pyramid basis");
        EXPECT_LT(a.relative.angularDistance(b.relative), 1e-9);
        EXPECT_NEAR(a.hinge.center, b.hinge.center, 1e-12);
        EXPECT_NEAR(a.hinge.halfWidth, b.hinge.halfWidth, 1e-12);
    }
}

}  // namespace
}  // namespace af::test
