// Limits: a limit row appears exactly when the joint is past its limit or within the margin of
// it, its error is the signed distance to the limit (negative outside), moving along it leads
// back inside, and the angles mean what docs/figures.md §3.8 says (full cone angle, pyramid faces and roll,
// the hinge's V). Angles are exact to 1e-9 rad; tests stay ≥ 0.1° away from the margin's edge.

#include "dynamics/joint_parts.h"
#include "joint_test_util.h"

namespace af::test {
namespace {

std::vector<RigidBody> hangingTurned(const Vec3& axis, Real degrees) {
    std::vector<RigidBody> bodies = {bodyAt(kHanging), bodyAt({})};
    turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(degrees), axis.normalized())), Vec3::Zero());
    return bodies;
}

struct LimitRows {
    JointRowRange range;
    ConstraintRows rows;
    const ConstraintRow& limit(int k = 0) const {
        return rows[static_cast<std::size_t>(range.first + range.equalityRows + k)];
    }
};

LimitRows limitRows(const Joint& j, const std::vector<RigidBody>& bodies) {
    LimitRows out;
    out.range = writeJointRows(j, bodies, JointRowSettings{}, out.rows);
    return out;
}

// Turning A a little along the row's angular direction (what a positive impulse does) must
// bring the joint's violation down.
void expectRowLeadsBackInside(const Joint& j, std::vector<RigidBody> bodies, const ConstraintRow& row) {
    const Real before = limitViolationDegrees(j, bodies);
    ASSERT_GT(before, 0);
    turnBody(bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(0.5), row.angularA.normalized())));
    EXPECT_LT(limitViolationDegrees(j, bodies), before - 0.4);
}

TEST(JointLimit, ConeHalfAngleIsHalfTheFilesAngleAndItsRowAppearsWithinTheMargin) {
    const Joint j = hangingBall(LimitType::Cone, {60, 0, 0});
    EXPECT_NEAR(j.cone.halfAngle, rad(30), 1e-12);
    const Real marginDegrees = kLimitMarginRadians * 180 / kPi;
    for (const Real tilt : {0.0, 10.0, 29.0, 29.5, 29.9, 30.0, 30.5, 45.0, 120.0}) {
        SCOPED_TRACE(tilt);
        const std::vector<RigidBody> bodies = hangingTurned(Vec3(1, 2, 0), tilt);
        const LimitRows r = limitRows(j, bodies);
        EXPECT_EQ(r.range.limitRows, 30 - tilt < marginDegrees ? 1 : 0);
        EXPECT_NEAR(limitViolationDegrees(j, bodies), std::max(0.0, tilt - 30), 1e-9);
        if (r.range.limitRows == 0) continue;
        const ConstraintRow& row = r.limit();
        EXPECT_NEAR(row.error, rad(30 - tilt), 1e-9);
        EXPECT_EQ(row.lo, 0);
        EXPECT_EQ(row.hi, kInfinity);
        EXPECT_EQ(row.target, 0);
        EXPECT_EQ(row.bodyB, kWorldBody);
        if (tilt > 30) expectRowLeadsBackInside(j, bodies, row);
    }
}

TEST(JointLimit, PyramidFacesLimitEachPlaneToHalfItsAngle) {
    // Axis −Z: Doom's angles (pitch 90, yaw 0, roll 0) give base = left = +Y, so a1 (40) limits
    // the tilt in the Y–Z plane (turns about X) and a2 (60) the tilt in the X–Z plane.
    const Joint j = hangingBall(LimitType::Pyramid, {40, 60, 0});
    EXPECT_LT((j.pyramid.basis.col(0) - Vec3(0, 1, 0)).norm(), 1e-12);
    EXPECT_LT((j.pyramid.basis.col(2) - Vec3(0, 0, -1)).norm(), 1e-12);
    struct Case {
        Vec3 axis;
        Real tilt;
        Real violation;
    };
    for (const Case& c : {Case{Vec3::UnitX(), 19, 0}, Case{Vec3::UnitX(), 25, 5}, Case{-Vec3::UnitX(), 25, 5},
                          Case{Vec3::UnitY(), 25, 0}, Case{Vec3::UnitY(), 29, 0}, Case{Vec3::UnitY(), 35, 5},
                          Case{-Vec3::UnitY(), 40, 10}}) {
        SCOPED_TRACE(testing::Message() << "about " << c.axis.transpose() << " by " << c.tilt);
        const std::vector<RigidBody> bodies = hangingTurned(c.axis, c.tilt);
        const LimitRows r = limitRows(j, bodies);
        EXPECT_NEAR(limitViolationDegrees(j, bodies), c.violation, 1e-9);
        EXPECT_EQ(r.range.limitRows, c.violation > 0 ? 1 : 0);
        if (c.violation > 0) {
            EXPECT_NEAR(r.limit().error, -rad(c.violation), 1e-9);
            expectRowLeadsBackInside(j, bodies, r.limit());
        }
    }
    // Past both faces at once: a row for each.
    std::vector<RigidBody> corner = hangingTurned(Vec3::UnitX(), 25);
    turnBodyAbout(corner, 0, Quat(Eigen::AngleAxis<Real>(rad(40), Vec3::UnitY())), Vec3::Zero());
    EXPECT_EQ(limitRows(j, corner).range.limitRows, 2);
}

TEST(JointLimit, PyramidRollTurnsTheFacesAboutTheAxis) {
    // Rolled by 90°, base = +X: the narrow face (a1 = 40) now limits turns about Y.
    const Joint j = hangingBall(LimitType::Pyramid, {40, 60, 90});
    EXPECT_LT((j.pyramid.basis.col(0) - Vec3(1, 0, 0)).norm(), 1e-12);
    EXPECT_NEAR(limitViolationDegrees(j, hangingTurned(Vec3::UnitY(), 25)), 5, 1e-9);
    EXPECT_NEAR(limitViolationDegrees(j, hangingTurned(Vec3::UnitX(), 25)), 0, 1e-9);
}

// A hinge about `axis` through the origin between A (random pose) and B (random pose or world).
Joint hingeWith(const Vec3& axis, Real3 angles, const RigidPose& a, const RigidPose& b, int body2) {
    FigureConstraint c = constraintOf(ConstraintType::Hinge, body2);
    c.anchor = Vec3::Zero();
    c.axis = axis;
    c.limit = LimitType::Cone;
    c.limitAngles = angles;
    return makeJoints(twoBodyFigure(a, b, c)).at(0);
}

TEST(JointLimit, HingeVIntervalIsDoomsFormula) {
    // θ (Doom's clockwise angle about the axis) ∈ [a1 − a3 − a2/2, a1 − a3 + a2/2].
    Random random(3);
    for (const Real3 a : {Real3{70, 150, 0}, Real3{-12.5, 65, 0}, Real3{0, 90, 30}, Real3{20, 40, -50},
                          Real3{170, 60, -170}}) {
        SCOPED_TRACE(testing::Message() << a[0] << ", " << a[1] << ", " << a[2]);
        const Vec3 axis = random.direction();
        const RigidPose poseA = random.pose(3), poseB = random.pose(3);
        const Joint j = hingeWith(axis, a, poseA, poseB, 1);
        const Real lo = a[0] - a[2] - a[1] / 2, hi = a[0] - a[2] + a[1] / 2;
        struct Probe {
            Real theta, violation;
        };
        for (const Probe p : {Probe{lo - 1, 1}, Probe{lo + 1, 0}, Probe{hi - 1, 0}, Probe{hi + 2, 2}}) {
            std::vector<RigidBody> bodies = {bodyAt(poseA), bodyAt(poseB)};
            // θ clockwise seen from the tip of the axis is a right-handed turn by −θ.
            turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(-rad(p.theta), axis)), Vec3::Zero());
            EXPECT_NEAR(limitViolationDegrees(j, bodies), p.violation, 1e-9) << "θ = " << p.theta;
        }
    }
}

TEST(JointLimit, HingeLimitAgreesWithDoomsConeAroundTheLimitDirection) {
    // Doom: limit direction = left turned clockwise by a1 (on B), shaft = left turned clockwise by
    // a3 (on A), a cone of full angle a2 around the former. Any `left` ⟂ the axis will do.
    Random random(5);
    for (int trial = 0; trial < 6; ++trial) {
        const Vec3 h = random.direction();
        const Real3 a{random.uniform(-180, 180), random.uniform(10, 300), random.uniform(-180, 180)};
        const RigidPose poseA = random.pose(3);
        const Joint j = hingeWith(h, a, poseA, {}, kWorld);
        const Vec3 left = h.cross(random.direction()).normalized();
        const Vec3 limitDirection = Eigen::AngleAxis<Real>(-rad(a[0]), h) * left;
        const Vec3 shaft = Eigen::AngleAxis<Real>(-rad(a[2]), h) * left;
        for (Real phi = -180; phi < 180; phi += 7) {
            std::vector<RigidBody> bodies = {bodyAt(poseA), bodyAt({})};
            const Quat turn(Eigen::AngleAxis<Real>(rad(phi), h));
            turnBodyAbout(bodies, 0, turn, Vec3::Zero());
            const Vec3 turnedShaft = turn * shaft;
            const Real apart = std::atan2(turnedShaft.cross(limitDirection).norm(), turnedShaft.dot(limitDirection)) * 180 / kPi;
            EXPECT_NEAR(limitViolationDegrees(j, bodies), std::max(0.0, apart - a[1] / 2), 1e-7)
                << "trial " << trial << ", φ = " << phi;
            EXPECT_NEAR(std::remainder(hingeAngle(j, bodies) - rad(phi), 2 * kPi), 0, 1e-9);  // ±180° alike
        }
    }
}

TEST(JointLimit, HingeLimitRowAppearsWithinTheMarginAndTurnsBack) {
    const Vec3 axis(0, 1, 0);
    const Joint j = hingeWith(axis, {0, 90, 0}, kHanging, {}, kWorld);  // |angle| ≤ 45°
    for (const Real phi : {0.0, 44.0, 44.7, 50.0, -44.0, -44.7, -50.0}) {
        SCOPED_TRACE(phi);
        std::vector<RigidBody> bodies = {bodyAt(kHanging), bodyAt({})};
        turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(phi), axis)), Vec3::Zero());
        const LimitRows r = limitRows(j, bodies);
        const bool near = std::fabs(phi) > 45 - kLimitMarginRadians * 180 / kPi;
        ASSERT_EQ(r.range.limitRows, near ? 1 : 0);
        if (!near) continue;
        EXPECT_NEAR(r.limit().error, rad(45 - std::fabs(phi)), 1e-9);
        EXPECT_EQ(r.limit().lo, 0);
        if (std::fabs(phi) > 45) expectRowLeadsBackInside(j, bodies, r.limit());
    }
}

// The writers skip the exact angle of a joint surely inside its limit, judged by roughAtan2:
// rows still appear exactly from the margin's edge on, however close to it.
TEST(JointLimit, LimitRowsAppearFromTheMarginsEdgeOnToWithin1e7Radians) {
    const Vec3 axis(0, 1, 0);
    const Joint hinge = hingeWith(axis, {0, 90, 0}, kHanging, {}, kWorld);  // |angle| ≤ 45°
    const Joint cone = hangingBall(LimitType::Cone, {60, 0, 0});         // tilt ≤ 30°
    for (const Real beyond : {-1e-7, 1e-7}) {
        SCOPED_TRACE(beyond);
        const Real hingeTurn = rad(45) - kLimitMarginRadians + beyond;
        for (const Real sign : {-1.0, 1.0}) {
            std::vector<RigidBody> bodies = {bodyAt(kHanging), bodyAt({})};
            turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(sign * hingeTurn, axis)), Vec3::Zero());
            EXPECT_EQ(limitRows(hinge, bodies).range.limitRows, beyond > 0 ? 1 : 0);
        }
        const Real coneTilt = rad(30) - kLimitMarginRadians + beyond;
        EXPECT_EQ(limitRows(cone, hangingTurned(Vec3(1, 2, 0), coneTilt * 180 / kPi)).range.limitRows, beyond > 0 ? 1 : 0);
    }
}

TEST(JointLimit, RoughAtan2IsWithin12MicroradiansOfAtan2AllRoundAndAtTheAxes) {
    std::mt19937 random(7);
    std::uniform_real_distribution<Real> coordinate(-2, 2);
    for (int k = 0; k < 100000; ++k) {
        const Real y = coordinate(random);
        const Real x = coordinate(random);
        ASSERT_NEAR(joint_detail::roughAtan2(y, x), std::atan2(y, x), 1.2e-5) << "y = " << y << ", x = " << x;
    }
    for (const Real y : {0.0, -0.0, 1.0, -1.0})
        for (const Real x : {0.0, -0.0, 1.0, -1.0}) EXPECT_NEAR(joint_detail::roughAtan2(y, x), std::atan2(y, x), 1.2e-5);
}

TEST(JointLimit, BallTwistIsTheTurnAboutTheShaftWithTheSwingTakenOut) {
    // Hanging along −Z, cone axis −Z, twist limit ±30°. Turn the bob about its own shaft by τ,
    // then swing it by σ about a horizontal axis: the twist is τ whatever the swing, and a row
    // appears within the margin of ±30°, one per side.
    FigureConstraint c = constraintOf(ConstraintType::BallAndSocket, kWorld);
    c.anchor = Vec3::Zero();
    c.limit = LimitType::Cone;
    c.limitAxis = Vec3(0, 0, -1);
    c.shafts[0] = Vec3(0, 0, -1);
    c.limitAngles = {170, 0, 0};
    c.twistLimit = 30;
    const Joint j = makeJoints(twoBodyFigure(kHanging, {}, c)).at(0);
    for (const Real swing : {0.0, 25.0, 70.0})
        for (const Real twist : {-45.0, -29.0, 0.0, 12.0, 29.9, 31.0}) {
            SCOPED_TRACE(testing::Message() << "swing " << swing << ", twist " << twist);
            std::vector<RigidBody> bodies = {bodyAt(kHanging), bodyAt({})};
            turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(twist), Vec3(0, 0, -1))), Vec3::Zero());
            turnBodyAbout(bodies, 0, Quat(Eigen::AngleAxis<Real>(rad(swing), Vec3(1, 1, 0).normalized())), Vec3::Zero());
            EXPECT_NEAR(twistAngle(j, bodies), rad(twist), 1e-11);
            EXPECT_NEAR(limitViolationDegrees(j, bodies), std::max(0.0, std::fabs(twist) - 30), 1e-9);
            const LimitRows r = limitRows(j, bodies);
            const Real marginDegrees = kLimitMarginRadians * 180 / kPi;
            EXPECT_EQ(r.range.limitRows, 30 - std::fabs(twist) < marginDegrees ? 1 : 0);
            if (r.range.limitRows == 1 && std::fabs(twist) > 30) expectRowLeadsBackInside(j, bodies, r.limit());
        }
}

TEST(JointLimit, UniversalLimitActsOnShaftOne) {
    FigureConstraint c = constraintOf(ConstraintType::Universal, kWorld);
    c.anchor = Vec3::Zero();
    c.shafts[0] = Vec3(0, 0, -1);  // into A, which hangs below
    c.shafts[1] = Vec3(0, 0, 1);
    c.limit = LimitType::Cone;
    c.limitAxis = Vec3(0, 0, -1);
    c.limitAngles = {50, 0, 0};
    const Joint j = makeJoints(twoBodyFigure(kHanging, {}, c)).at(0);
    EXPECT_NEAR(limitViolationDegrees(j, hangingTurned(Vec3::UnitX(), 24)), 0, 1e-9);
    const std::vector<RigidBody> bodies = hangingTurned(Vec3::UnitX(), 31);
    EXPECT_NEAR(limitViolationDegrees(j, bodies), 6, 1e-9);
    const LimitRows r = limitRows(j, bodies);
    ASSERT_EQ(r.range.limitRows, 1);
    expectRowLeadsBackInside(j, bodies, r.limit());
}

TEST(JointLimit, SpringLengthRowsAppearNearMinAndMaxAndPushBack) {
    FigureConstraint c = constraintOf(ConstraintType::Spring, kWorld);
    c.anchor = Vec3::Zero();  // on A, at its centre of mass
    c.anchor2 = Vec3(5, 0, 0);
    c.minLength = 2;
    c.maxLength = 8;
    const Joint j = makeJoints(twoBodyFigure({}, {}, c)).at(0);
    for (const Real length : {1.0, 1.99, 2.04, 2.1, 5.0, 7.9, 7.96, 8.5}) {
        SCOPED_TRACE(length);
        const std::vector<RigidBody> bodies = {bodyAt({Vec3(5 - length, 0, 0), Mat3::Identity()}), bodyAt({})};
        EXPECT_NEAR(springLength(j, bodies), length, 1e-12);
        const LimitRows r = limitRows(j, bodies);
        const bool nearMin = length - 2 < kSpringLimitMargin, nearMax = 8 - length < kSpringLimitMargin;
        ASSERT_EQ(r.range.limitRows, (nearMin ? 1 : 0) + (nearMax ? 1 : 0));
        EXPECT_EQ(r.range.equalityRows, 0);
        EXPECT_NEAR(jointError(j, bodies), std::max({0.0, 2 - length, length - 8}), 1e-12);
        if (r.range.limitRows == 0) continue;
        const ConstraintRow& row = r.limit();
        EXPECT_NEAR(row.error, nearMin ? length - 2 : 8 - length, 1e-12);
        // A positive impulse moves A along linearA: away from the anchor (−X) when too short.
        EXPECT_NEAR(row.linearA.x(), nearMin ? -1 : 1, 1e-12);
    }
}

}  // namespace
}  // namespace af::test
