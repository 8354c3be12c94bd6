// Rest and wake of whole figures in a world with collision (world.h, rest.h).

#include "af/geometry/shapes.h"
#include "dynamics/world_access.h"
#include "scene_test_util.h"

namespace af {
namespace {

using test::freeBox;
using test::humanoidAt;

// Steps until every figure rests; returns the simulated time, or a negative value if `limit`
// seconds were not enough.
Real stepUntilRest(World& world, Real limit) {
    while (world.time() < limit) {
        world.step();
        if (world.atRest()) return world.time();
    }
    return -1;
}

TEST(WorldRest, DroppedHumanoidRestsWithinFiveSecondsAndStaysAtRest) {
    World world(humanoidAt(Vec3(0, 0, 40)));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const Real rest = stepUntilRest(world, 5);
    ASSERT_GT(rest, 0) << "not at rest after 5 s";
    const std::vector<RigidPose> atRest = world.bodyPoses();
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_TRUE(world.atRest());
    const std::vector<RigidPose> later = world.bodyPoses();
    for (std::size_t i = 0; i < later.size(); ++i) EXPECT_EQ(later[i].position, atRest[i].position) << "body " << i;
    EXPECT_EQ(world.kineticEnergy(), 0);
    EXPECT_EQ(world.lastStep().rows, 0) << "a resting figure costs no solver time";
}

TEST(WorldRest, ImpulseAboveTheThresholdWakesAndOneBelowIsIgnored) {
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8), 0));  // on ice, so that the woken box slides
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    ASSERT_GT(stepUntilRest(world, 3), 0);
    const Real threshold = world.settings().impulseThreshold;
    world.applyImpulse(0, world.bodies()[0].position, Vec3(0.9 * threshold, 0, 0));
    EXPECT_TRUE(world.figureAtRest(FigureId{0}));
    EXPECT_EQ(world.bodies()[0].linearVelocity.norm(), 0);
    world.applyImpulse(0, world.bodies()[0].position, Vec3(1.1 * threshold, 0, 0));
    EXPECT_FALSE(world.figureAtRest(FigureId{0}));
    const Real mass = world.bodies()[0].mass();
    EXPECT_NEAR(world.bodies()[0].linearVelocity.x(), 1.1 * threshold / mass, 1e-9);
    world.step();
    EXPECT_GT(world.bodies()[0].position.x(), 0.1) << "the woken box slides";
}

TEST(WorldRest, FigureAtTheTopOfItsArcStaysAwake) {
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8)));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    world.setVelocity(0, Vec3(0, 0, 400), Vec3::Zero());  // apex after 0.375 s
    Real firstRest = -1;
    for (int i = 0; i < 300 && firstRest < 0; ++i) {
        world.step();
        if (world.atRest()) firstRest = world.time();
    }
    ASSERT_GT(firstRest, 0);
    EXPECT_GT(firstRest, 0.75) << "it fell asleep in the air";
    EXPECT_LT(world.bodies()[0].position.z(), 9);
}

TEST(WorldRest, RemovingTheFloorWakesWhatLayOnIt) {
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8)));
    const int floor = world.addStaticBrush(makeBox(Vec3(-50, -50, -8), Vec3(50, 50, 0)));
    ASSERT_GT(stepUntilRest(world, 3), 0);
    world.removeStatic(floor);
    EXPECT_FALSE(world.atRest());
    for (int i = 0; i < 30; ++i) world.step();
    EXPECT_LT(world.bodies()[0].position.z(), 0) << "with the floor gone the box falls";
}

// Planes and brushes are numbered together, the numbers removeStatic takes: removing the plane
// under a box that also stands on a brush wakes it, and the brush still holds it.
TEST(WorldRest, PlanesAndBrushesShareTheNumbersRemoveStaticTakes) {
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8)));
    EXPECT_EQ(world.addStaticPlane(Plane{Vec3::UnitZ(), 0}), 0);
    EXPECT_EQ(world.addStaticBrush(makeBox(Vec3(-50, -50, -8), Vec3(50, 50, 0))), 1);
    EXPECT_EQ(world.collision().staticCount(), 2u);
    ASSERT_GT(stepUntilRest(world, 3), 0);
    world.removeStatic(0);
    EXPECT_FALSE(world.atRest());
    for (int i = 0; i < 30; ++i) world.step();
    EXPECT_NEAR(world.bodies()[0].position.z(), 8, 0.1) << "the brush holds the box";
}

TEST(WorldRest, PileOfHumanoidsSleepsAsOneIslandAndWakesWhenOneIsPushed) {
    // The default (tree) solver: the pile is one island whose rows outside the joints' equality
    // rows number beyond exactRowLimit, so the world solves it figure by figure (figure_blocks.h),
    // velocities and positions (the pivoting solver would take minutes over that dense problem).
    World world;
    for (int i = 0; i < 4; ++i) world.addFigure(humanoidAt(Vec3(0, 0, 20 + 30 * i), 0, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    int largeIslandSteps = 0;
    Real rest = 0;
    std::vector<Real> figureRest(4, 0);  // when each figure first came to rest
    Real worstJoint = 0;
    for (int i = 0; i < 600 && rest == 0; ++i) {
        world.step();
        largeIslandSteps += detail::WorldAccess::counters(world).largeIslands > 0 ? 1 : 0;
        worstJoint = std::max(worstJoint, world.maxJointError());
        for (int f = 0; f < 4; ++f)
            if (figureRest[static_cast<std::size_t>(f)] == 0 && world.figureAtRest(FigureId{f}))
                figureRest[static_cast<std::size_t>(f)] = world.time();
        if (world.atRest()) rest = world.time();
    }
    ASSERT_GT(rest, 0) << "the pile never slept";
    EXPECT_GT(largeIslandSteps, 0) << "the pile never made one island beyond exactRowLimit";
    // Each figure's block is solved exactly in every sweep, velocities and positions, so the
    // joints hold as in a figure alone (PGS over all rows, before the blocks: 5.3e-11 over the
    // fall; at 40a1086, when a pass's PGS answer did not lower the largest violation, 1.3e-5 at rest).
    EXPECT_LT(worstJoint, 5e-10) << "the blocks must close the joints";
    // Figures that touch rest as one group: none of the four came to rest on its own before the
    // pile did (all four at step 72), and every body of the resting pile is still.
    for (int f = 0; f < 4; ++f) EXPECT_EQ(figureRest[static_cast<std::size_t>(f)], rest) << "figure " << f;
    for (const RigidBody& b : world.bodies()) {
        EXPECT_EQ(b.linearVelocity.norm(), 0);
        EXPECT_EQ(b.angularVelocity.norm(), 0);
    }

    // Push the top figure hard: it wakes, and so does every figure it touches when it moves.
    const World::FigureRange top = world.range(FigureId{3});
    world.applyImpulse(top.firstBody, world.bodies()[static_cast<std::size_t>(top.firstBody)].position, Vec3(0, 0, -5000));
    EXPECT_FALSE(world.figureAtRest(FigureId{3}));
    world.step();
    int awake = 0;
    for (int f = 0; f < 4; ++f) awake += world.figureAtRest(FigureId{f}) ? 0 : 1;
    EXPECT_GE(awake, 2) << "the pushed figure must wake the figures it presses on";
}

// A box sunk 6 units into the floor with its centre bound where it is: the bind and the floor
// cannot both be met, so it stands still with the bind open or the contact deep. Resting would
// freeze that; the world calls it stuck instead, once, and keeps it awake, and once unbound it
// rises clear and rests as usual.
TEST(WorldRest, AFigureHeldWithAJointOpenIsStuckNotResting) {
    World world(freeBox(Vec3(4, 4, 4), Vec3(0, 0, -2)));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    world.bind(BodyRef{FigureId{0}, 0}, Vec3(0, 0, -2));
    std::vector<StuckFigure> stuck;
    while (world.time() < 3) {
        world.step();
        stuck.insert(stuck.end(), world.lastStep().stuck.begin(), world.lastStep().stuck.end());
        ASSERT_FALSE(world.atRest()) << "rested at " << world.time() << " s with the bind open "
                                     << world.maxJointError() << " or the box " << world.maxPenetration() << " deep";
    }
    ASSERT_EQ(stuck.size(), 1u) << "reported once";
    EXPECT_EQ(stuck[0].figure, FigureId{0});
    EXPECT_TRUE(stuck[0].jointError > kStuckJointError || stuck[0].penetration > kStuckPenetration);
    // Between them the bind and the contact still hold the 6 units the box was sunk by.
    EXPECT_NEAR(stuck[0].jointError + stuck[0].penetration, 6, 0.5);

    world.unbind(FigureId{0});
    world.wakeFigure(FigureId{0});
    const Real freed = world.time();
    const Real rest = stepUntilRest(world, freed + 3);
    ASSERT_GT(rest, 0) << "the freed box never rested";
    EXPECT_LT(world.maxPenetration(), kStuckPenetration);
    EXPECT_TRUE(world.lastStep().stuck.empty());
}

}  // namespace
}  // namespace af
