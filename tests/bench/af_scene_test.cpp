// Our engine on the benchmark scene (a) `single` with the exact solver, judged by the scene's
// own metrics (bench-scene.md §6). Measured when written (Release, exact solver, 600 steps):
// joint error 3.9e-11 m, ground penetration 1.27 mm (= the contact slop, 0.05 inch), energy gain 0,
// rest from step 101, hinge, universal (§2 angles) and cone limits exceeded by 6.6e-11 rad at most.
// Twist is limited by our ball joint's twist limit (not in Doom's decl), set from §2.

#include "af_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace benchscene {
namespace {

// How far the limits are exceeded, by §2's angles: those our joints enforce as §2 defines them
// (hinge, cone swing, twist), and the hips, whose pyramid matches §2's cardan ranges only along
// its two central planes.
struct Violations {
    double exact = 0;
    double hips = 0;
};

Violations limitViolations(std::span<const BodyState> states) {
    Violations worst;
    const auto beyond = [](double a, double lo, double hi) { return std::max({0.0, lo - a, a - hi}); };
    for (const JointDef& j : ragdollJoints()) {
        const Quat& qA = states[j.parent].q;
        const Quat& qB = states[j.child].q;
        switch (j.kind) {
            case JointKind::Hinge: worst.exact = std::max(worst.exact, beyond(hingeAngle(j, qA, qB), j.lo1, j.hi1)); break;
            case JointKind::Universal: {
                const auto [t1, t2] = universalAngles(j, qA, qB);
                worst.hips = std::max({worst.hips, beyond(t1, j.lo1, j.hi1), beyond(t2, j.lo2, j.hi2)});
                break;
            }
            case JointKind::ConeTwist: {
                const auto [swing, twist] = swingTwist(j, qA, qB);
                worst.exact = std::max({worst.exact, swing - j.hi1, beyond(twist, j.lo2, j.hi2)});
                break;
            }
            case JointKind::Fixed: break;
        }
    }
    return worst;
}

struct Drop {
    RunMetrics metrics{1};
    Violations violation;
    int sparseFallbacks = 0;  // velocity and position solves the sparse path handed on
};

Drop dropTheRagdoll(af::SolverKind solver) {
    af::World world = buildAfWorld("single", solver, false);
    Drop run;
    std::vector<BodyState> states;
    readStates(world, states);
    run.metrics.setInitial(states);
    for (int s = 0; s < kSteps; ++s) {
        world.step();
        run.sparseFallbacks += world.lastStep().sparseFallbacks;
        readStates(world, states);
        run.metrics.addStep(states, 0, world.maxPenetration());
        const Violations now = limitViolations(states);
        run.violation.exact = std::max(run.violation.exact, now.exact);
        run.violation.hips = std::max(run.violation.hips, now.hips);
    }
    return run;
}

void expectTightJointsAndRest(const Drop& run) {
    const RunMetrics& metrics = run.metrics;
    EXPECT_FALSE(metrics.exploded());
    EXPECT_LT(metrics.jointErrMax(), 1e-6);  // m
    EXPECT_LT(metrics.groundPenMax(), 0.002);  // m: the slop (1.27 mm) and a little
    EXPECT_LT(metrics.energyGainMax(), 0.1);   // J, of 1380 J at the start
    ASSERT_TRUE(metrics.restStep().has_value());
    EXPECT_LT(*metrics.restStep(), 300);  // at rest within 5 s of the drop
    EXPECT_LT(run.violation.exact, 1e-6) << "hinge, cone or twist past its limit, rad";  // measured ~1e-10
    EXPECT_LT(run.violation.hips, 0.1) << "hips past §2's ranges, rad";                     // measured 0.033
    std::printf("limit violation: hinge/cone/twist %.6g rad, hips %.6g rad; joint ang err %.6g rad, "
                "rest step %d, ground pen %.6g m, sparse fallbacks %d\n",
                run.violation.exact, run.violation.hips, metrics.jointAngErrMax(), *metrics.restStep(),
                metrics.groundPenMax(), run.sparseFallbacks);
}

TEST(AfBenchScene, ExactSolverDropsTheRagdollToRestWithTightJoints) {
    expectTightJointsAndRest(dropTheRagdoll(af::SolverKind::Exact));
}

// The tree solver gives the same answers, and its sparse path serves nearly every solve, the
// impacts included: their rows that keep switching are settled by the dense core, grown by the
// rows its answer finds wrong (measured: 4 of about 840 solves handed on; 58 when the core was
// neither grown nor solved with frozen friction boxes).
TEST(AfBenchScene, TreeSolverDropsTheRagdollToRestWithTightJointsMostlyOnTheSparsePath) {
    const Drop run = dropTheRagdoll(af::SolverKind::Tree);
    expectTightJointsAndRest(run);
    EXPECT_LE(run.sparseFallbacks, 12);
}

}  // namespace
}  // namespace benchscene
