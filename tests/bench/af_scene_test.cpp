// Our engine on the benchmark scene (a) `single` with the exact solver, judged by the scene's
// own metrics (docs/bench-scene.md §6). Measured when the hips became Cardan joints (Release, exact
// solver, 600 steps): joint error 1.3e-10 m, locked rotations 6.8e-11 rad, limits (§2's angles)
// exceeded by 9.9e-11 rad at most, ground penetration 1.27 mm (= the contact slop, 0.05 inch),
// energy gain 2e-12 J, rest from step 103. Twist is limited by our ball joint's twist limit and
// the hips are our Cardan cross (neither is in Doom's decl), both set from §2.

#include "af_scene.h"
#include "../dynamics/allocation_counter.h"
#include "dynamics/world_access.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace benchscene {
namespace {

// How far the limits are exceeded, by §2's angles, over all joints (our joints enforce them as §2
// defines them: hinge, cone swing, twist, and the hips' Cardan angles).
double limitViolation(std::span<const BodyState> states) {
    double worst = 0;
    const auto beyond = [](double a, double lo, double hi) { return std::max({0.0, lo - a, a - hi}); };
    for (const JointDef& j : ragdollJoints()) {
        const Quat& qA = states[j.parent].q;
        const Quat& qB = states[j.child].q;
        switch (j.kind) {
            case JointKind::Hinge: worst = std::max(worst, beyond(hingeAngle(j, qA, qB), j.lo1, j.hi1)); break;
            case JointKind::Universal: {
                const auto [t1, t2] = universalAngles(j, qA, qB);
                worst = std::max({worst, beyond(t1, j.lo1, j.hi1), beyond(t2, j.lo2, j.hi2)});
                break;
            }
            case JointKind::ConeTwist: {
                const auto [swing, twist] = swingTwist(j, qA, qB);
                worst = std::max({worst, swing - j.hi1, beyond(twist, j.lo2, j.hi2)});
                break;
            }
            case JointKind::Fixed: break;
        }
    }
    return worst;
}

struct Drop {
    RunMetrics metrics{1};
    double limitViolation = 0;  // rad
    int sparseFallbacks = 0;  // velocity and position solves the sparse path handed on
    double slop = 0;          // m: the world's contact slop
};

Drop dropTheRagdoll(af::SolverKind solver) {
    af::World world = buildAfWorld("single", solver, false);
    Drop run;
    run.slop = world.settings().contact.slop;
    std::vector<BodyState> states;
    readStates(world, states);
    run.metrics.setInitial(states);
    for (int s = 0; s < kSteps; ++s) {
        world.step();
        run.sparseFallbacks += af::detail::WorldAccess::counters(world).sparseFallbacks;
        readStates(world, states);
        run.metrics.addStep(states, 0, world.maxPenetration());
        run.limitViolation = std::max(run.limitViolation, limitViolation(states));
    }
    return run;
}

void expectTightJointsAndRest(const Drop& run) {
    const RunMetrics& metrics = run.metrics;
    std::printf("joint err %.3g m, joint ang err %.3g rad, limit violation %.3g rad, ground pen %.6g m, "
                "energy gain %.3g J, rest step %d, sparse fallbacks %d\n",
                metrics.jointErrMax(), metrics.jointAngErrMax(), run.limitViolation, metrics.groundPenMax(),
                metrics.energyGainMax(), metrics.restStep().value_or(-1), run.sparseFallbacks);
    // Bounds a few times what the exact and tree solvers achieve (measured: joints 1.3e-10 m,
    // locked rotations 7e-11 to 1.2e-10 rad, limits 1e-10 rad, 2e-12 J gained, rest at step 103).
    EXPECT_FALSE(metrics.exploded());
    EXPECT_LT(metrics.jointErrMax(), 1e-9);  // m
    // The locked rotations (fixed joints, hinge axes, the hips' arms ⟂) hold as tightly as the anchors.
    EXPECT_LT(metrics.jointAngErrMax(), 1e-9);  // rad
    EXPECT_LT(run.limitViolation, 1e-9) << "a joint past its docs/bench-scene.md §2 limit, rad";
    EXPECT_LT(metrics.groundPenMax(), run.slop * 1.02);  // m: the slop and the projection's tolerance
    EXPECT_LT(metrics.energyGainMax(), 1e-9);         // J, of 1380 J at the start: rounding
    ASSERT_TRUE(metrics.restStep().has_value());
    EXPECT_LT(*metrics.restStep(), 150);  // at rest within 2.5 s of the drop
}

TEST(AfBenchScene, ExactSolverDropsTheRagdollToRestWithTightJoints) {
    expectTightJointsAndRest(dropTheRagdoll(af::SolverKind::Exact));
}

// The tree solver gives the same answers, and its sparse path serves nearly every solve, the
// impacts included: their rows that keep switching are settled by the dense core, grown by the
// rows its answer finds wrong (measured: none of the drop's solves handed on, 4 before the hips
// were Cardan joints; 58 when the core was neither grown nor solved with frozen friction boxes).
TEST(AfBenchScene, TreeSolverDropsTheRagdollToRestWithTightJointsMostlyOnTheSparsePath) {
    const Drop run = dropTheRagdoll(af::SolverKind::Tree);
    expectTightJointsAndRest(run);
    EXPECT_LE(run.sparseFallbacks, 2);
}

// Sixteen ragdolls landing side by side (scene grid4): where a projection pushes bodies out of
// one contact it must not push them into another that no search had seen yet. Measured: a
// forearm 4.1 mm into the floor at step 66 when the projection's problem held only what touched;
// with the pairs near it, the slop (1.27 mm) at most.
TEST(AfBenchScene, SixteenRagdollsLandWithoutAProjectionPushingABodyIntoTheFloor) {
    af::World world = buildAfWorld("grid4", af::SolverKind::Tree, false);
    RunMetrics metrics(static_cast<int>(world.figureIds().size()));
    std::vector<BodyState> states;
    readStates(world, states);
    metrics.setInitial(states);
    for (int s = 0; s < 80; ++s) {
        world.step();
        readStates(world, states);
        metrics.addStep(states, 0, world.maxPenetration());
    }
    const af::WorldSettings& settings = world.settings();
    std::printf("ground pen %.6g m, joint err %.3g m\n", metrics.groundPenMax(), metrics.jointErrMax());
    EXPECT_LT(metrics.groundPenMax(), settings.contact.slop * 1.02);  // the slop and the projection's tolerance
    EXPECT_LT(metrics.jointErrMax(), 1e-9);  // m; measured 1.3e-10
    EXPECT_EQ(world.solverFailures(), 0);
}

// Once a figure's largest structures have been seen (its rows, contacts and factorisations grow
// their buffers while it settles), a step allocates nothing: the resting ragdoll's 100 steps
// after it comes to rest (from step 103) make no heap allocation at all.
TEST(AfBenchScene, ARestingRagdollStepsWithoutAllocating) {
    af::World world = buildAfWorld("single", af::SolverKind::Tree, false);
    for (int s = 0; s < 150; ++s) world.step();
    const long before = af::test::gAllocations.load();
    for (int s = 0; s < 100; ++s) world.step();
    const long after = af::test::gAllocations.load();
    EXPECT_EQ(after - before, 0);
    for (const af::RigidBody& b : world.bodies()) EXPECT_LT(b.linearVelocity.norm(), 1e-6);  // m/s: at rest
}

}  // namespace
}  // namespace benchscene
