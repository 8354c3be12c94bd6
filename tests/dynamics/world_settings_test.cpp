// World::setSettings: the rules a console changes between steps (Doom's af_skipLimits,
// af_skipFriction, af_forceFriction, g_gravity, the time step), each checked on a figure whose
// motion under the rule is known, and settings that a world refuses.

#include "world_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace af {
namespace {

using test::figureFromText;
using test::namesOnlySkeleton;

constexpr Real kG = 1066;

// A 10-unit link hinged to the world at (0, 0, 100) about +Y, held out horizontally along +X, its
// hinge allowing 20° either way of where it starts, with joint friction `friction`.
std::shared_ptr<const Figure> hingedLink(Real friction) {
    return std::make_shared<const Figure>(figureFromText(
        "articulatedFigure link {\nsettings { friction 0, 0, 0 }\n"
        "body \"b0\" { joint \"origin\" model box( ( -5, -1, -1 ), ( 5, 1, 1 ) ) origin ( 5, 0, 100 ) density 0.2 }\n"
        "hinge \"h\" { body1 \"b0\" body2 \"world\" anchor ( 0, 0, 100 ) axis ( 0, 1, 0 ) friction " +
            std::to_string(friction) + " limit 0, 40, 0 }\n}\n",
        namesOnlySkeleton({"origin"})));
}

// How far below the horizontal the link hangs, degrees.
Real droop(const World& world, FigureId id) {
    const Vec3 c = world.body({id, 0}).position;
    return std::atan2(100 - c.z(), c.x()) * 180 / std::numbers::pi;
}

Real mechanicalEnergy(const World& world, FigureId id) {
    const RigidBody& b = world.body({id, 0});
    return world.kineticEnergy() + world.definition(id).bodies[0].mass * kG * b.position.z();
}

WorldSettings noRest() {
    WorldSettings s;
    s.comeToRest = false;
    return s;
}

TEST(WorldSettings, HingeLimitHoldsTheLinkUnlessLimitsAreSkipped) {
    for (const bool limits : {true, false}) {
        SCOPED_TRACE(limits ? "limits" : "no limits");
        World world(noRest());
        const FigureId id = world.spawn(hingedLink(0));
        WorldSettings s = world.settings();
        s.rows.limits = limits;
        world.setSettings(s);
        Real lowest = 0;
        for (int i = 0; i < 60; ++i) {
            world.step();
            lowest = std::max(lowest, droop(world, id));
        }
        if (limits) {
            EXPECT_LT(lowest, 20 + 1e-6) << "the link passed its 20° limit";
            EXPECT_GT(lowest, 19.9);
            EXPECT_LT(world.maxJointError(), 1e-9);
        } else {
            EXPECT_GT(lowest, 85) << "without limits the link swings down to hang";
        }
    }
}

// With limits skipped, the link released horizontally swings down through the bottom and up the
// other side; joint friction takes energy from the swing, so it reaches less far.
struct Swing {
    Real farthest = 0;    // degrees below the start, the largest reached within a second
    Real energyLost = 0;  // fraction of the mechanical energy
};

Swing swingForASecond(Real friction, bool frictionOn, Real forcedFriction) {
    World world(noRest());
    const FigureId id = world.spawn(hingedLink(friction));
    WorldSettings s = world.settings();
    s.rows.limits = false;
    s.rows.friction = frictionOn;
    s.rows.forcedFriction = forcedFriction;
    world.setSettings(s);
    const Real start = mechanicalEnergy(world, id);
    Swing swing;
    for (int i = 0; i < 60; ++i) {
        world.step();
        const Vec3 c = world.body({id, 0}).position;
        swing.farthest = std::max(swing.farthest, std::atan2(100 - c.z(), c.x()) * 180 / std::numbers::pi);
    }
    swing.energyLost = (start - mechanicalEnergy(world, id)) / start;
    return swing;
}

TEST(WorldSettings, JointFrictionBrakesTheSwingUnlessSkippedAndAForcedCoefficientReplacesTheJoints) {
    const Swing own = swingForASecond(0.5, true, 0);
    const Swing skipped = swingForASecond(0.5, false, 0);
    const Swing frictionless = swingForASecond(0, true, 0);
    const Swing forced = swingForASecond(0.5, true, 2);
    EXPECT_GT(own.energyLost, 0.01) << "a joint with friction 0.5 loses energy";
    EXPECT_LT(skipped.energyLost, own.energyLost / 10);
    EXPECT_EQ(skipped.farthest, frictionless.farthest) << "skipping friction is a joint without friction, to the bit";
    EXPECT_LT(own.farthest, skipped.farthest - 10) << "measured: 162° against 180°";
    EXPECT_LT(forced.farthest, own.farthest - 20) << "a forced coefficient of 2 brakes harder (121°) than the joint's own 0.5";
    EXPECT_EQ(swingForASecond(0, true, 0.5).farthest, own.farthest) << "a forced 0.5 on a frictionless joint is the joint's 0.5";
}

// An 8-unit box with contact friction 0.8, sliding along +X at 100 units/s on the floor.
Real speedAfterHalfASecond(bool friction) {
    WorldSettings s = noRest();
    s.contact.friction = friction;
    World world(s);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const FigureId id = world.spawn(std::make_shared<const Figure>(figureFromText(
        "articulatedFigure box {\nsettings { friction 0, 0, 0 }\n"
        "body \"box\" { joint \"origin\" model box( ( -4, -4, -4 ), ( 4, 4, 4 ) ) origin ( 0, 0, 4 ) density 0.01 "
        "friction 0, 0, 0.8 }\n}\n",
        namesOnlySkeleton({"origin"}))));
    world.setVelocity({id, 0}, Vec3(100, 0, 0), Vec3::Zero());
    for (int i = 0; i < 30; ++i) world.step();
    return world.body({id, 0}).linearVelocity.x();
}

TEST(WorldSettings, ContactFrictionStopsASlidingBoxUnlessSkipped) {
    // μ g = 853 units/s²: the box stops within 0.12 s; without friction nothing slows it.
    EXPECT_LT(std::fabs(speedAfterHalfASecond(true)), 1e-6);
    EXPECT_NEAR(speedAfterHalfASecond(false), 100, 1e-9);
}

TEST(WorldSettings, NewGravityAndTimeStepTakeEffectAtTheNextStepAndWakeARestingFigure) {
    World world;
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const FigureId id = world.spawn(hingedLink(0));
    for (int i = 0; i < 600 && !world.figureAtRest(id); ++i) world.step();
    ASSERT_TRUE(world.figureAtRest(id));
    const Vec3 before = world.body({id, 0}).position;

    WorldSettings s = world.settings();
    s.gravity = Vec3(0, 0, 0);
    s.timeStep = Real(1) / 120;
    world.setSettings(s);
    EXPECT_FALSE(world.figureAtRest(id)) << "new rules wake every figure";
    const Real t = world.time();
    world.step();
    EXPECT_DOUBLE_EQ(world.time() - t, Real(1) / 120);
    EXPECT_LT((world.body({id, 0}).position - before).norm(), 1e-9) << "a link at rest under no gravity stays";
}

TEST(WorldSettings, RefusedSettingsLeaveTheWorldAsItWas) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN(), inf = std::numeric_limits<Real>::infinity();
    World refused(noRest()), untouched(noRest());
    const FigureId id = refused.spawn(hingedLink(0.5));
    untouched.spawn(hingedLink(0.5));
    const auto bad = [&](auto change) {
        WorldSettings s = refused.settings();
        change(s);
        return s;
    };
    for (const WorldSettings& s :
         {bad([&](WorldSettings& s) { s.gravity.z() = nan; }), bad([](WorldSettings& s) { s.timeStep = 0; }),
          bad([&](WorldSettings& s) { s.timeStep = inf; }), bad([](WorldSettings& s) { s.substeps = 0; }),
          bad([&](WorldSettings& s) { s.integration.maxLinearSpeed = nan; }),
          bad([](WorldSettings& s) { s.integration.maxAngularSpeed = -1; }),
          bad([](WorldSettings& s) { s.contact.slop = -0.1; }), bad([&](WorldSettings& s) { s.rows.forcedFriction = inf; }),
          bad([&](WorldSettings& s) { s.positionTolerance = nan; })}) {
        EXPECT_THROW(refused.setSettings(s), std::invalid_argument);
        EXPECT_THROW(World{s}, std::invalid_argument);
    }
    WorldSettings uncapped = noRest();
    uncapped.integration.maxLinearSpeed = inf;  // +∞ is no cap, not an error
    EXPECT_NO_THROW(World{uncapped});
    for (int i = 0; i < 30; ++i) {
        refused.step();
        untouched.step();
    }
    EXPECT_EQ(refused.body({id, 0}).position, untouched.body({id, 0}).position) << "the refusals changed nothing";
}

}  // namespace
}  // namespace af
