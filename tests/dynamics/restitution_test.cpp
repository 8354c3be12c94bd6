// Restitution: a body alone bounces at the restitution times its impact speed, and a bounce
// never makes the motion of what it hits livelier than the impact was.

#include "scene_test_util.h"

namespace af {
namespace {

using test::boxBodyText;
using test::figureOfBlocks;

// Doom's bounciness 0.4 (figure.h), of the approach the contact was found with: the velocity at
// the step's start, before gravity's part of the step.
TEST(Restitution, ABoxDroppedOnTheFloorLeavesItAtTheRestitutionTimesItsImpactSpeed) {
    WorldSettings settings;
    settings.comeToRest = false;
    World world(test::freeBox(Vec3(8, 8, 8), Vec3(0, 0, 40)), settings);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    Real impact = 0, leaving = 0;
    for (int i = 0; i < 120 && leaving <= 0; ++i) {
        impact = world.bodies()[0].linearVelocity.z();
        world.step();
        leaving = world.bodies()[0].linearVelocity.z();
    }
    ASSERT_GT(leaving, 0) << "the box never bounced";
    EXPECT_LT(impact, -world.settings().contact.restitutionThreshold);
    // Measured: 1.5e-9 short, the contact's relative softness (ContactSettings::relativeCfm 1e-9).
    EXPECT_NEAR(leaving / -impact, 0.4, 3e-9);
    EXPECT_EQ(detail::WorldAccess::counters(world).plainResolves, 0) << "a lone body's bounce loses energy";
}

// A light box welded under a heavy one, both still but the light one thrown at the floor a unit
// below it: the weld shares the light box's momentum with the heavy one, so the pair barely
// moves, and the speculative contact under the light box would be reached only by the throw.
// Newton's law asks that contact for 0.4 times the throw's speed upwards, which the weld would
// make the heavy box carry too: a thousand times the energy of the throw. The solve that gains
// energy through its bounce is done again without it; then momentum is all the step can keep.
TEST(Restitution, ABounceThatWouldGainEnergyThroughAJointIsRefused) {
    const Real light = 0.001, heavy = 1;
    const Figure figure = figureOfBlocks(
        {"origin", "below"}, boxBodyText("heavy", "origin", Vec3(4, 4, 4), Vec3(0, 0, 13), heavy) +
                                 boxBodyText("light", "below", Vec3(4, 4, 4), Vec3(0, 0, 5), light) +
                                 "fixed \"weld\" { body1 \"light\" body2 \"heavy\" }\n");
    WorldSettings settings;
    settings.comeToRest = false;
    settings.gravity.setZero();
    World world(figure, settings);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const Real throwSpeed = -200;  // 3.3 units within the step: the floor 1 unit away is reached
    world.setVelocity(1, Vec3(0, 0, throwSpeed), Vec3::Zero());
    const Real m = world.bodies()[1].mass(), M = world.bodies()[0].mass();
    const Real before = world.kineticEnergy();
    world.step();
    EXPECT_EQ(detail::WorldAccess::counters(world).plainResolves, 1);
    // The weld alone: momentum m·v shared by m + M, to rounding (measured: 4.6e-13 relative).
    const Real shared = m * throwSpeed / (m + M);
    for (const RigidBody& b : world.bodies()) EXPECT_NEAR(b.linearVelocity.z() / shared, 1, 1e-12);
    EXPECT_LT(world.kineticEnergy(), before * m / (m + M) * (1 + 1e-12));
    EXPECT_LT(world.maxJointError(), 1e-9);
}

}  // namespace
}  // namespace af
