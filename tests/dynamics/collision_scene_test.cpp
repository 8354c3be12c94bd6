// Whole scenes with real collision: boxes and our humanoid dropped on floors and on each other.

#include "af/geometry/shapes.h"
#include "dynamics/world_access.h"
#include "scene_test_util.h"

#include <algorithm>

namespace af {
namespace {

using test::freeBox;
using test::humanoidAt;

Real lowestPoint(const World& world, int figure) {
    const World::FigureRange r = world.range(FigureId{figure});
    Real lowest = 1e30;
    for (int i = r.firstBody; i < r.firstBody + r.bodyCount; ++i) {
        const RigidBody& b = world.bodies()[static_cast<std::size_t>(i)];
        for (const Vec3& v : world.collision().bodyShape(i).vertices) lowest = std::min(lowest, (b.position + b.orientation * v).z());
    }
    return lowest;
}

Real centreHeight(const World& world, int figure) {
    const World::FigureRange r = world.range(FigureId{figure});
    Real sum = 0, mass = 0;
    for (int i = r.firstBody; i < r.firstBody + r.bodyCount; ++i) {
        const RigidBody& b = world.bodies()[static_cast<std::size_t>(i)];
        sum += b.mass() * b.position.z();
        mass += b.mass();
    }
    return sum / mass;
}

TEST(CollisionScene, BoxDroppedFlatRestsOnFourPointsWithoutDrift) {
    WorldSettings awake;
    awake.comeToRest = false;  // a resting box looks for no contacts; this test counts them
    World world(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 40)), awake);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    Real deepest = 0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        deepest = std::max(deepest, world.maxPenetration());
    }
    ASSERT_EQ(world.contacts().size(), 1u);
    EXPECT_EQ(world.contacts()[0].manifold.count, 4);
    EXPECT_LT(deepest, 0.5);
    const RigidBody& box = world.bodies()[0];
    EXPECT_NEAR(box.position.z(), 8, 0.5);
    EXPECT_LT(std::hypot(box.position.x(), box.position.y()), 1e-6) << "no sideways drift";
    EXPECT_LT(box.angularVelocity.norm(), 1e-6);
}

TEST(CollisionScene, StackOfFiveBoxesStandsForTenSeconds) {
    World world;
    for (int i = 0; i < 5; ++i) world.addFigure(freeBox(Vec3(8, 8, 8), Vec3(0, 0, 8 + 16.5 * i)));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    Real deepest = 0;
    for (int i = 0; i < 600; ++i) {
        world.step();
        deepest = std::max(deepest, world.maxPenetration());
    }
    for (int i = 0; i < 5; ++i) {
        const RigidBody& box = world.bodies()[static_cast<std::size_t>(i)];
        EXPECT_NEAR(box.position.z(), 8 + 16 * i, 1.0) << "box " << i;
        EXPECT_LT(std::hypot(box.position.x(), box.position.y()), 0.5) << "box " << i;
    }
    EXPECT_LT(deepest, 0.5);
    // A pivoting solve whose friction coupling does not settle falls back to PGS for that step;
    // it must stay rare.
    EXPECT_LT(world.solverFailures(), 600 / 50);
}

TEST(CollisionScene, BoxDroppedFromTwoThousandUnitsDoesNotTunnelThroughAThinFloor) {
    World world(freeBox(Vec3(6, 6, 6), Vec3(0, 0, 2000)));
    world.addStaticBrush(makeBox(Vec3(-200, -200, -8), Vec3(200, 200, 0)));
    Real lowest = 1e30;
    for (int i = 0; i < 480; ++i) {  // it lands at 830 units/s and bounces for a while
        world.step();
        lowest = std::min(lowest, lowestPoint(world, 0));
    }
    EXPECT_GT(lowest, -1.0) << "the box went into (or through) the 8-unit floor";
    EXPECT_NEAR(world.bodies()[0].position.z(), 6, 1.0);
}

TEST(CollisionScene, HumanoidDroppedFromAHundredUnitsLandsWithoutPenetratingOrJittering) {
    // Kept awake: it comes to rest at step 117, after which its kinetic energy is 0 by definition
    // and the jitter check below would measure nothing.
    WorldSettings awake;
    awake.comeToRest = false;
    World world(humanoidAt(Vec3(0, 0, 100)), awake);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    Real deepest = 0, lowest = 1e30;
    for (int i = 0; i < 240; ++i) {
        world.step();
        deepest = std::max(deepest, world.maxPenetration());
        lowest = std::min(lowest, lowestPoint(world, 0));
    }
    EXPECT_LT(deepest, 1.0);
    EXPECT_GT(lowest, -1.0);
    EXPECT_LT(world.maxJointError(), 1e-3);
    // Lying still, awake: the kinetic energy of 150 mass units at 1 unit/s would be 75; measured
    // at most 6.9e-21 over steps 240-300 (118 over steps 120-180, while it settles).
    Real energy = 0;
    for (int i = 0; i < 60; ++i) {
        world.step();
        energy = std::max(energy, world.kineticEnergy());
    }
    EXPECT_FALSE(world.atRest());
    EXPECT_LT(energy, 5e-20) << "the figure jitters on the floor";
}

// Every joint of our humanoid has Doom's joint friction (0.5), whose rows' states jump from step
// to step as the bounds follow the joints' last impulses. With the tree solver a landing is
// solved by the sparse path: its dense core takes those rows at once instead of finding them wrong
// a few per round, which grew cores past their limit and sent steps to the tree solver (these 18
// drops: 69 of 1612 steps, and one solver failure; since: 35 of 1534, none).
TEST(CollisionScene, HumanoidWithJointFrictionLandsOnTheTreeSolversSparsePath) {
    WorldSettings settings;
    settings.solver = SolverKind::Tree;
    int steps = 0, giveUps = 0, drops = 0;
    for (const Real yaw : {0, 30, 60, 90, 120, 150})
        for (const Real pitch : {0, 20, 45}) {
            World world(humanoidAt(Vec3(0, 0, 40), yaw, pitch), settings);
            world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
            ASSERT_TRUE(std::all_of(world.joints().begin(), world.joints().end(), [](const Joint& j) {
                return j.type == ConstraintType::Fixed || j.type == ConstraintType::Slider ||
                       j.type == ConstraintType::Spring || j.friction > 0;
            }));
            int step = 0;
            for (; step < 300 && !world.atRest(); ++step) {
                world.step();
                giveUps += detail::WorldAccess::counters(world).sparseFallbacks;
            }
            steps += step;
            ++drops;
            EXPECT_TRUE(world.atRest()) << "yaw " << yaw << ", pitch " << pitch;
            EXPECT_EQ(world.solverFailures(), 0) << "yaw " << yaw << ", pitch " << pitch;
            EXPECT_LT(world.maxJointError(), 1e-6) << "yaw " << yaw << ", pitch " << pitch;
        }
    std::printf("humanoid with joint friction, tree solver, %d drops: %d steps to rest, the sparse path gave up %d times\n",
                drops, steps, giveUps);
    EXPECT_LE(giveUps * 25, steps) << "the sparse path gave up in more than 4% of the steps";
}

TEST(CollisionScene, FiguresApartAreSeparateIslandsAndStepAsIfAlone) {
    // A humanoid dropped on the floor alone, and the same humanoid with a second one falling far
    // away (another island): the first one's bodies must follow bit for bit the same path, each
    // island being solved on its own copy of its bodies, rows and warm starts.
    WorldSettings settings;
    settings.comeToRest = false;
    World alone(settings);
    alone.addFigure(humanoidAt(Vec3(0, 0, 40), 30, 60));
    alone.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    World both(settings);
    both.addFigure(humanoidAt(Vec3(0, 0, 40), 30, 60));
    both.addFigure(humanoidAt(Vec3(400, 0, 80), -20, 90));
    both.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const std::size_t count = alone.bodies().size();
    int differingSteps = 0;
    for (int i = 0; i < 120; ++i) {
        alone.step();
        both.step();
        bool same = true;
        for (std::size_t b = 0; b < count; ++b) {
            const RigidBody& x = alone.bodies()[b];
            const RigidBody& y = both.bodies()[b];
            same = same && x.position == y.position && x.orientation.coeffs() == y.orientation.coeffs() &&
                   x.linearVelocity == y.linearVelocity && x.angularVelocity == y.angularVelocity;
        }
        differingSteps += same ? 0 : 1;
    }
    EXPECT_EQ(differingSteps, 0);
    EXPECT_LT(lowestPoint(both, 1), 1.0) << "the second figure should have landed too";
    EXPECT_LT(both.maxJointError(), 1e-6);
}

TEST(CollisionScene, TwoHumanoidsDroppedOntoEachOtherPileUp) {
    WorldSettings settings;
    settings.comeToRest = false;  // resting figures look for no contacts; this test wants to see them
    World world(settings);
    world.addFigure(humanoidAt(Vec3(0, 0, 20), 0, 90));
    world.addFigure(humanoidAt(Vec3(0, 0, 60), 0, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    Real deepest = 0;
    for (int i = 0; i < 180; ++i) {
        world.step();
        deepest = std::max(deepest, world.maxPenetration());
    }
    EXPECT_LT(deepest, 1.0);
    EXPECT_GT(centreHeight(world, 1), centreHeight(world, 0) + 3) << "the upper figure should lie on the lower one";
    bool touching = false;
    for (const BodyContact& c : world.contacts())
        touching = touching || (c.bodyB != kStaticWorld && world.figureOf(c.bodyA) != world.figureOf(c.bodyB));
    EXPECT_TRUE(touching);
}

}  // namespace
}  // namespace af
