// Joint friction (docs/doom-physics.md §4.7): boxed rows on the relative angular velocity, bounded by the
// friction coefficient times the joint's impulse of the previous step, absent when that is 0. Ball 3
// rows, universal 2 (⟂ shaft 1), hinge 1 (the axis); fixed, slider and spring none.

#include "joint_test_util.h"

namespace af::test {
namespace {

Joint jointOf(ConstraintType type, Real friction, Real lastImpulse) {
    FigureConstraint c = constraintOf(type);
    c.anchor = Vec3(1, 0, 0);
    c.axis = Vec3(0, 0, 1);
    c.shafts[0] = Vec3(1, 0, 0);
    c.shafts[1] = Vec3(-1, 0, 0);
    c.anchor2 = Vec3(3, 0, 0);
    c.friction = friction;
    Joint j = makeJoints(twoBodyFigure({}, {Vec3(2, 0, 0), Mat3::Identity()}, c)).at(0);
    j.lastImpulse = lastImpulse;
    return j;
}

std::vector<RigidBody> restingBodies() { return {bodyAt({}), bodyAt({Vec3(2, 0, 0), Mat3::Identity()})}; }

TEST(JointFriction, RowsAreBoundedByFrictionTimesTheLastImpulse) {
    struct Case {
        ConstraintType type;
        int rows;
    };
    for (const Case c : {Case{ConstraintType::BallAndSocket, 3}, Case{ConstraintType::Universal, 2},
                         Case{ConstraintType::Hinge, 1}, Case{ConstraintType::Fixed, 0}, Case{ConstraintType::Slider, 0},
                         Case{ConstraintType::Spring, 0}}) {
        for (const Real lastImpulse : {1.0, 2.5}) {
            SCOPED_TRACE(testing::Message() << toString(c.type) << ", last impulse " << lastImpulse);
            const Joint j = jointOf(c.type, 0.4, lastImpulse);
            ConstraintRows rows;
            const JointRowRange range = writeJointRows(j, restingBodies(), JointRowSettings{}, rows);
            ASSERT_EQ(range.frictionRows, c.rows);
            ASSERT_EQ(static_cast<int>(rows.size()), range.total());
            for (int k = 0; k < range.frictionRows; ++k) {
                const ConstraintRow& row = rows[static_cast<std::size_t>(range.equalityRows + range.limitRows + k)];
                EXPECT_DOUBLE_EQ(row.hi, 0.4 * lastImpulse);
                EXPECT_DOUBLE_EQ(row.lo, -0.4 * lastImpulse);
                EXPECT_EQ(row.frictionSource, -1);
                EXPECT_EQ(row.error, 0);
                EXPECT_EQ(row.target, 0);
                EXPECT_EQ(row.linearA, Vec3::Zero());
                EXPECT_EQ(row.linearB, Vec3::Zero());
                EXPECT_EQ(row.angularB, -row.angularA);  // relative angular velocity
                EXPECT_NEAR(row.angularA.norm(), 1, 1e-12);
                EXPECT_GT(row.cfm, 0);
            }
        }
    }
}

TEST(JointFriction, NoRowsWithoutALastImpulseOrWithoutFriction) {
    for (const ConstraintType type : {ConstraintType::BallAndSocket, ConstraintType::Universal, ConstraintType::Hinge}) {
        for (const auto& [friction, lastImpulse] : {std::pair{0.5, 0.0}, std::pair{0.0, 3.0}, std::pair{-1.0, 3.0}}) {
            ConstraintRows rows;
            const JointRowRange range =
                writeJointRows(jointOf(type, friction, lastImpulse), restingBodies(), JointRowSettings{}, rows);
            EXPECT_EQ(range.frictionRows, 0) << toString(type) << " friction " << friction << " impulse " << lastImpulse;
        }
    }
}

TEST(JointFriction, BallFrictionDampsRelativeNotSummedAngularVelocity) {
    // Doom's rows measure ωA + ωB; ours ωA − ωB: bodies spinning together feel no friction,
    // bodies spinning against each other do.
    const Joint j = jointOf(ConstraintType::BallAndSocket, 0.5, 1);
    std::vector<RigidBody> bodies = restingBodies();
    ConstraintRows rows;
    const JointRowRange range = writeJointRows(j, bodies, JointRowSettings{}, rows);
    ASSERT_EQ(range.frictionRows, 3);
    const Vec3 spin(0.3, -1.2, 2);
    for (int k = 0; k < 3; ++k) {
        const ConstraintRow& row = rows[static_cast<std::size_t>(range.equalityRows + k)];
        bodies[0].angularVelocity = bodies[1].angularVelocity = spin;
        EXPECT_NEAR(rowVelocity(row, bodies), 0, 1e-12);
        bodies[1].angularVelocity = -spin;
        EXPECT_NEAR(rowVelocity(row, bodies), 2 * spin[k], 1e-12);
    }
}

TEST(JointFriction, UniversalFrictionActsAcrossShaftOneAndHingeFrictionAlongTheAxis) {
    {
        ConstraintRows rows;
        const JointRowRange range =
            writeJointRows(jointOf(ConstraintType::Universal, 0.5, 1), restingBodies(), JointRowSettings{}, rows);
        for (int k = 0; k < range.frictionRows; ++k)
            EXPECT_NEAR(rows[static_cast<std::size_t>(range.equalityRows + range.limitRows + k)].angularA.dot(Vec3::UnitX()), 0,
                        1e-12);
    }
    ConstraintRows rows;
    const JointRowRange range =
        writeJointRows(jointOf(ConstraintType::Hinge, 0.5, 1), restingBodies(), JointRowSettings{}, rows);
    ASSERT_EQ(range.frictionRows, 1);
    EXPECT_NEAR(std::fabs(rows[static_cast<std::size_t>(range.equalityRows + range.limitRows)].angularA.z()), 1, 1e-12);
}

}  // namespace
}  // namespace af::test
