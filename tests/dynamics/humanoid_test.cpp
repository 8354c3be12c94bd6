// Our humanoid, hung from the world by its chest and shaken: joints hold and limits are kept.

#include "../figure/figure_test_util.h"
#include "scene_test_util.h"

#include <random>

namespace af {
namespace {

void shake(World& world, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> spin(-6, 6);
    for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b) {
        // One draw a statement, z first: the order GCC gave Vec3(spin(rng), spin(rng), spin(rng)),
        // whose arguments may be evaluated in any order (clang drew x first and shook otherwise).
        const Real z = spin(rng), y = spin(rng), x = spin(rng);
        world.setVelocity(b, world.bodies()[static_cast<std::size_t>(b)].linearVelocity, Vec3(x, y, z));
    }
}

TEST(WorldHumanoid, HungByTheChestItSwingsTenSecondsWithTightJointsAndLimits) {
    World world(test::hungHumanoid(), test::dynamicsOnly());
    shake(world, 3);
    Real worstJoint = 0, worstLimit = 0;
    for (int i = 0; i < 600; ++i) {
        world.step();
        worstJoint = std::max(worstJoint, world.maxJointError());
        worstLimit = std::max(worstLimit, world.maxLimitViolationDegrees());
    }
    std::printf("humanoid hung by the chest, 10 s: max joint error %.3g units, max limit violation %.3g deg\n",
                worstJoint, worstLimit);
    EXPECT_LT(worstJoint, 1e-4);
    EXPECT_LT(worstLimit, 3.0);
    EXPECT_LT(world.maxLimitViolationDegrees(), 1.0) << "at the end, when the figure hangs still";
    EXPECT_EQ(world.solverFailures(), 0);
}

// The tree solver gives the dense solve's impulses (tree_solver_test.cpp); stepped in the world
// the two paths must stay together, and the tree path must really be taken (no fallback). Over
// the 30 steps they differ by 1.2e-11 units in position and 1.0e-10 rad/s in angular velocity,
// and the tree's joints are closed to 7e-15.
TEST(WorldHumanoid, TreeSolverStepsLikeTheExactSolver) {
    WorldSettings exactSettings = test::dynamicsOnly();
    exactSettings.solver = SolverKind::Exact;  // the default is the tree solver
    WorldSettings treeSettings = test::dynamicsOnly();
    treeSettings.solver = SolverKind::Tree;
    World exact(test::hungHumanoid(), exactSettings);
    World tree(test::hungHumanoid(), treeSettings);
    shake(exact, 5);
    shake(tree, 5);
    int fallbacks = 0;
    for (int i = 0; i < 30; ++i) {
        exact.step();
        tree.step();
        fallbacks += detail::WorldAccess::counters(tree).treeFallbacks;
        for (std::size_t b = 0; b < exact.bodies().size(); ++b) {
            ASSERT_LT((exact.bodies()[b].position - tree.bodies()[b].position).norm(), 5e-11) << "step " << i << " body " << b;
            ASSERT_LT((exact.bodies()[b].angularVelocity - tree.bodies()[b].angularVelocity).norm(), 5e-10) << "step " << i;
        }
    }
    EXPECT_EQ(fallbacks, 0);
    EXPECT_EQ(tree.solverFailures(), 0);
    EXPECT_LT(tree.maxJointError(), 5e-14);
}

// Our humanoid high above any floor, turning as one rigid body.
World spinningInFreeFall(SolverKind solver, const Vec3& spin) {
    WorldSettings settings = test::dynamicsOnly();
    settings.solver = solver;
    World world(test::humanoidAt(Vec3(0, 0, 1000), 0, 90), settings);
    Vec3 centre = Vec3::Zero();
    for (const RigidBody& b : world.bodies()) centre += b.position / world.bodies().size();
    for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b)
        world.setVelocity(b, spin.cross(world.bodies()[static_cast<std::size_t>(b)].position - centre), spin);
    return world;
}

// A figure turning as one rigid body opens its joints only by the O(dt²) drift of integrating
// each body on its own, and SHAKE closes that drift well: the hand, at the end of three joints
// that each correct a little, moves a few times as far as the largest drift, which must not count
// as an ill-conditioned correction (left to the position projection, whose limit rows it then has
// to settle again).
TEST(WorldHumanoid, AFigureSpinningInFreeFallKeepsEveryShakeCorrection) {
    for (const SolverKind solver : {SolverKind::Exact, SolverKind::Tree}) {
        World world = spinningInFreeFall(solver, Vec3(0.3, 0.2, 2));
        int refusals = 0;
        for (int i = 0; i < 60; ++i) {
            world.step();
            refusals += detail::WorldAccess::counters(world).shakeRefusals;
        }
        EXPECT_EQ(refusals, 0) << (solver == SolverKind::Tree ? "tree" : "exact");
        EXPECT_LT(world.maxJointError(), 1e-8);
        EXPECT_EQ(world.solverFailures(), 0);
    }
}

// SHAKE's second Newton step closes whatever drift the first left, so a figure turning slowly in
// free fall keeps its joints closed to rounding. Skipping the second step when the first left
// less than 1e-9 units piled its remainders up past positionTolerance (1e-10): with the tree
// solver, 54 projection passes in these 60 steps, and 15 at half this speed.
TEST(WorldHumanoid, AFigureTurningSlowlyInFreeFallNeedsNoProjection) {
    for (const SolverKind solver : {SolverKind::Exact, SolverKind::Tree}) {
        World world = spinningInFreeFall(solver, Vec3(0.03, 0.02, 0.2));
        world.step();  // the figure's own start
        int passes = 0;
        for (int i = 0; i < 60; ++i) {
            world.step();
            passes += detail::WorldAccess::counters(world).projectionPasses;
        }
        EXPECT_EQ(passes, 0) << (solver == SolverKind::Tree ? "tree" : "exact");
        EXPECT_LT(world.maxJointError(), 1e-10);
    }
}

}  // namespace
}  // namespace af
