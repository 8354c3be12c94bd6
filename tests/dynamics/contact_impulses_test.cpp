// World::contactImpulses: what the velocity solve applied at each contact point holds the bodies
// up against gravity, as Newton says it must.

#include "scene_test_util.h"

#include <cmath>
#include <numbers>

namespace af {
namespace {

using test::freeBox;

struct Sums {
    Real normal = 0;
    Vec3 friction = Vec3::Zero();
    Vec3 total = Vec3::Zero();  // normal and friction, world
    int points = 0;
};

Sums sumOver(const World& world) {
    const std::vector<ContactImpulse> impulses = world.contactImpulses();
    Sums s;
    std::size_t i = 0;
    for (const BodyContact& c : world.contacts())
        for (int k = 0; k < c.manifold.count; ++k, ++i) {
            s.normal += impulses.at(i).normal;
            s.friction += impulses.at(i).friction;
            s.total += impulses.at(i).normal * c.manifold.normal + impulses.at(i).friction;
            ++s.points;
        }
    EXPECT_EQ(i, impulses.size()) << "one impulse per point of contacts()";
    return s;
}

TEST(ContactImpulses, ABoxRestingOnTheFloorTakesItsWeightEveryStep) {
    WorldSettings settings;
    settings.comeToRest = false;
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8.5)), settings);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    for (int i = 0; i < 120; ++i) world.step();
    const Real weight = world.bodies()[0].mass() * world.settings().gravity.norm() * world.settings().timeStep;
    const Sums s = sumOver(world);
    EXPECT_EQ(s.points, 4) << "a box flat on the floor touches at its four corners";
    // Measured: equal to the last bit, friction 1e-16 of the weight.
    EXPECT_NEAR(s.normal / weight, 1, 1e-14);
    EXPECT_LT(s.friction.norm(), 1e-14 * weight) << "nothing pushes it sideways on a level floor";
}

// A figure at rest is not solved: the step it comes to rest in still reports what held it, and
// from the next its contacts are gone with their impulses.
TEST(ContactImpulses, ABoxComingToRestKeepsItsWeightForThatStepThenLeavesTheContacts) {
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8.5)));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    while (!world.atRest() && world.time() < 5) world.step();
    ASSERT_TRUE(world.atRest());
    const Real weight = world.bodies()[0].mass() * world.settings().gravity.norm() * world.settings().timeStep;
    // Measured: 2.8e-10 off, the box still settling by that much in the step it rests after.
    EXPECT_NEAR(sumOver(world).normal / weight, 1, 1e-9);
    world.step();
    EXPECT_TRUE(world.contacts().empty());
    EXPECT_TRUE(world.contactImpulses().empty());
}

// Gravity tilted by `slope` about Y is the floor tilted; friction μ = 0.8 holds the box below 38.7°.
TEST(ContactImpulses, FrictionHoldsABoxOnASlopeAgainstGravityAlongIt) {
    const Real slope = 20 * std::numbers::pi / 180;
    WorldSettings settings;
    settings.comeToRest = false;
    settings.gravity = 1066 * Vec3(std::sin(slope), 0, -std::cos(slope));
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8.5), 0.8), settings);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    for (int i = 0; i < 120; ++i) world.step();
    const Real m = world.bodies()[0].mass(), dt = world.settings().timeStep;
    const Sums s = sumOver(world);
    const Vec3 expected = -m * world.settings().gravity * dt;
    EXPECT_EQ(s.points, 4);
    // Measured: 4.8e-16 of gravity's impulse off.
    EXPECT_LT((s.total - expected).norm(), 1e-14 * expected.norm()) << "the contacts cancel gravity's impulse";
    EXPECT_NEAR(s.friction.x() / expected.x(), 1, 1e-14) << "friction holds against the slope's pull";
    EXPECT_LT(std::abs(s.friction.x()), 0.8 * s.normal) << "inside the friction cone";
}

}  // namespace
}  // namespace af
