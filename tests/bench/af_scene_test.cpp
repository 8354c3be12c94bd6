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

// How far the limits we enforce (hinge, universal via the pyramid, cone swing, twist) are exceeded.
double enforcedLimitViolation(std::span<const BodyState> states) {
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

TEST(AfBenchScene, ExactSolverDropsTheRagdollToRestWithTightJoints) {
    af::World world = buildAfWorld("single", af::SolverKind::Exact, false);
    RunMetrics metrics(1);
    std::vector<BodyState> states;
    readStates(world, states);
    metrics.setInitial(states);
    double enforcedViolation = 0;
    for (int s = 0; s < kSteps; ++s) {
        world.step();
        readStates(world, states);
        metrics.addStep(states, 0, world.maxPenetration());
        enforcedViolation = std::max(enforcedViolation, enforcedLimitViolation(states));
    }
    EXPECT_FALSE(metrics.exploded());
    EXPECT_LT(metrics.jointErrMax(), 1e-6);  // m
    EXPECT_LT(metrics.groundPenMax(), 0.002);  // m: the slop (1.27 mm) and a little
    EXPECT_LT(metrics.energyGainMax(), 0.1);   // J, of 1380 J at the start
    ASSERT_TRUE(metrics.restStep().has_value());
    EXPECT_LT(*metrics.restStep(), 300);  // at rest within 5 s of the drop
    EXPECT_LT(enforcedViolation, 1.0) << "largest violation of an enforced limit, rad";
    RecordProperty("enforced_limit_violation_rad", std::to_string(enforcedViolation));
    std::printf("enforced limit violation %.6g rad, joint ang err %.6g rad, limit viol (incl. twist) %.6g rad, "
                "rest step %d, ground pen %.6g m\n",
                enforcedViolation, metrics.jointAngErrMax(), metrics.limitViolMax(), *metrics.restStep(),
                metrics.groundPenMax());
}

}  // namespace
}  // namespace benchscene
