// What each joint type holds and lets go: row counts, the world side, the slider's frame (Doom's
// offset quirk fixed), the universal joint's twist (homokinetic), the fixed joint's rotation,
// and the measurements. Lengths exact to 1e-9, angles to 1e-9 rad.

#include "joint_test_util.h"

namespace af::test {
namespace {


TEST(JointTypes, EqualityRowCountsPerType) {
    struct Case {
        ConstraintType type;
        int rows;
    };
    for (const Case c : {Case{ConstraintType::Fixed, 6}, Case{ConstraintType::BallAndSocket, 3},
                         Case{ConstraintType::Universal, 4}, Case{ConstraintType::Hinge, 5}, Case{ConstraintType::Slider, 5},
                         Case{ConstraintType::Spring, 0}}) {
        FigureConstraint fc = constraintOf(c.type);
        fc.anchor = Vec3(1, 0, 0);
        fc.anchor2 = Vec3(2, 0, 0);
        fc.shafts[1] = -fc.shafts[0];
        const Figure f = twoBodyFigure({}, {Vec3(2, 0, 0), Mat3::Identity()}, fc);
        ConstraintRows rows;
        const JointRowRange range = writeJointRows(makeJoints(f).at(0), spawnBodies(f), JointRowSettings{}, rows);
        EXPECT_EQ(range.equalityRows, c.rows) << toString(c.type);
        EXPECT_EQ(static_cast<int>(rows.size()), range.total()) << toString(c.type);
    }
}

TEST(JointTypes, RowsAgainstTheWorldHaveZeroBodyBBlocks) {
    Random random(21);
    for (const ConstraintType type : {ConstraintType::Fixed, ConstraintType::BallAndSocket, ConstraintType::Universal,
                                      ConstraintType::Hinge, ConstraintType::Slider, ConstraintType::Spring}) {
        FigureConstraint c = randomConstraint(type, kWorld, random);
        c.limit = type == ConstraintType::Hinge ? LimitType::Cone : LimitType::Pyramid;
        c.limitAngles = {20, 30, 0};
        c.minLength = 1;
        c.maxLength = 10;
        c.friction = 1;
        auto [j, bodies] = posedJoint(c, random);
        ConstraintRows rows;
        writeJointRows(j, bodies, allLimitRows(), rows);
        ASSERT_GT(rows.size(), 0u) << toString(type);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            EXPECT_EQ(rows[i].bodyA, 0);
            EXPECT_EQ(rows[i].bodyB, kWorldBody);
            EXPECT_EQ(rows[i].linearB, Vec3::Zero()) << toString(type) << " row " << i;
            EXPECT_EQ(rows[i].angularB, Vec3::Zero()) << toString(type) << " row " << i;
        }
    }
}

TEST(JointTypes, RowsBetweenBodiesNameBothBodies) {
    FigureConstraint c = constraintOf(ConstraintType::BallAndSocket, 1);
    const Figure f = twoBodyFigure({}, {Vec3(2, 0, 0), Mat3::Identity()}, c);
    ConstraintRows rows;
    writeJointRows(makeJoints(f).at(0), spawnBodies(f), JointRowSettings{}, rows);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(rows[i].bodyA, 0);
        EXPECT_EQ(rows[i].bodyB, 1);
        EXPECT_GT(rows[i].cfm, 0);
        EXPECT_LT(rows[i].cfm, 1e-6);  // relative softness 1e-9 of a diagonal of order 1
    }
}

TEST(JointTypes, SliderKeepsItsLineWhenTheBodiesAreTurnedDifferently) {
    // Doom stores the offset in body1's frame and reads it in body2's; with B turned 90° from A
    // that would move the line. Ours: zero error at spawn, and sliding along the axis is free.
    const RigidPose a{Vec3(0, 0, 0), turn(Vec3::UnitZ(), 90).toRotationMatrix()};
    const RigidPose b{Vec3(3, 1, 0), turn(Vec3::UnitX(), -60).toRotationMatrix()};
    FigureConstraint c = constraintOf(ConstraintType::Slider);
    c.axis = Vec3(1, 1, 0).normalized();
    const Figure f = twoBodyFigure(a, b, c);
    const Joint j = makeJoints(f).at(0);
    std::vector<RigidBody> bodies = spawnBodies(f);
    EXPECT_NEAR(jointError(j, bodies), 0, 1e-9);
    bodies[0].position += 2.5 * c.axis;
    ConstraintRows rows;
    writeJointRows(j, bodies, JointRowSettings{}, rows);
    for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i].error, 0, 1e-9) << "row " << i;
    bodies[0].position += Vec3(0, 0, 0.75);  // off the axis
    EXPECT_NEAR(jointError(j, bodies), 0.75, 1e-9);
    // The line turns with B: turning B about its centre carries the line with it.
    bodies = spawnBodies(f);
    const Quat q = turn(Vec3(0, 0, 1), 30);
    turnBody(bodies, 1, q);
    bodies[0].position = bodies[1].position + q * (a.position - b.position) + 1.5 * (q * c.axis);
    turnBody(bodies, 0, q);
    EXPECT_NEAR(jointError(j, bodies), 0, 1e-9);
    EXPECT_NEAR(jointAngularError(j, bodies), 0, 1e-9);
}

TEST(JointTypes, FixedJointMeasuresDisplacementAndRotation) {
    const RigidPose a{Vec3(1, 2, 3), turn(Vec3(1, 2, 0), 40).toRotationMatrix()};
    const RigidPose b{Vec3(-2, 0, 1), turn(Vec3(0, 1, 1), -70).toRotationMatrix()};
    const Figure f = twoBodyFigure(a, b, constraintOf(ConstraintType::Fixed));
    const Joint j = makeJoints(f).at(0);
    std::vector<RigidBody> bodies = spawnBodies(f);
    EXPECT_NEAR(jointError(j, bodies), 0, 1e-9);
    EXPECT_NEAR(jointAngularError(j, bodies), 0, 1e-9);
    turnBody(bodies, 0, turn(Vec3(3, -1, 2), 12));
    bodies[0].position += Vec3(0, 0.5, 0);
    EXPECT_NEAR(jointError(j, bodies), 0.5, 1e-9);
    EXPECT_NEAR(jointAngularError(j, bodies), rad(12), 1e-9);
}

// A universal joint at the origin: A above along +Z (shaft 1 = +Z points into A), B below.
struct UniversalScene {
    Figure figure;
    Joint joint;
};

UniversalScene universalScene() {
    FigureConstraint c = constraintOf(ConstraintType::Universal);
    c.anchor = Vec3::Zero();
    c.shafts[0] = Vec3(0, 0, 1);
    c.shafts[1] = Vec3(0, 0, -1);
    UniversalScene s;
    s.figure = twoBodyFigure({Vec3(0, 0, 5), Mat3::Identity()}, {Vec3(0, 0, -5), Mat3::Identity()}, c);
    s.joint = makeJoints(s.figure).at(0);
    return s;
}

TEST(JointTypes, UniversalJointLetsBothBodiesSwingWithoutTwist) {
    const UniversalScene s = universalScene();
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-0.3, 1, 0)}) {
        for (const Real degrees : {10.0, 45.0, 80.0}) {
            std::vector<RigidBody> bodies = spawnBodies(s.figure);
            turnBodyAbout(bodies, 0, turn(axis, degrees), Vec3::Zero());
            turnBodyAbout(bodies, 1, turn(axis, -degrees / 3), Vec3::Zero());
            ConstraintRows rows;
            writeJointRows(s.joint, bodies, JointRowSettings{}, rows);
            for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(rows[i].error, 0, 1e-9) << degrees << "°, row " << i;
            EXPECT_NEAR(jointAngularError(s.joint, bodies), 0, 1e-9);
        }
    }
}

TEST(JointTypes, UniversalJointMeasuresTwistAboutTheShaftsAfterAnySwing) {
    // A twisted by τ about its own shaft, then both swung: the twist reads τ whatever the swing
    // (constant velocity), where a Cardan cross would read up to several degrees off.
    const UniversalScene s = universalScene();
    for (const Real twist : {5.0, 30.0, -60.0}) {
        for (const Real swing : {0.0, 30.0, 70.0}) {
            std::vector<RigidBody> bodies = spawnBodies(s.figure);
            turnBody(bodies, 0, turn(Vec3::UnitZ(), twist));
            turnBodyAbout(bodies, 0, turn(Vec3(1, 2, 0), swing), Vec3::Zero());
            turnBodyAbout(bodies, 0, turn(Vec3(0, 1, 0), -swing / 2), Vec3::Zero());
            turnBodyAbout(bodies, 1, turn(Vec3(0, 1, 0), -swing / 2), Vec3::Zero());
            EXPECT_NEAR(jointAngularError(s.joint, bodies), rad(std::fabs(twist)), 1e-9) << twist << "°, swing " << swing;
        }
    }
}

TEST(JointTypes, HingeMeasuresAxisMisalignmentAndAngle) {
    FigureConstraint c = constraintOf(ConstraintType::Hinge, kWorld);
    c.anchor = Vec3::Zero();
    c.axis = Vec3(0, 1, 0);
    const Figure f = twoBodyFigure({Vec3(0, 0, -4), Mat3::Identity()}, {}, c);
    const Joint j = makeJoints(f).at(0);
    std::vector<RigidBody> bodies = spawnBodies(f);
    turnBodyAbout(bodies, 0, turn(Vec3(0, 1, 0), 35), Vec3::Zero());
    EXPECT_NEAR(hingeAngle(j, bodies), rad(35), 1e-9);
    EXPECT_NEAR(jointAngularError(j, bodies), 0, 1e-9);
    EXPECT_NEAR(jointError(j, bodies), 0, 1e-9);
    turnBodyAbout(bodies, 0, turn(Vec3(1, 0, 0), 3), Vec3::Zero());
    EXPECT_NEAR(jointAngularError(j, bodies), rad(3), 1e-9);
}

}  // namespace
}  // namespace af::test
