// Physics of each constraint type over whole steps (issue 4, "Tests of physics"): limits stop a
// hard swing at their angles, a universal joint transmits spin without twist, a slider slides
// straight, a fixed pair tumbles as one body, a spring obeys Doom's quadratic law and its length
// limits, and joint friction acts as Coulomb friction bounded by f times the joint impulse.
//
// Every angle, drift and twist is measured twice: with the engine's own measure (jointError,
// jointAngularError, limitViolationDegrees, hingeAngle, springLength) and with a measure computed
// here from the bodies' poses alone, which must agree. Each test states its tolerance; each checks
// that the situation it tests really happened (the limit was reached, the joint was bent, the
// pair tumbled), so that it can fail. Doom units: gravity 1066 units/s², 60 Hz steps.

#include "joint_test_util.h"
#include "world_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

namespace af {
namespace {

using test::afVector;
using test::boxBodyText;
using test::deg;
using test::figureOfBlocks;
using test::rad;
using test::turn;

Real angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }
// The angle of a rotation, radians in [0, π].
Real rotationAngle(const Quat& q) { return 2 * std::atan2(q.vec().norm(), std::fabs(q.w())); }

// Sets body `index` turning rigidly about `pivot` at angular velocity `omega`.
void spinAbout(World& world, int index, const Vec3& pivot, const Vec3& omega) {
    const RigidBody& b = world.bodies()[static_cast<std::size_t>(index)];
    world.setVelocity(index, omega.cross(b.position - pivot), omega);
}

// Air friction is a figure's setting; the tests set it on the built world's bodies instead.
void setAirFriction(World& world, Real friction) {
    for (RigidBody& b : detail::WorldAccess::bodies(world)) b.linearFriction = b.angularFriction = friction;
}

// ---------------------------------------------------------------------------------------------
// Limits. A cube bob (half size 2, density 1: mass 64) hangs 30 units from a world joint; it is
// thrown into its limit (an initial angular velocity of 8–10 rad/s: 240–290 units/s at the bob,
// 8–9° per step; then three times that) and swings freely under gravity for `swingSteps`, then air
// friction is switched on and it settles, resting against the limit because gravity pulls it
// outside (the limit or gravity is tilted for that). `slack` is our own measure of the distance
// to the limit in degrees (negative outside).

constexpr Real kArm = 30;
const Vec3 kAnchor(0, 0, kArm);

struct LimitRun {
    Real swingOvershoot = 0;        // degrees, our measure, worst during the swing
    Real swingOvershootEngine = 0;  // the same by limitViolationDegrees
    Real closestDuringSwing = 1e9;  // smallest slack during the swing: ≤ 0 means it hit the limit
    int stepsAtLimit = 0;           // swing steps within 0.6° of the limit
    Real restOvershoot = 0;         // degrees, our measure, at the end of settling
    Real restOvershootEngine = 0;
    Real restSlack = 0;  // how far inside the limit it rests (≈ 0: pressed against it)
    Real restKineticEnergy = 0;
    Real startKineticEnergy = 0;
    Real disagreement = 0;  // largest |our violation − engine's| over all steps, degrees
    int failures = 0;
};

LimitRun runIntoLimit(World& world, int joint, const std::function<Real(const World&)>& slack, int swingSteps,
                      int settleSteps) {
    LimitRun r;
    r.startKineticEnergy = world.kineticEnergy();
    const Joint& j = world.joints()[static_cast<std::size_t>(joint)];
    auto measure = [&](Real& own, Real& engine) {
        const Real s = slack(world);
        own = std::max(Real(0), -s);
        engine = limitViolationDegrees(j, world.bodies());
        r.disagreement = std::max(r.disagreement, std::fabs(own - engine));
        return s;
    };
    for (int i = 0; i < swingSteps; ++i) {
        world.step();
        Real own = 0, engine = 0;
        const Real s = measure(own, engine);
        r.swingOvershoot = std::max(r.swingOvershoot, own);
        r.swingOvershootEngine = std::max(r.swingOvershootEngine, engine);
        r.closestDuringSwing = std::min(r.closestDuringSwing, s);
        if (s < 0.6) ++r.stepsAtLimit;
    }
    setAirFriction(world, 0.05);
    for (int i = 0; i < settleSteps; ++i) {
        world.step();
        Real own = 0, engine = 0;
        measure(own, engine);
    }
    r.restSlack = measure(r.restOvershoot, r.restOvershootEngine);
    r.restKineticEnergy = world.kineticEnergy();
    r.failures = world.solverFailures();
    return r;
}

void expectStopsAtLimit(const LimitRun& r, const char* what) {
    std::printf(
        "%s: overshoot in the swing %.3g deg (engine %.3g), at rest %.3g deg (engine %.3g), "
        "rests %.3g deg inside, %d swing steps at the limit\n",
        what, r.swingOvershoot, r.swingOvershootEngine, r.restOvershoot, r.restOvershootEngine, r.restSlack,
        r.stepsAtLimit);
    // The swing really reached the limit and spent steps against it.
    EXPECT_LE(r.closestDuringSwing, 0.1) << "the bob never reached its limit";
    EXPECT_GE(r.stepsAtLimit, 5);
    // The tolerances.
    EXPECT_LT(r.swingOvershoot, 3.0);
    EXPECT_LT(r.swingOvershootEngine, 3.0);
    EXPECT_LT(r.restOvershoot, 1.0);
    EXPECT_LT(r.restOvershootEngine, 1.0);
    // At rest, and pressed against the limit (gravity pulls it outside): within the margin where
    // the limit row acts. (Resting *on* the limit is asked by the disabled tests below.)
    EXPECT_LT(r.restKineticEnergy, 1e-6 * r.startKineticEnergy);
    EXPECT_LT(r.restSlack, 0.6);
    // Our measure and the engine's are the same angle.
    EXPECT_LT(r.disagreement, 1e-6);
    EXPECT_EQ(r.failures, 0);
}

std::string cubeBob(const Vec3& centre) { return boxBodyText("bob", "origin", Vec3(2, 2, 2), centre); }

// Hinge about +X through the anchor, the bob hanging below. V limit "limit -35, 50, 0": centre
// a3 − a1 = 35°, half width 25°, so the hinge angle (right-handed about +X, 0 hanging straight
// down) may lie in [10°, 60°]. Hanging straight down is outside: the bob starts at the V's centre
// and comes to rest on the 10° side. Thrown at 8 rad/s (240 units/s at the bob), then 24 rad/s,
// into the 60° side.
TEST(ConstraintPhysicsLimit, HingeVLimitStopsAHardSwingAtBothSidesOfTheV) {
    const Figure figure =
        figureOfBlocks({"origin"}, cubeBob(Vec3::Zero()) + "hinge \"knee\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " axis ( 1, 0, 0 ) friction 0 limit -35, 50, 0 }\n");
    for (const Real speed : {1.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "speed × " << speed);
        World world(figure, test::dynamicsOnly());
        test::swingAbout(world, kAnchor, 35);
        spinAbout(world, 0, kAnchor, speed * Vec3(8, 0, 0));
        const Real lo = 10, hi = 60;
        Real hingeDisagreement = 0;
        const auto slack = [&](const World& w) {
            // The bob's "down" turned about +X by θ is (0, sin θ, −cos θ).
            const Vec3 down = w.bodies()[0].orientation * Vec3(0, 0, -1);
            const Real angle = deg(std::atan2(down.y(), -down.z()));
            hingeDisagreement =
                std::max(hingeDisagreement, std::fabs(angle - deg(hingeAngle(w.joints()[0], w.bodies()))));
            return std::min(angle - lo, hi - angle);
        };
        const LimitRun r = runIntoLimit(world, 0, slack, 120, 300);
        expectStopsAtLimit(r, "hinge V limit");
        EXPECT_LT(hingeDisagreement, 1e-6) << "hingeAngle against the angle from the bob's orientation";
        EXPECT_LT(world.maxJointError(), 1e-6);
    }
}

// A limit the body never reaches must not act. A frictionless hinge pendulum under a symmetric
// V of ±10° ("limit 0, 20, 0") swings with an amplitude of 9.7°, 0.3° short of the limit; it must
// keep that amplitude (the integrator alone keeps it within 0.01°: 9.0° stays 9.01° over 10 s).

TEST(ConstraintPhysicsLimit, ASwingTurningJustShortOfALimitIsNotStoppedByIt) {
    const Figure figure =
        figureOfBlocks({"origin"}, cubeBob(Vec3::Zero()) + "hinge \"knee\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " axis ( 1, 0, 0 ) friction 0 limit 0, 20, 0 }\n");
    World world(figure, test::dynamicsOnly());
    test::swingAbout(world, kAnchor, 9.7);
    Real lastAmplitude = 0;
    for (int i = 0; i < 600; ++i) {
        world.step();
        if (i >= 540)
            lastAmplitude = std::max(lastAmplitude, std::fabs(deg(hingeAngle(world.joints()[0], world.bodies()))));
    }
    std::printf("hinge swinging 0.3 deg short of its limit: amplitude after 10 s %.4f deg (from 9.7)\n", lastAmplitude);
    EXPECT_NEAR(lastAmplitude, 9.7, 0.05);
    EXPECT_EQ(world.maxLimitViolationDegrees(), 0);
}

// Released at rest 2°, 0.8° and 0.3° inside the 10° side of the [10°, 60°] V, with gravity pulling
// it on and air friction: the bob must come to rest on the limit, not in front of it.
//
// DISABLED: engine bug, the same as above. The bob enters the 0.57° margin slowly, the limit row
// (Cdot ≥ 0) stops it there, and it rests 0.38°, 0.48° and 0.29° short of the limit, held by a
// limit force that acts at a distance. With WorldSettings::rows.limitMargin = 0 it rests on the
// limit (0.0000°).
TEST(ConstraintPhysicsLimit, HingeReleasedNearItsLimitComesToRestOnIt) {
    const Figure figure =
        figureOfBlocks({"origin"}, cubeBob(Vec3::Zero()) + "hinge \"knee\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " axis ( 1, 0, 0 ) friction 0 limit -35, 50, 0 }\n");
    for (const Real start : {12.0, 10.8, 10.3}) {
        World world(figure, test::dynamicsOnly());
        test::swingAbout(world, kAnchor, start);
        setAirFriction(world, 0.05);
        for (int i = 0; i < 300; ++i) world.step();
        const Real slack = deg(hingeAngle(world.joints()[0], world.bodies())) - 10;
        std::printf("hinge released %.1f deg from its limit rests %.4f deg from it\n", start - 10, slack);
        EXPECT_LT(std::fabs(slack), 0.05) << "released " << start - 10 << " deg from the limit";
    }
}

// Rows carry CFM, so a solve leaves each yielding by CFM × its impulse, every step again; a
// body held up by its rows keeps that much velocity (the bench ragdoll's ankle limit sank 5.5e-7
// rad per step until the projection put it back, every step). With targets that make up for last
// step's yield, a bob resting on its hinge limit (as in the test above, pressed against the 10°
// side) comes to rest from the velocity solve alone, the position projection off; without them
// it kept 3e-5 of kinetic energy.
TEST(ConstraintPhysicsLimit, ABobRestingOnALimitComesToRestDespiteItsRowsSoftness) {
    const Figure figure =
        figureOfBlocks({"origin"}, cubeBob(Vec3::Zero()) + "hinge \"knee\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " axis ( 1, 0, 0 ) friction 0 limit -35, 50, 0 }\n");
    WorldSettings settings = test::dynamicsOnly();
    settings.positionTolerance = 0;
    settings.solver = SolverKind::Tree;
    World world(figure, settings);
    test::swingAbout(world, kAnchor, 10.2);
    setAirFriction(world, 0.05);
    for (int i = 0; i < 120; ++i) world.step();
    const Real early = deg(hingeAngle(world.joints()[0], world.bodies()));
    for (int i = 0; i < 600; ++i) world.step();
    const Real late = deg(hingeAngle(world.joints()[0], world.bodies()));
    std::printf("bob resting on its hinge limit, projection off: %.6f deg, moved %.3g deg from 2 s to 12 s, kinetic energy %.3g\n",
                early, late - early, world.kineticEnergy());
    EXPECT_LT(std::fabs(early - 10), 0.6) << "pressed against the limit's 10° side, within its margin";
    EXPECT_LT(std::fabs(late - early), 1e-6);
    EXPECT_LT(world.kineticEnergy(), 1e-9);
}

// Ball and socket, cone limit around the axis (3, 0, −4)/5, tilted 36.9° from the vertical, full
// angle 60° (half angle 30°). The bob starts on the cone's axis; straight down is 6.9° outside
// the cone. (.af numbers are 32-bit floats, as in Doom: directions here are written with small
// integers so that the file says exactly what the test measures against.)
TEST(ConstraintPhysicsLimit, BallConeLimitStopsAHardSwingAtItsCone) {
    const Vec3 axis = Vec3(3, 0, -4) / 5;
    const Figure figure =
        figureOfBlocks({"origin"}, cubeBob(kAnchor + kArm * axis) +
                                       "ballAndSocketJoint \"hip\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " friction 0 coneLimit ( 3, 0, -4 ), 60, ( 3, 0, -4 ) }\n");
    for (const Real speed : {1.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "speed × " << speed);
        World world(figure, test::dynamicsOnly());
        spinAbout(world, 0, kAnchor, speed * Vec3(2, 9, -1.5));
        const auto slack = [&](const World& w) {
            const Vec3 shaft = w.bodies()[0].orientation * axis;  // the shaft is along the axis at spawn
            return 30 - deg(angleBetween(shaft, axis));
        };
        expectStopsAtLimit(runIntoLimit(world, 0, slack, 120, 300), "ball cone limit");
        EXPECT_LT(world.maxJointError(), 1e-6);
    }
}

// Ball and socket with our twist limit (not in Doom's decl: set on the figure), ±30° about the
// shaft, the bob hanging straight below the anchor on a wide cone. Spun about the shaft (no
// swing, no gravity torque about it) at 2 and 6 rad/s: the twist stops at 30° within the issue's
// tolerances (3° in a hard swing, 1° at rest) and the point joint holds.
TEST(ConstraintPhysicsLimit, BallTwistLimitStopsASpinAboutTheShaft) {
    Figure figure =
        figureOfBlocks({"origin"}, cubeBob(kAnchor - Vec3(0, 0, kArm)) +
                                       "ballAndSocketJoint \"neck\" { body1 \"bob\" body2 \"world\" anchor " +
                                       afVector(kAnchor) + " friction 0 coneLimit ( 0, 0, -1 ), 170, ( 0, 0, -1 ) }\n");
    figure.constraints.at(0).twistLimit = 30;
    for (const Real spin : {2.0, 6.0}) {
        SCOPED_TRACE(testing::Message() << "spin " << spin << " rad/s");
        World world(figure, test::dynamicsOnly());
        world.setVelocity(0, world.bodies()[0].linearVelocity, Vec3(0, 0, spin));
        const Joint& joint = world.joints().at(0);
        Real largest = 0;
        for (int i = 0; i < 120; ++i) {
            world.step();
            largest = std::max(largest, std::fabs(deg(twistAngle(joint, world.bodies()))));
        }
        const Real final = std::fabs(deg(twistAngle(joint, world.bodies())));
        std::printf("ball twist limit, spin %.0f rad/s: largest twist %.4f deg, final %.4f deg\n", spin, largest, final);
        EXPECT_GT(largest, 29.9) << "the spin never reached the limit";
        EXPECT_LT(largest, 33.0);
        EXPECT_LT(final, 31.0);
        EXPECT_GT(final, 29.0) << "the limit stops the spin; nothing turns it back";
        EXPECT_NEAR(limitViolationDegrees(joint, world.bodies()), std::max(Real(0), final - 30), 1e-9);
        EXPECT_LT(world.maxJointError(), 1e-6);
    }
}

// Ball and socket, pyramid around −Z: "pyramidLimit (0,0,-1), 40, 30, 0": base = +Y (Doom's
// `left` of the axis' angles, roll 0), so the shaft's angle from −Z within the Y–Z plane is at
// most 20°, within the X–Z plane at most 15°. Gravity points 31° (Y–Z) and 27° (X–Z) away from
// −Z: the bob comes to rest in the corner, against both faces.
TEST(ConstraintPhysicsLimit, BallPyramidLimitStopsAHardSwingAtItsFaces) {
    const Figure figure = figureOfBlocks(
        {"origin"}, cubeBob(Vec3::Zero()) + "ballAndSocketJoint \"shoulder\" { body1 \"bob\" body2 \"world\" anchor " +
                        afVector(kAnchor) + " friction 0 pyramidLimit ( 0, 0, -1 ), 40, 30, 0, ( 0, 0, -1 ) }\n");
    WorldSettings settings;
    settings.gravity = 1066 * Vec3(-0.5, 0.6, -1).normalized();
    for (const Real speed : {1.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "speed × " << speed);
        World world(figure, test::dynamicsOnly(settings));
        spinAbout(world, 0, kAnchor, speed * Vec3(7, -6, 3));
        const Vec3 e0(0, 1, 0), e2(0, 0, -1), e1 = e0.cross(e2);
        const auto slack = [&](const World& w) {
            const Vec3 shaft = w.bodies()[0].orientation * e2;
            const Real psi0 = deg(std::atan2(shaft.dot(e0), shaft.dot(e2)));
            const Real psi1 = deg(std::atan2(shaft.dot(e1), shaft.dot(e2)));
            return std::min(20 - std::fabs(psi0), 15 - std::fabs(psi1));
        };
        const LimitRun r = runIntoLimit(world, 0, slack, 120, 300);
        expectStopsAtLimit(r, "ball pyramid limit");
        // In the corner: against both faces at once.
        const Vec3 shaft = world.bodies()[0].orientation * e2;
        EXPECT_NEAR(deg(std::atan2(shaft.dot(e0), shaft.dot(e2))), 20, 0.6);
        EXPECT_NEAR(std::fabs(deg(std::atan2(shaft.dot(e1), shaft.dot(e2)))), 15, 0.6);
        EXPECT_LT(world.maxJointError(), 1e-6);
    }
}

// Universal joint to the world (shaft 1 down into the bob, shaft 2 up), cone limit of full angle
// 60° around −Z on shaft 1. Gravity is tilted 40° from −Z, so the bob rests against the cone.
TEST(ConstraintPhysicsLimit, UniversalConeLimitStopsAHardSwingAtItsCone) {
    const Figure figure = figureOfBlocks(
        {"origin"}, cubeBob(Vec3::Zero()) + "universalJoint \"wrist\" { body1 \"bob\" body2 \"world\" anchor " +
                        afVector(kAnchor) +
                        " shafts ( 0, 0, -1 ), ( 0, 0, 1 ) friction 0 coneLimit ( 0, 0, -1 ), 60 }\n");
    WorldSettings settings;
    settings.gravity = 1066 * (turn(Vec3(1, -2, 0), 40) * Vec3(0, 0, -1));
    for (const Real speed : {1.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "speed × " << speed);
        World world(figure, test::dynamicsOnly(settings));
        spinAbout(world, 0, kAnchor, speed * Vec3(7, -5, 0));
        Real twist = 0;
        const auto slack = [&](const World& w) {
            twist = std::max(twist, jointAngularError(w.joints()[0], w.bodies()));
            const Vec3 shaft = w.bodies()[0].orientation * Vec3(0, 0, -1);
            return 30 - deg(angleBetween(shaft, Vec3(0, 0, -1)));
        };
        expectStopsAtLimit(runIntoLimit(world, 0, slack, 120, 300), "universal cone limit");
        EXPECT_LT(deg(twist), 1e-4) << "twist about the shafts while swinging into the limit";
        EXPECT_LT(world.maxJointError(), 1e-6);
    }
}

// ---------------------------------------------------------------------------------------------
// Universal joint between two moving bodies: an upper link hangs from the world by a ball joint
// and a lower link hangs from it by a universal joint (shafts along the links, cone limit 120°
// to stay clear of the fold-over). The upper link is spun about its own axis at 12 rad/s and both
// are thrown sideways: the universal joint must carry the spin over to the lower link while
// bending, with no twist between the two shafts.
//
// Our twist: D = (qB⁻¹ qA)(qB0⁻¹ qA0)⁻¹ is A's rotation relative to B since spawn, in B's frame;
// s = A's shaft at spawn in B's frame. Split D = S·T with S the shortest rotation taking s to D·s
// (Eigen's FromTwoVectors); the twist is T's angle about s. That is the homokinetic
// (constant-velocity) "no relative twist" of docs/doom-physics.md §4.3, computed without the engine's
// formula.
Real homokineticTwist(const Quat& qA, const Quat& qB, const Quat& qA0, const Quat& qB0, const Vec3& shaftInB) {
    const Quat d = (qB.conjugate() * qA) * (qB0.conjugate() * qA0).conjugate();
    const Quat swing = Quat::FromTwoVectors(shaftInB, d * shaftInB);
    const Quat t = swing.conjugate() * d;
    // T turns about s only; measure its angle on a vector ⟂ s.
    const Vec3 p = shaftInB.unitOrthogonal();
    const Vec3 tp = t * p;
    return std::atan2(p.cross(tp).dot(shaftInB), p.dot(tp));
}

TEST(ConstraintPhysicsUniversal, SwungAroundItCarriesSpinWithoutRelativeTwist) {
    const Figure figure = figureOfBlocks(
        {"origin", "lower"},
        boxBodyText("upper", "origin", Vec3(2, 2, 10), Vec3(0, 0, 50)) +
            boxBodyText("lower", "lower", Vec3(3, 1.5, 8), Vec3(0, 0, 32)) +
            "ballAndSocketJoint \"shoulder\" { body1 \"upper\" body2 \"world\" anchor ( 0, 0, 60 ) friction 0 }\n"
            "universalJoint \"elbow\" { body1 \"lower\" body2 \"upper\" anchor ( 0, 0, 40 ) "
            "shafts ( 0, 0, -1 ), ( 0, 0, 1 ) friction 0 coneLimit ( 0, 0, -1 ), 120 }\n");
    World world(figure, test::dynamicsOnly());
    spinAbout(world, 0, Vec3(0, 0, 60), Vec3(3, -2, 12));
    spinAbout(world, 1, Vec3(0, 0, 60), Vec3(-4, 5, 0));
    const Quat a0 = world.bodies()[1].orientation, b0 = world.bodies()[0].orientation;
    const Vec3 shaftInB = b0.conjugate() * Vec3(0, 0, -1);
    Real worstOwn = 0, worstEngine = 0, worstDisagreement = 0, largestBend = 0, fastestLowerSpin = 0, worstPoint = 0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        const RigidBody& upper = world.bodies()[0];
        const RigidBody& lower = world.bodies()[1];
        const Real own = homokineticTwist(lower.orientation, upper.orientation, a0, b0, shaftInB);
        const Real engine = jointAngularError(world.joints()[1], world.bodies());
        worstOwn = std::max(worstOwn, std::fabs(own));
        worstEngine = std::max(worstEngine, engine);
        worstDisagreement = std::max(worstDisagreement, std::fabs(std::fabs(own) - engine));
        const Vec3 lowerShaft = lower.orientation * Vec3(0, 0, -1), upperShaft = upper.orientation * Vec3(0, 0, -1);
        largestBend = std::max(largestBend, deg(angleBetween(lowerShaft, upperShaft)));
        fastestLowerSpin = std::max(fastestLowerSpin, std::fabs(lower.angularVelocity.dot(lowerShaft)));
        worstPoint = std::max(worstPoint, world.maxJointError());
    }
    std::printf(
        "universal joint swung around 3 s: twist %.3g deg (engine %.3g deg), bend up to %.1f deg, "
        "lower link spin up to %.2f rad/s, joint error %.3g\n",
        deg(worstOwn), deg(worstEngine), largestBend, fastestLowerSpin, worstPoint);
    EXPECT_GT(largestBend, 20.0) << "the joint was not bent: the test would not see a Cardan-type twist";
    EXPECT_GT(fastestLowerSpin, 4.0) << "the upper link's spin did not reach the lower one";
    EXPECT_LT(deg(worstOwn), 1e-4);
    EXPECT_LT(deg(worstEngine), 1e-4);
    EXPECT_LT(deg(worstDisagreement), 1e-6);
    EXPECT_LT(worstPoint, 1e-6);
    EXPECT_EQ(world.solverFailures(), 0);
}

// ---------------------------------------------------------------------------------------------
// Slider to the world along n = (4, 0, −3)/5, 36.9° below the horizontal (sin α = 0.6): an
// unsymmetric block (8 × 4 × 2, density 1) slides down it under gravity.

constexpr Real kSinSlope = 0.6;

Figure blockOnSlider() {
    return figureOfBlocks({"origin"}, boxBodyText("block", "origin", Vec3(4, 2, 1), Vec3(5, -3, 7)) +
                                          "slider \"rail\" { body1 \"block\" body2 \"world\" axis ( 4, 0, -3 ) }\n");
}

Vec3 slopeAxis() { return Vec3(4, 0, -3) / 5; }

// Without friction the block accelerates at g·sin α along the axis: s = ½ g sin α t². The
// integrator (velocity first, then position) lands at a·dt²·n(n+1)/2 after n steps, ahead of
// the continuous curve by 1/n: 1.7 % after 1 s, 0.8 % after 2 s. Checked within 2 %.
TEST(ConstraintPhysicsSlider, SlideDistanceFollowsHalfGSinAlphaTSquared) {
    const Vec3 n = slopeAxis();
    World world(blockOnSlider(), test::dynamicsOnly());
    const Vec3 start = world.bodies()[0].position;
    const Real a = 1066 * kSinSlope;
    for (int second = 1; second <= 2; ++second) {
        for (int i = 0; i < 60; ++i) world.step();
        const Real t = world.time();
        const Real s = (world.bodies()[0].position - start).dot(n);
        const Real expected = 0.5 * a * t * t;
        std::printf("slider at t = %.0f s: slid %.4f units, ½ g sin α t² = %.4f (%+.2f %%)\n", t, s, expected,
                    100 * (s / expected - 1));
        EXPECT_NEAR(s / expected, 1, 0.02) << "t = " << t;
        EXPECT_NEAR(world.bodies()[0].linearVelocity.dot(n) / (a * t), 1, 1e-9) << "speed g sin α t, t = " << t;
    }
    EXPECT_EQ(world.solverFailures(), 0);
}

// The same slide, with an initial spin, and every step a force across the axis (twice the
// block's weight) and a torque: the block must stay on its line and keep its orientation, and the
// cross force must not change its progress along the axis.
TEST(ConstraintPhysicsSlider, PushedAndTwistedItSlidesWithoutOffAxisDriftOrRotation) {
    const Vec3 n = slopeAxis();
    World world(blockOnSlider(), test::dynamicsOnly());
    const RigidBody& block = world.bodies()[0];
    const Vec3 start = block.position;
    const Quat startOrientation = block.orientation;
    const Real m = block.mass();
    world.setVelocity(0, block.linearVelocity, Vec3(3, -2, 5));
    const Vec3 across = n.cross(Vec3(0.3, 1, 0.2)).normalized();
    Real drift = 0, driftEngine = 0, rotation = 0, rotationEngine = 0;
    for (int i = 0; i < 120; ++i) {
        RigidBody& pushed = detail::WorldAccess::bodies(world)[0];  // a pure torque: World has no call for one
        pushed.force = 2 * m * 1066 * across;
        pushed.torque = m * 1000 * Vec3(1, 2, -3);
        world.step();
        const Vec3 d = block.position - start;
        drift = std::max(drift, (d - d.dot(n) * n).norm());
        driftEngine = std::max(driftEngine, world.maxJointError());
        rotation = std::max(rotation, rotationAngle(block.orientation * startOrientation.conjugate()));
        rotationEngine = std::max(rotationEngine, jointAngularError(world.joints()[0], world.bodies()));
    }
    const Real s = (block.position - start).dot(n), t = world.time();
    std::printf(
        "slider pushed across and twisted, 2 s: off-axis drift %.3g units (engine %.3g), rotation %.3g deg "
        "(engine %.3g), slid %.2f units\n",
        drift, driftEngine, deg(rotation), deg(rotationEngine), s);
    EXPECT_LT(drift, 1e-6);
    EXPECT_LT(driftEngine, 1e-6);
    EXPECT_LT(deg(rotation), 1e-6);
    EXPECT_LT(deg(rotationEngine), 1e-6);
    EXPECT_NEAR(s / (0.5 * 1066 * kSinSlope * t * t), 1, 0.02);
    EXPECT_EQ(world.solverFailures(), 0);
}

// A slider between two moving bodies: a block slides along a rail that spins about its own axis
// (6 rad/s) and tumbles slowly, in zero gravity. Centrifugal force drives the block along the
// rail; relative to the rail it must move only along the axis and not turn. (Doom's slider rows
// lack the rail's lever arm and hold only while the rail does not rotate, docs/doom-quirks.md item 7; ours
// must hold here too.)
TEST(ConstraintPhysicsSlider, OnASpinningRailItSlidesWithoutOffAxisDriftOrRotation) {
    const Figure figure = figureOfBlocks({"origin", "block"},
                                         boxBodyText("rail", "origin", Vec3(20, 1, 1), Vec3::Zero()) +
                                             boxBodyText("block", "block", Vec3(2, 2, 2), Vec3(5, 0, 0), 0.5) +
                                             "slider \"rail\" { body1 \"block\" body2 \"rail\" axis ( 1, 0, 0 ) }\n");
    WorldSettings settings;
    settings.gravity.setZero();
    World world(figure, test::dynamicsOnly(settings));
    spinAbout(world, 0, Vec3::Zero(), Vec3(6, 0.3, 0.5));
    spinAbout(world, 1, Vec3::Zero(), Vec3(6, 0.3, 0.5));
    world.setVelocity(1, world.bodies()[1].linearVelocity + Vec3(10, 0, 0), world.bodies()[1].angularVelocity);
    const RigidBody& rail = world.bodies()[0];
    const RigidBody& block = world.bodies()[1];
    const Vec3 offset0 = rail.orientation.conjugate() * (block.position - rail.position);
    const Quat relative0 = rail.orientation.conjugate() * block.orientation;
    const Vec3 axis = Vec3::UnitX();  // in the rail's frame
    Real drift = 0, driftEngine = 0, rotation = 0, rotationEngine = 0, railTurn = 0, slid = 0;
    const Quat rail0 = rail.orientation;
    for (int i = 0; i < 180; ++i) {
        world.step();
        const Vec3 d = rail.orientation.conjugate() * (block.position - rail.position) - offset0;
        drift = std::max(drift, (d - d.dot(axis) * axis).norm());
        slid = std::max(slid, std::fabs(d.dot(axis)));
        driftEngine = std::max(driftEngine, world.maxJointError());
        const Quat relative = rail.orientation.conjugate() * block.orientation;
        rotation = std::max(rotation, rotationAngle(relative * relative0.conjugate()));
        rotationEngine = std::max(rotationEngine, jointAngularError(world.joints()[0], world.bodies()));
        railTurn = std::max(railTurn, deg(rotationAngle(rail.orientation * rail0.conjugate())));
    }
    std::printf(
        "slider on a spinning rail, 3 s: off-axis drift %.3g units (engine %.3g), relative rotation %.3g deg "
        "(engine %.3g), slid up to %.1f units, rail turned up to %.0f deg\n",
        drift, driftEngine, deg(rotation), deg(rotationEngine), slid, railTurn);
    EXPECT_GT(railTurn, 90.0);
    EXPECT_GT(slid, 20.0);
    EXPECT_LT(drift, 1e-6);
    EXPECT_LT(driftEngine, 1e-6);
    EXPECT_LT(deg(rotation), 1e-6);
    EXPECT_LT(deg(rotationEngine), 1e-6);
    EXPECT_EQ(world.solverFailures(), 0);
}

// ---------------------------------------------------------------------------------------------
// Fixed joint: two unequal boxes welded together, thrown with unrelated random velocities in zero
// gravity. From the first step on they must move as one rigid body: B's position and orientation
// in A's frame stay at their spawn values.
TEST(ConstraintPhysicsFixed, TumblingPairKeepsItsRelativePose) {
    const Figure figure =
        figureOfBlocks({"origin", "tip"}, boxBodyText("a", "origin", Vec3(6, 2, 1), Vec3(0, 0, 0)) +
                                              boxBodyText("b", "tip", Vec3(1, 3, 2), Vec3(8, 1, -2), 0.5) +
                                              "fixed \"weld\" { body1 \"b\" body2 \"a\" }\n");
    WorldSettings settings;
    settings.gravity.setZero();
    World world(figure, test::dynamicsOnly(settings));
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> speed(-50, 50), spin(-5, 5);
    for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b) {
        const Vec3 linear = Vec3(speed(rng), speed(rng), speed(rng));
        const Vec3 angular = Vec3(spin(rng), spin(rng), spin(rng));
        world.setVelocity(b, linear, angular);
    }
    const RigidBody& a = world.bodies()[0];
    const RigidBody& b = world.bodies()[1];
    const Vec3 offset0 = a.orientation.conjugate() * (b.position - a.position);
    const Quat relative0 = a.orientation.conjugate() * b.orientation;
    const Quat a0 = a.orientation;
    Real offsetError = 0, rotationError = 0, engineError = 0, engineRotation = 0, tumbled = 0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        const Vec3 offset = a.orientation.conjugate() * (b.position - a.position);
        const Quat relative = a.orientation.conjugate() * b.orientation;
        offsetError = std::max(offsetError, (offset - offset0).norm());
        rotationError = std::max(rotationError, rotationAngle(relative * relative0.conjugate()));
        engineError = std::max(engineError, world.maxJointError());
        engineRotation = std::max(engineRotation, jointAngularError(world.joints()[0], world.bodies()));
        tumbled = std::max(tumbled, deg(rotationAngle(a.orientation * a0.conjugate())));
    }
    std::printf(
        "fixed pair tumbling 3 s: relative offset error %.3g units (engine %.3g), relative rotation %.3g deg "
        "(engine %.3g), turned up to %.0f deg\n",
        offsetError, engineError, deg(rotationError), deg(engineRotation), tumbled);
    EXPECT_GT(tumbled, 90.0) << "the pair did not tumble";
    EXPECT_LT(offsetError, 1e-6);
    EXPECT_LT(engineError, 1e-6);
    EXPECT_LT(deg(rotationError), 1e-6);
    EXPECT_LT(deg(engineRotation), 1e-6);
    EXPECT_EQ(world.solverFailures(), 0);
}

// ---------------------------------------------------------------------------------------------
// Spring (Doom's law, docs/doom-physics.md §4.3): force = stretch·(L − restLength)², quadratic, along the spring. A
// cube bob hangs from a world anchor by a spring attached at its centre of mass, and air friction
// lets it settle. Doom's damping term only shrinks the force's magnitude, so damping is 0 here.

Figure bobOnSpring(Real startLength, Real stretch, Real restLength, Real minLength, Real maxLength, Real airFriction,
                   Real compress = 0) {
    return figureOfBlocks({"origin"},
                          boxBodyText("bob", "origin", Vec3(2, 2, 2), Vec3::Zero(), 1, airFriction, airFriction) +
                              "spring \"bungee\" { body1 \"bob\" body2 \"world\" anchor1 ( 0, 0, 0 ) anchor2 ( 0, 0, " +
                              test::afNumber(startLength) + " ) friction 0 stretch " + test::afNumber(stretch) +
                              " compress " + test::afNumber(compress) + " damping 0 restLength " +
                              test::afNumber(restLength) + " minLength " + test::afNumber(minLength) + " maxLength " +
                              test::afNumber(maxLength) + " }\n");
}

// Our length: the distance from the world anchor to the bob's centre (anchor1 is at its centre).
Real ownSpringLength(const World& world, Real anchorHeight) {
    return (Vec3(0, 0, anchorHeight) - world.bodies()[0].position).norm();
}

TEST(ConstraintPhysicsSpring, HangingBodyRestsWhereWeightEqualsStretchTimesExtensionSquared) {
    const Real rest = 20, start = 30;
    std::vector<Real> extensions;
    for (const Real stretch : {100.0, 400.0}) {
        World world(bobOnSpring(start, stretch, rest, 0, 0, 0.05), test::dynamicsOnly());
        for (int i = 0; i < 480; ++i) world.step();
        const Real weight = world.bodies()[0].mass() * 1066;
        const Real length = springLength(world.joints()[0], world.bodies());
        EXPECT_NEAR(ownSpringLength(world, start), length, 1e-9);
        const Real x = length - rest;
        const Real expected = std::sqrt(weight / stretch);
        std::printf("spring stretch %.0f: rests at extension %.4f, sqrt(m g / stretch) = %.4f (%+.3f %%)\n", stretch, x,
                    expected, 100 * (x / expected - 1));
        EXPECT_LT(world.kineticEnergy(), 1e-6 * weight * expected) << "not at rest";
        EXPECT_NEAR(stretch * x * x / weight, 1, 0.01) << "m g = stretch x², stretch " << stretch;
        EXPECT_NEAR(world.bodies()[0].position.x(), 0, 1e-9);
        EXPECT_NEAR(world.bodies()[0].position.y(), 0, 1e-9);
        extensions.push_back(x);
    }
    // Quadratic, not Hooke: four times the stiffness halves the extension (a linear spring would
    // quarter it).
    EXPECT_NEAR(extensions[0] / extensions[1], 2, 0.02);
}

// The compression side of the law: gravity turned upwards pushes the bob (hanging below the
// anchor) towards it, and it rests where m g = compress·(restLength − L)². (Upside down this is
// an inverted pendulum on the spring; it stays balanced because everything is exactly on the axis.)
TEST(ConstraintPhysicsSpring, PushedInBodyRestsWhereWeightEqualsCompressTimesCompressionSquared) {
    const Real rest = 40, start = 40, compress = 100;
    WorldSettings settings;
    settings.gravity = Vec3(0, 0, 1066);
    World world(bobOnSpring(start, 0, rest, 0, 0, 0.05, compress), test::dynamicsOnly(settings));
    for (int i = 0; i < 480; ++i) world.step();
    const Real weight = world.bodies()[0].mass() * 1066;
    const Real x = rest - springLength(world.joints()[0], world.bodies());
    const Real expected = std::sqrt(weight / compress);
    std::printf("spring compress %.0f: rests at compression %.4f, sqrt(m g / compress) = %.4f (%+.3f %%)\n", compress,
                x, expected, 100 * (x / expected - 1));
    EXPECT_NEAR(rest - ownSpringLength(world, start), x, 1e-9);
    EXPECT_LT(world.kineticEnergy(), 1e-6 * weight * expected) << "not at rest";
    EXPECT_NEAR(compress * x * x / weight, 1, 0.01);
}

// Length limits [30, 50] around the free equilibrium (46.1): a hard kick down (600 units/s) must
// stop at 50, a hard kick up (800 units/s) at 30. Violations in length units (engine: jointError).
TEST(ConstraintPhysicsSpring, MinAndMaxLengthLimitsStopHardKicks) {
    const Real top = 40, minLength = 30, maxLength = 50;
    World world(bobOnSpring(top, 100, 20, minLength, maxLength, 0), test::dynamicsOnly());
    Real longest = 0, shortest = 1e9, worstEngine = 0;
    auto run = [&](int steps) {
        for (int i = 0; i < steps; ++i) {
            world.step();
            const Real length = ownSpringLength(world, top);
            EXPECT_NEAR(springLength(world.joints()[0], world.bodies()), length, 1e-9);
            longest = std::max(longest, length);
            shortest = std::min(shortest, length);
            worstEngine = std::max(worstEngine, world.maxJointError());
        }
    };
    world.setVelocity(0, Vec3(0, 0, -600), world.bodies()[0].angularVelocity);
    run(60);
    world.setVelocity(0, Vec3(0, 0, 800), world.bodies()[0].angularVelocity);
    run(60);
    std::printf("spring limits [%.0f, %.0f] under kicks: length from %.6f to %.6f, engine violation %.3g\n", minLength,
                maxLength, shortest, longest, worstEngine);
    // Both limits were reached (a free kick would go far past them) and held.
    EXPECT_GT(longest, maxLength - 0.05);
    EXPECT_LT(shortest, minLength + 0.05);
    EXPECT_LT(longest, maxLength + 1e-3);
    EXPECT_GT(shortest, minLength - 1e-3);
    EXPECT_LT(worstEngine, 1e-3);
    EXPECT_EQ(world.solverFailures(), 0);
}

// A max length below the free equilibrium (46.1): the limit carries part of the weight and the bob
// rests at exactly maxLength.
TEST(ConstraintPhysicsSpring, MaxLengthLimitHoldsTheBobBelowItsFreeEquilibrium) {
    const Real top = 30, maxLength = 40;
    World world(bobOnSpring(top, 100, 20, 0, maxLength, 0.05), test::dynamicsOnly());
    Real longest = 0;
    for (int i = 0; i < 300; ++i) {
        world.step();
        longest = std::max(longest, ownSpringLength(world, top));
    }
    std::printf("spring max length %.0f below equilibrium: longest %.6f, rests at %.6f\n", maxLength, longest,
                ownSpringLength(world, top));
    EXPECT_LT(longest, maxLength + 1e-3);
    EXPECT_NEAR(ownSpringLength(world, top), maxLength, 1e-3);
    EXPECT_LT(world.kineticEnergy(), 1e-3);
}

// ---------------------------------------------------------------------------------------------
// Joint friction (docs/doom-physics.md §4.7) on a hinge pendulum: a cube bob (mass 64) 30 units below a world hinge
// about +X. The friction row is an angular impulse bounded by f·|λ|, λ the hinge's impulse of the
// previous step (about the weight times dt), so it acts as Coulomb friction with a torque of
// about f·m·g: each half swing loses 2f/l radians of amplitude, and the bob sticks once
// m·g·l·sin θ < f·m·g at a turning point.

constexpr Real kHingeArm = 30;
const Vec3 kHingeAnchor(0, 0, kHingeArm);

Figure hingePendulum(Real friction) {
    return figureOfBlocks(
        {"origin"}, cubeBob(Vec3::Zero()) + "hinge \"pivot\" { body1 \"bob\" body2 \"world\" anchor " +
                        afVector(kHingeAnchor) + " axis ( 1, 0, 0 ) friction " + test::afNumber(friction) + " }\n");
}

Real hingeRate(const World& world) { return world.bodies()[0].angularVelocity.x(); }
Real swingEnergy(const World& world, Real bottom) {
    return world.kineticEnergy() + test::potentialEnergy(world) - bottom;
}

// Mean energy over each half swing (between zero crossings of the hinge angle; the integrator's
// energy wobble repeats every half swing, so the means are free of it).
struct SwingHistory {
    std::vector<Real> meanEnergy;  // per completed half swing
    Real finalEnergy = 0;
    Real finalAngle = 0;
    Real finalKinetic = 0;
};

SwingHistory swingHistory(Real friction, Real startDegrees, int steps) {
    World bottomWorld(hingePendulum(friction), test::dynamicsOnly());
    const Real bottom = test::potentialEnergy(bottomWorld);
    World world(hingePendulum(friction), test::dynamicsOnly());
    test::swingAbout(world, kHingeAnchor, startDegrees);
    SwingHistory h;
    Real previousAngle = hingeAngle(world.joints()[0], world.bodies());
    Real sum = 0;
    int count = 0;
    bool started = false;
    for (int i = 0; i < steps; ++i) {
        world.step();
        const Real angle = hingeAngle(world.joints()[0], world.bodies());
        if ((previousAngle < 0) != (angle < 0)) {
            if (started) h.meanEnergy.push_back(sum / count);
            started = true;
            sum = 0;
            count = 0;
        }
        sum += swingEnergy(world, bottom);
        ++count;
        previousAngle = angle;
    }
    h.finalEnergy = swingEnergy(world, bottom);
    h.finalAngle = hingeAngle(world.joints()[0], world.bodies());
    h.finalKinetic = world.kineticEnergy();
    EXPECT_EQ(world.solverFailures(), 0);
    return h;
}

TEST(ConstraintPhysicsJointFriction, FrictionlessHingeKeepsItsEnergySwingAfterSwing) {
    const SwingHistory h = swingHistory(0, 30, 20 * 66);
    ASSERT_GE(h.meanEnergy.size(), 30u);
    const Real first = h.meanEnergy.front();
    Real worst = 0;
    for (const Real e : h.meanEnergy) worst = std::max(worst, std::fabs(e / first - 1));
    std::printf("frictionless hinge, %zu half swings: mean energy per half swing varies by %.3g %%\n",
                h.meanEnergy.size(), 100 * worst);
    EXPECT_LT(worst, 0.005);
}

TEST(ConstraintPhysicsJointFriction, FrictionDrainsEnergySwingAfterSwingAndMoreFrictionDrainsFaster) {
    const int steps = 10 * 60;
    const SwingHistory none = swingHistory(0, 30, steps);
    std::vector<SwingHistory> runs;
    const std::vector<Real> frictions = {0.25, 0.5, 1.0};
    for (const Real f : frictions) {
        SCOPED_TRACE(testing::Message() << "friction " << f);
        runs.push_back(swingHistory(f, 30, steps));
        const SwingHistory& h = runs.back();
        ASSERT_GE(h.meanEnergy.size(), 4u);
        for (std::size_t k = 1; k < h.meanEnergy.size(); ++k)
            EXPECT_LT(h.meanEnergy[k], h.meanEnergy[k - 1]) << "half swing " << k << " did not lose energy";
        std::printf(
            "hinge friction %.2f: %zu half swings, mean energy of the first %.4g, last %.4g; after 10 s %.4g "
            "(frictionless %.4g)\n",
            f, h.meanEnergy.size(), h.meanEnergy.front(), h.meanEnergy.back(), h.finalEnergy, none.finalEnergy);
        EXPECT_LT(h.finalEnergy, 0.9 * none.finalEnergy);
    }
    // More friction: less energy in every half swing, and fewer half swings before it sticks. (Not
    // less energy at the end: where each one sticks, within ±asin(f/l), is a matter of phase.)
    for (std::size_t r = 1; r < runs.size(); ++r) {
        SCOPED_TRACE(testing::Message() << "friction " << frictions[r] << " against " << frictions[r - 1]);
        EXPECT_LT(runs[r].meanEnergy.size(), runs[r - 1].meanEnergy.size());
        for (std::size_t k = 0; k < runs[r].meanEnergy.size(); ++k)
            EXPECT_LT(runs[r].meanEnergy[k], runs[r - 1].meanEnergy[k]) << "half swing " << k;
    }
    // The strongest has stopped, stuck where gravity's torque m g l sin θ no longer beats the
    // friction torque f·m·g: |θ| ≤ asin(f / l), within 5 % for the joint force's swing.
    const SwingHistory& strongest = runs.back();
    EXPECT_LT(strongest.finalKinetic, 1e-9 * none.finalEnergy) << "friction 1 should have stopped the bob";
    EXPECT_LE(std::fabs(strongest.finalAngle), 1.05 * std::asin(frictions.back() / kHingeArm));
}

// Coulomb friction takes a fixed amount of amplitude per half swing, 2 f / l radians (for small
// swings, where the joint force is about the weight), instead of a fixed fraction as viscous
// damping would: the turning points fall on a straight line. Peaks are refined by a parabola
// through the three samples around each turning point.
TEST(ConstraintPhysicsJointFriction, EachHalfSwingLosesTwoFOverLOfAmplitude) {
    const Real f = 0.2;
    World world(hingePendulum(f), test::dynamicsOnly());
    test::swingAbout(world, kHingeAnchor, 10);
    std::vector<Real> angles = {hingeAngle(world.joints()[0], world.bodies())};
    for (int i = 0; i < 600; ++i) {
        world.step();
        angles.push_back(hingeAngle(world.joints()[0], world.bodies()));
    }
    std::vector<Real> peaks;
    for (std::size_t i = 1; i + 1 < angles.size(); ++i) {
        const Real a = std::fabs(angles[i - 1]), b = std::fabs(angles[i]), c = std::fabs(angles[i + 1]);
        if (!(b > a && b >= c) || b < rad(3)) continue;  // turning points while clearly swinging
        const Real curvature = a - 2 * b + c;
        peaks.push_back(b - (a - c) * (a - c) / (8 * curvature));
    }
    ASSERT_GE(peaks.size(), 5u);
    const Real expected = 2 * f / kHingeArm;
    Real sum = 0;
    for (std::size_t k = 1; k < peaks.size(); ++k) {
        const Real drop = peaks[k - 1] - peaks[k];
        sum += drop;
        EXPECT_NEAR(drop / expected, 1, 0.1) << "half swing " << k;
    }
    const Real mean = sum / Real(peaks.size() - 1);
    std::printf(
        "hinge friction %.1f from 10 deg: %zu turning points, amplitude drops %.4f deg per half swing, "
        "2f/l = %.4f deg\n",
        f, peaks.size(), deg(mean), deg(expected));
    EXPECT_NEAR(mean / expected, 1, 0.03);
}

// The friction impulse itself, measured from outside: from the same state, one step with the
// friction row (the world) and one without (a fresh world, whose joint has no previous impulse,
// so no friction row on its first step). Only the friction row has a moment about the hinge axis
// through the pivot (the point rows act at the pivot, the axis rows ⟂ the axis), so the difference
// of the angular momenta about that axis is the friction impulse. It must stay within ±f·λ_prev,
// oppose the motion, and reach the bound while the bob slides (Coulomb).
//
// The energy it removes in the step: with p the friction impulse, I the moment of inertia about
// the axis and τ(θ) gravity's torque, the two runs end with ω differing by p/I and θ by dt·p/I,
// so their energies differ by p·(ω_free + ω)/2 − τ(θ_end)·dt·p/I to first order. With |p| at
// most the bound: |ΔE| ≤ f·λ_prev·(max(|ω_free|, |ω|) + dt·|τ|/I), τ taken at the larger of the
// start and end poses.
TEST(ConstraintPhysicsJointFriction, FrictionImpulseAndEnergyRemovedPerStepStayWithinFTimesTheJointImpulse) {
    const Real f = 0.5;
    const Figure frictional = hingePendulum(f), frictionless = hingePendulum(0);
    World world(frictional, test::dynamicsOnly());
    const Real bottom = test::potentialEnergy(world);
    test::swingAbout(world, kHingeAnchor, 30);
    const Real startEnergy = swingEnergy(world, bottom);
    const Vec3 h = Vec3::UnitX();
    const auto momentAboutAxis = [&](const World& w) {
        const RigidBody& b = w.bodies()[0];
        return h.dot(b.angularMomentum() - kHingeAnchor.cross(b.linearMomentum()));
    };
    // Gravity's angular acceleration about the axis, |τ| / I, at the current pose.
    const auto gravityAcceleration = [&](const World& w) {
        const RigidBody& b = w.bodies()[0];
        const Vec3 arm = b.position - kHingeAnchor;
        const Real inertia = h.dot(b.inertiaWorld() * h) + b.mass() * h.cross(arm).squaredNorm();
        return std::fabs(h.dot(arm.cross(b.mass() * w.settings().gravity))) / inertia;
    };
    const Real dt = world.settings().timeStep;
    int active = 0, sliding = 0;
    Real worstRatio = 0, worstOpposition = 0, slidingLowest = 1e9, worstEnergyRatio = 0, removed = 0;
    for (int i = 0; i < 240; ++i) {
        const Real bound = f * world.joints()[0].lastImpulse;
        const Real accelerationBefore = gravityAcceleration(world);
        World free(frictionless, test::dynamicsOnly());
        detail::WorldAccess::bodies(free) = world.bodies();
        world.step();
        free.step();
        if (bound <= 0) continue;
        ++active;
        const Real impulse = momentAboutAxis(world) - momentAboutAxis(free);
        const Real rateFree = hingeRate(free), rate = hingeRate(world);
        worstRatio = std::max(worstRatio, std::fabs(impulse) / bound);
        worstOpposition =
            std::max(worstOpposition, impulse * rateFree / (bound * std::max(std::fabs(rateFree), Real(1e-9))));
        if (std::fabs(rate) > 0.05) {
            ++sliding;
            slidingLowest = std::min(slidingLowest, std::fabs(impulse) / bound);
        }
        const Real energyRemoved = swingEnergy(free, bottom) - swingEnergy(world, bottom);
        removed += energyRemoved;
        const Real allowed = bound * (std::max(std::fabs(rateFree), std::fabs(rate)) +
                                      dt * std::max(accelerationBefore, gravityAcceleration(world)));
        worstEnergyRatio = std::max(worstEnergyRatio, std::fabs(energyRemoved) / (allowed + 1e-9 * startEnergy));
    }
    std::printf(
        "hinge friction %.1f, 4 s: |friction impulse| / (f·λ_prev) at most %.9f, at least %.9f while sliding "
        "(%d of %d steps); energy removed per step at most %.4f of its bound; %.1f %% of the swing energy "
        "removed\n",
        f, worstRatio, slidingLowest, sliding, active, worstEnergyRatio, 100 * removed / startEnergy);
    EXPECT_GE(active, 200);
    EXPECT_GE(sliding, 100);
    EXPECT_LE(worstRatio, 1 + 1e-6) << "friction impulse above f times the joint's last impulse";
    EXPECT_LE(worstOpposition, 1e-6) << "friction pushed along the motion";
    EXPECT_GE(slidingLowest, 1 - 1e-3) << "sliding friction below its bound: not Coulomb";
    EXPECT_LE(worstEnergyRatio, 1.01) << "a step removed more energy than the friction bound allows";
    EXPECT_GT(removed, 0.5 * startEnergy);
}

}  // namespace
}  // namespace af
