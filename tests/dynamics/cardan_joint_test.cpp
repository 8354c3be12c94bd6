// The Cardan (Hooke) universal joint, our extension (FigureConstraint::cardan, joint_cardan.cpp):
// its angles are the turns about both arms, its limit rows come at the ends of each range, and
// swung hard it keeps its arms ⟂ and stops at each range's ends. Angles are measured here from
// the bodies' poses alone, with the formulas of docs/bench-scene.md §2, and compared with the engine's.

#include "joint_test_util.h"
#include "world_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace af {
namespace {

using test::deg;
using test::rad;
using test::turn;


// A Cardan joint between body 0 (arm a) and body 1 or the world (arm b ⟂ a), both arms in world
// space at spawn.
FigureConstraint cardanJoint(const Vec3& armA, const Vec3& armB, int body2) {
    FigureConstraint c = test::constraintOf(ConstraintType::Universal, body2);
    c.cardan = true;
    c.shafts[0] = armA;
    c.shafts[1] = armB;
    return c;
}

// A's orientation for the relative rotation R(b, θ0)·R(a, θ1) of A against B since spawn (a, b the
// arms in world space at spawn), B now at qB.
Quat orientationFor(Real theta0, Real theta1, const Vec3& a, const Vec3& b, const Quat& qA0, const Quat& qB0,
                    const Quat& qB) {
    return (qB * qB0.conjugate() * turn(b, deg(theta0)) * turn(a, deg(theta1)) * qA0).normalized();
}

TEST(CardanJoint, ItsAnglesAreTheTurnsAboutBsArmThenAsOwnAndItsArmsStayPerpendicular) {
    test::Random random(5);
    Real worstAngle = 0, worstArms = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const RigidPose poseA = random.pose(5), poseB = random.pose(5);
        const Vec3 b = random.direction();
        const Vec3 a = b.cross(random.direction()).normalized();
        const int body2 = trial % 2 ? 1 : kWorld;
        const Figure figure = test::twoBodyFigure(poseA, poseB, cardanJoint(a, b, body2));
        const Joint joint = makeJoints(figure).at(0);
        std::vector<RigidBody> bodies = test::spawnBodies(figure);
        const Quat qA0 = bodies[0].orientation;
        const Quat qB0 = body2 == kWorld ? Quat::Identity() : bodies[1].orientation;
        const Quat qB = body2 == kWorld ? Quat::Identity() : random.rotation();
        if (body2 != kWorld) bodies[1].orientation = qB;
        const Real theta0 = random.uniform(-3, 3), theta1 = random.uniform(-3, 3);
        bodies[0].orientation = orientationFor(theta0, theta1, a, b, qA0, qB0, qB);
        const std::array<Real, 2> angles = cardanAngles(joint, bodies);
        worstAngle = std::max({worstAngle, std::fabs(angles[0] - theta0), std::fabs(angles[1] - theta1)});
        worstArms = std::max(worstArms, jointAngularError(joint, bodies));
    }
    EXPECT_LT(worstAngle, 1e-12);
    EXPECT_LT(worstArms, 1e-12);
}

// The range [−20°, 40°] about B's arm: nothing far inside, one row (C = the distance to the nearer
// end, along that angle's gradient) within the margin of either end, and the limit is measured
// past the end.
TEST(CardanJoint, ALimitRowComesWithinTheMarginOfEachEndOfARange) {
    const Vec3 a = Vec3::UnitY(), b = Vec3::UnitX();
    FigureConstraint c = cardanJoint(a, b, kWorld);
    c.cardanLower = {-20, 0};
    c.cardanUpper = {40, 0};
    const Figure figure = test::twoBodyFigure({Vec3(0, 0, -3), Mat3::Identity()}, {}, c);
    const Joint joint = makeJoints(figure).at(0);
    std::vector<RigidBody> bodies = test::spawnBodies(figure);
    const Quat q0 = bodies[0].orientation;
    const JointRowSettings settings;
    const auto rowsAt = [&](Real degrees) {
        bodies[0].orientation = orientationFor(rad(degrees), rad(5), a, b, q0, Quat::Identity(), Quat::Identity());
        ConstraintRows rows;
        const JointRowRange range = writeJointRows(joint, bodies, settings, rows);
        EXPECT_EQ(range.equalityRows, 4);
        return std::pair(range.limitRows, range.limitRows ? rows[4] : ConstraintRow{});
    };
    const Real margin = deg(settings.limitMargin);
    EXPECT_EQ(rowsAt(10).first, 0);
    EXPECT_EQ(rowsAt(40 - 2 * margin).first, 0);
    for (const Real at : {40 - margin / 2, Real(41), -20 + margin / 2, Real(-21)}) {
        const auto [count, row] = rowsAt(at);
        ASSERT_EQ(count, 1) << at;
        const bool upper = at > 10;
        EXPECT_NEAR(row.error, rad(upper ? 40 - at : at + 20), 1e-12) << at;
        // Turning A about b towards the end closes the row: ω·J < 0 along the way in.
        EXPECT_NEAR(row.angularA.dot(b), upper ? -1 : 1, 1e-12) << at;
        EXPECT_NEAR(limitViolationDegrees(joint, bodies), std::max(Real(0), upper ? at - 40 : -20 - at), 1e-9) << at;
    }
}

// A box hangs from the world by a Cardan joint: the world carries arm b = X, the box arm a = Y,
// so the box may swing about X (θ0 in [−20°, 30°]) and about its own Y (θ1 in [−15°, 25°]) but
// never spin about the vertical. Thrown about both arms at once, it must reach both ranges' ends
// and stop there, its arms ⟂ and its anchor closed.
TEST(CardanJoint, SwungHardItKeepsItsArmsPerpendicularAndStopsAtBothRanges) {
    const Vec3 anchor(0, 0, 40);
    Figure figure = test::figureOfBlocks(
        {"origin"}, test::boxBodyText("bob", "origin", Vec3(3, 2, 8), Vec3(0, 0, 30)) +
                        "universalJoint \"hip\" { body1 \"bob\" body2 \"world\" anchor " + test::afVector(anchor) +
                        " shafts ( 0, 1, 0 ), ( 1, 0, 0 ) friction 0 }\n");
    FigureConstraint& c = figure.constraints.at(0);
    c.cardan = true;
    c.cardanLower = {-20, -15};
    c.cardanUpper = {30, 25};
    for (const Real speed : {1.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "speed × " << speed);
        Real reached[2][2] = {{0, 0}, {0, 0}};  // per angle: lowest, highest, over the throws
        Real armsOff = 0, overshoot = 0;
        for (const Vec3& throwAbout : {Vec3(6, -7, 0), Vec3(-6, 7, 0), Vec3(7, 6, 0), Vec3(-7, -6, 0)}) {
            World world(figure, test::dynamicsOnly());
            const RigidBody& bob = world.bodies()[0];
            const Vec3 spin = speed * throwAbout;
            world.setVelocity(0, spin.cross(bob.position - anchor), spin);
            const Quat q0 = bob.orientation;
            Real engineArmsOff = 0, ownArmsOff = 0, worstPoint = 0;
            for (int i = 0; i < 120; ++i) {
                world.step();
                const Quat q = world.bodies()[0].orientation * q0.conjugate();
                const Vec3 a = q * Vec3::UnitY(), b = Vec3::UnitX(), cross = Vec3::UnitZ();
                const Real theta0 = std::atan2(a.dot(cross), a.dot(Vec3::UnitY()));
                const Real theta1 = std::atan2(b.dot(q * cross), b.dot(q * b));
                ownArmsOff = std::max(ownArmsOff, std::fabs(std::asin(a.dot(b))));
                engineArmsOff = std::max(engineArmsOff, jointAngularError(world.joints()[0], world.bodies()));
                const std::array<Real, 2> engine = cardanAngles(world.joints()[0], world.bodies());
                EXPECT_NEAR(engine[0], theta0, 1e-9);
                EXPECT_NEAR(engine[1], theta1, 1e-9);
                for (int k = 0; k < 2; ++k) {
                    const Real t = deg(k == 0 ? theta0 : theta1);
                    reached[k][0] = std::min(reached[k][0], t);
                    reached[k][1] = std::max(reached[k][1], t);
                    overshoot = std::max({overshoot, c.cardanLower[k] - t, t - c.cardanUpper[k]});
                }
                worstPoint = std::max(worstPoint, world.maxJointError());
            }
            armsOff = std::max(armsOff, ownArmsOff);
            EXPECT_NEAR(engineArmsOff, ownArmsOff, 1e-12);
            EXPECT_LT(worstPoint, 1e-6);
            EXPECT_EQ(world.solverFailures(), 0);
        }
        std::printf("Cardan joint thrown four ways (× %.0f): angle 0 in [%.2f, %.2f], angle 1 in [%.2f, %.2f] deg, "
                    "overshoot %.3g deg, arms off ⟂ %.3g rad\n",
                    speed, reached[0][0], reached[0][1], reached[1][0], reached[1][1], overshoot, armsOff);
        for (int k = 0; k < 2; ++k) {
            EXPECT_LT(reached[k][0], c.cardanLower[k] + 0.5) << "angle " << k << " did not reach its lower end";
            EXPECT_GT(reached[k][1], c.cardanUpper[k] - 0.5) << "angle " << k << " did not reach its upper end";
        }
        EXPECT_LT(overshoot, 3.0) << "degrees past a range in a hard swing";
        EXPECT_LT(armsOff, 1e-8) << "rad";
    }
}

}  // namespace
}  // namespace af
