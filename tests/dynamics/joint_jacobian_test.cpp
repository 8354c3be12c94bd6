// Every row's Jacobian is the time derivative of its error: at random poses (joints violated,
// limits written whatever the margin) and random velocities, J·v equals the central difference
// (C(t + h) − C(t − h)) / 2h of the row's error along the motion, for every joint type, against
// a second body and against the world. h = 1e-6 s; tolerance 1e-6·(1 + |J·v|), far above the
// difference's own error (~1e-9 here) and far below any wrong term (≥ 1e-2).

#include "joint_test_util.h"

#include <functional>

namespace af::test {
namespace {

constexpr Real kStep = 1e-6;
constexpr Real kTolerance = 1e-6;
constexpr int kTrials = 40;

using ConstraintMaker = std::function<FigureConstraint(Random&, int body2)>;

// Runs kTrials random poses of a figure whose constraint `make` builds; returns rows checked.
int checkRowDerivatives(const ConstraintMaker& make, int body2, unsigned seed) {
    Random random(seed);
    int checked = 0;
    for (int trial = 0; trial < kTrials; ++trial) {
        const RigidPose poseA = random.pose(5), poseB = random.pose(5);
        const Figure figure = twoBodyFigure(poseA, poseB, make(random, body2));
        const Joint joint = makeJoints(figure).at(0);

        // Knock the joint out of place so the errors are not zero, then set it moving.
        std::vector<RigidBody> bodies = spawnBodies(figure);
        for (RigidBody& b : bodies) {
            b.position += random.vector(1);
            b.orientation = (random.turn(Real(0.6)) * b.orientation).normalized();
            b.linearVelocity = random.vector(3);
            b.angularVelocity = random.vector(2);
        }
        ConstraintRows now, later, earlier;
        const JointRowSettings settings = allLimitRows();
        writeJointRows(joint, bodies, settings, now);
        writeJointRows(joint, advanced(bodies, kStep), settings, later);
        writeJointRows(joint, advanced(bodies, -kStep), settings, earlier);
        EXPECT_EQ(now.size(), later.size());
        EXPECT_EQ(now.size(), earlier.size());
        if (now.size() != later.size() || now.size() != earlier.size()) continue;
        for (std::size_t i = 0; i < now.size(); ++i) {
            const Real cdot = rowVelocity(now[i], bodies);
            const Real difference = (later[i].error - earlier[i].error) / (2 * kStep);
            EXPECT_NEAR(cdot, difference, kTolerance * (1 + std::fabs(cdot)))
                << toString(joint.type) << " row " << i << " of " << now.size() << ", trial " << trial;
            ++checked;
        }
    }
    return checked;
}

void expectDerivatives(const ConstraintMaker& make, int rowsPerJoint) {
    EXPECT_EQ(checkRowDerivatives(make, 1, 11), kTrials * rowsPerJoint) << "against a body";
    EXPECT_EQ(checkRowDerivatives(make, kWorld, 12), kTrials * rowsPerJoint) << "against the world";
}

FigureConstraint withAnchor(ConstraintType type, Random& random, int body2) {
    FigureConstraint c = constraintOf(type, body2);
    c.anchor = random.vector(4);
    c.friction = 0.5;  // no friction rows anyway: lastImpulse is 0
    return c;
}

TEST(JointJacobian, FixedRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives([](Random& r, int body2) { return withAnchor(ConstraintType::Fixed, r, body2); }, 6);
}

TEST(JointJacobian, BallRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives([](Random& r, int body2) { return withAnchor(ConstraintType::BallAndSocket, r, body2); }, 3);
}

TEST(JointJacobian, BallConeLimitRowIsTheDerivativeOfItsError) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = withAnchor(ConstraintType::BallAndSocket, r, body2);
            c.limit = LimitType::Cone;
            c.limitAxis = r.direction();
            c.shafts[0] = r.direction();
            c.limitAngles = {60, 0, 0};
            return c;
        },
        4);
}

TEST(JointJacobian, BallPyramidLimitRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = withAnchor(ConstraintType::BallAndSocket, r, body2);
            c.limit = LimitType::Pyramid;
            c.limitAxis = r.direction();
            c.shafts[0] = r.direction();
            c.limitAngles = {50, 80, 30};
            return c;
        },
        5);
}

TEST(JointJacobian, BallTwistLimitRowsAreTheDerivativeOfTheirErrors) {
    // Both twist rows (allLimitRows), with a cone axis and without one (B's copy of the shaft).
    // The cone axis stays within ~45° of the shaft, so the knocked poses keep b·c > −1.
    for (const LimitType limit : {LimitType::Cone, LimitType::None}) {
        expectDerivatives(
            [limit](Random& r, int body2) {
                FigureConstraint c = withAnchor(ConstraintType::BallAndSocket, r, body2);
                c.shafts[0] = r.direction();
                c.limit = limit;
                c.limitAxis = r.turn(0.8) * c.shafts[0];
                c.limitAngles = {120, 0, 0};
                c.twistLimit = 40;
                return c;
            },
            limit == LimitType::Cone ? 6 : 5);
    }
}

FigureConstraint universal(Random& r, int body2, LimitType limit) {
    FigureConstraint c = withAnchor(ConstraintType::Universal, r, body2);
    c.shafts[0] = r.direction();
    c.shafts[1] = -(r.turn(1.0) * c.shafts[0]);  // bent by up to ~57°
    c.limit = limit;
    c.limitAxis = r.direction();
    c.limitAngles = limit == LimitType::Cone ? Real3{70, 0, 0} : Real3{40, 60, -20};
    return c;
}

TEST(JointJacobian, UniversalRowsAndTwistRowAreTheDerivativeOfTheirErrors) {
    expectDerivatives([](Random& r, int body2) { return universal(r, body2, LimitType::None); }, 4);
}

TEST(JointJacobian, UniversalConeAndPyramidLimitRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives([](Random& r, int body2) { return universal(r, body2, LimitType::Cone); }, 5);
    expectDerivatives([](Random& r, int body2) { return universal(r, body2, LimitType::Pyramid); }, 6);
}

// Both angle ranges are written (allLimitRows), and knocked out of place the arms are not ⟂.
TEST(JointJacobian, CardanArmsRowAndBothAngleLimitRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = withAnchor(ConstraintType::Universal, r, body2);
            c.cardan = true;
            c.shafts[1] = r.direction();
            c.shafts[0] = c.shafts[1].unitOrthogonal();
            c.cardanLower = {-20, -35};
            c.cardanUpper = {40, 10};
            return c;
        },
        6);
}

TEST(JointJacobian, HingeRowsAndVLimitRowAreTheDerivativeOfTheirErrors) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = withAnchor(ConstraintType::Hinge, r, body2);
            c.axis = r.direction();
            c.limit = LimitType::Cone;
            c.limitAngles = {30, 100, 10};
            return c;
        },
        6);
}

TEST(JointJacobian, SliderRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = constraintOf(ConstraintType::Slider, body2);
            c.axis = r.direction();
            return c;
        },
        5);
}

TEST(JointJacobian, SpringLengthLimitRowsAreTheDerivativeOfTheirErrors) {
    expectDerivatives(
        [](Random& r, int body2) {
            FigureConstraint c = constraintOf(ConstraintType::Spring, body2);
            c.anchor = r.vector(4);
            c.anchor2 = r.vector(4);
            c.stretch = c.compress = 10;
            c.restLength = 4;
            c.minLength = 1;
            c.maxLength = 9;
            return c;
        },
        2);
}

}  // namespace
}  // namespace af::test
