// The start-of-step contact search kept from step to step while the bodies stay put
// (World::State::findContacts): whatever moves a body, or changes the collision world, between
// steps makes it look again.

#include "af/geometry/shapes.h"
#include "dynamics/world_access.h"
#include "scene_test_util.h"

namespace af {
namespace {

using test::freeBox;

bool touching(const World& world, int a, int b) {
    for (const BodyContact& c : world.contacts())
        if (c.bodyA == a && c.bodyB == b && c.manifold.count > 0) return true;
    return false;
}

// Two 10-unit frictionless boxes resting on the floor 3 units apart (beyond the 1-unit contact
// margin).
World boxesApart() {
    WorldSettings settings;
    settings.comeToRest = false;
    World world(settings);
    world.addFigure(freeBox(Vec3(5, 5, 5), Vec3(0, 0, 5), 0));
    world.addFigure(freeBox(Vec3(5, 5, 5), Vec3(13, 0, 5), 0));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    for (int i = 0; i < 60; ++i) world.step();
    return world;
}

// Set 0.5 units from the first box and thrown at it at 60 units/s (1 unit in the step): only a
// contact found at the step's start makes it bounce off the first box within the step (equal
// masses, bounciness 0.4: momentum −60 shared, relative velocity +24 after, so −42 and −18).
TEST(ContactSearch, ABoxThrownAtAnotherBetweenRestingStepsBouncesOffIt) {
    World world = boxesApart();
    ASSERT_FALSE(touching(world, 0, 1));
    ASSERT_LT(world.kineticEnergy(), 1e-9) << "both boxes rest";
    detail::WorldAccess::bodies(world)[1].position.x() = 10.5;  // behind the search's back
    world.setVelocity(1, Vec3(-60, 0, 0), world.bodies()[1].angularVelocity);
    world.step();
    EXPECT_NEAR(world.bodies()[0].linearVelocity.x(), -42, 1e-6);
    EXPECT_NEAR(world.bodies()[1].linearVelocity.x(), -18, 1e-6);
}

TEST(ContactSearch, ABoxWhoseFloorIsRemovedFalls) {
    World world = boxesApart();
    ASSERT_TRUE(touching(world, 0, kStaticWorld));
    world.removeStatic(0);
    const Real before = world.bodies()[0].linearVelocity.z();
    world.step();
    EXPECT_FALSE(touching(world, 0, kStaticWorld));
    // Free fall: dv = g·dt, no contact impulse from points found before the floor went.
    const Real expected = world.settings().gravity.z() * world.settings().timeStep;
    EXPECT_NEAR(world.bodies()[0].linearVelocity.z() - before, expected, 1e-9 * std::abs(expected));
}

TEST(ContactSearch, ARestingBoxKeepsTouchingTheFloorStepAfterStep) {
    World world = boxesApart();
    const Real z = world.bodies()[0].position.z();
    for (int i = 0; i < 120; ++i) {
        world.step();
        ASSERT_TRUE(touching(world, 0, kStaticWorld)) << "step " << i;
    }
    EXPECT_NEAR(world.bodies()[0].position.z(), z, 1e-9);
    EXPECT_LT(world.maxPenetration(), world.settings().contact.slop + 1e-6);
}

// Two resting boxes 0.5 units apart: their point is apart and was not closing, so the velocity
// solve leaves it out (Island::leaveOutFarPoints). A force that drives the second box into the
// first within the step (6000 units/s² for 1/60 s: 100 units/s, the gap closed in 1/200 s) must
// bring the point back into the same step's solve, whose contact row lets the boxes close the
// gap (and the slop) exactly by the step's end: frictionless, too slow before the force to
// bounce, equal masses, so −100 units/s shared with a relative speed of gap/dt. Left out, the
// first box would not move and the second would sink into it.
TEST(ContactSearch, AForceDrivingARestingBoxIntoItsNeighbourPushesItWithinTheStep) {
    World world = boxesApart();
    detail::WorldAccess::bodies(world)[1].position.x() = 10.5;
    for (int i = 0; i < 30; ++i) world.step();
    ASSERT_LT(world.kineticEnergy(), 1e-9) << "both boxes rest";
    const Real dt = world.settings().timeStep;
    const Real gap = (world.bodies()[1].position.x() - 5) - (world.bodies()[0].position.x() + 5) + world.settings().contact.slop;
    ASSERT_NEAR(gap, 0.55, 1e-6);
    const RigidBody& pushed = world.bodies()[1];
    world.addForce(1, pushed.position, Vec3(-6000 / pushed.inverseMass, 0, 0));
    world.step();
    EXPECT_NEAR(world.bodies()[0].linearVelocity.x(), -50 + gap / (2 * dt), 1e-6);
    EXPECT_NEAR(world.bodies()[1].linearVelocity.x(), -50 - gap / (2 * dt), 1e-6);
}

}  // namespace
}  // namespace af
