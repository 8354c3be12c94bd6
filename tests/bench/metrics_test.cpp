// The run metrics of docs/bench-scene.md §6 on hand-made states: a ragdoll resting in the T-pose,
// pushed into the ground, torn at a joint, bent beyond a limit, falling, exploding.

#include "metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>
#include <numbers>

namespace benchscene {
namespace {


// The T-pose with the soles on the ground, everything still.
std::vector<BodyState> standingStill() {
    const Placement atModel{kPivot, Quat::Identity(), Vec3::Zero()};
    std::vector<BodyState> states;
    for (int i = 0; i < kBodiesPerRagdoll; ++i) states.push_back(placeBody(atModel, i));
    return states;
}

double potentialEnergy() {
    double e = 0;
    for (const BoxBody& b : ragdollBodies()) e += b.mass * kGravity * b.centre.z();
    return e;
}

TEST(BenchMetrics, RestingTPoseHasNoErrorsAndRestsFromTheFirstStep) {
    RunMetrics metrics(1);
    const auto states = standingStill();
    metrics.setInitial(states);
    for (int s = 0; s < 5; ++s) metrics.addStep(states, 1e-5, 0);
    EXPECT_LT(metrics.jointErrMax(), 1e-15);  // round-off of anchor − centre + centre
    EXPECT_LT(metrics.jointAngErrMax(), 1e-15);
    EXPECT_EQ(metrics.limitViolMax(), 0.0);
    EXPECT_NEAR(metrics.groundPenMax(), 0.0, 1e-12);
    EXPECT_EQ(metrics.energyGainMax(), 0.0);
    ASSERT_TRUE(metrics.restStep().has_value());
    EXPECT_EQ(*metrics.restStep(), 0);
    EXPECT_FALSE(metrics.exploded());
    EXPECT_NEAR(metrics.last().potential, potentialEnergy(), 1e-9);
    EXPECT_EQ(metrics.last().kinetic, 0.0);
    const std::string json = metrics.json("af", "exact", "single", false, "\"twist_limited\": false");
    EXPECT_NE(json.find("\"rest_step\": 0"), std::string::npos) << json;
    EXPECT_NE(json.find("\"steps_done\": 5"), std::string::npos) << json;
    EXPECT_NE(json.find("\"us_per_step_median\": 10"), std::string::npos) << json;
    EXPECT_NE(json.find("\"exploded\": false, \"twist_limited\": false}"), std::string::npos) << json;
    EXPECT_EQ(json.find("sleep_step"), std::string::npos) << json;
}

TEST(BenchMetrics, BodyOneCentimetreBelowTheGroundIsPenetration) {
    auto states = standingStill();
    states[12].x.z() -= 0.01;  // r_foot
    RunMetrics metrics(1);
    metrics.addStep(states, 1e-5, 0.004);
    EXPECT_NEAR(metrics.groundPenMax(), 0.01, 1e-12);
    // The foot moved off its ankle anchor by the same centimetre.
    EXPECT_NEAR(metrics.jointErrMax(), 0.01, 1e-12);
    EXPECT_NE(metrics.json("af", "exact", "single", false).find("\"contact_depth_max_m\": 0.004"), std::string::npos);
}

TEST(BenchMetrics, TiltedBoxPenetratesByItsLowestCorner) {
    auto states = standingStill();
    // Head (half-extents 0.08, 0.1, 0.14) rotated 90° about X, centre 5 cm up: its lowest corner
    // is 0.1 below the centre, 5 cm under the ground.
    states[3].q = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()));
    states[3].x = Vec3(3, 0, 0.05);
    EXPECT_NEAR(measureStates(states, 1).groundPen, 0.05, 1e-12);
}

TEST(BenchMetrics, HingeBentBeyondItsLimitIsAViolationNotAnError) {
    auto states = standingStill();
    // r_wrist hinge about +Y at (0.755, 0, 1.37), limit [−0.1π, 0.2π]: bend the hand 0.3π about it.
    const JointDef& wrist = ragdollJoints()[5];
    const Quat bend(Eigen::AngleAxisd(0.3 * std::numbers::pi, wrist.axis1));
    states[6].q = bend;
    states[6].x = wrist.anchor + bend * (states[6].x - wrist.anchor);
    const StateMeasures m = measureStates(states, 1);
    EXPECT_NEAR(m.limitViol, 0.1 * std::numbers::pi, 1e-12);
    EXPECT_LT(m.jointErr, 1e-12);
    EXPECT_LT(m.jointAngErr, 1e-12);
}

TEST(BenchMetrics, HingeTurnedOffItsAxisIsAnAngularError) {
    auto states = standingStill();
    const JointDef& elbow = ragdollJoints()[4];  // axis +Z
    const Quat off(Eigen::AngleAxisd(0.02, Vec3::UnitX()));
    states[5].q = off;
    states[5].x = elbow.anchor + off * (states[5].x - elbow.anchor);
    EXPECT_NEAR(measureStates(states, 1).jointAngErr, 0.02, 1e-12);
}

TEST(BenchMetrics, FixedJointRotationAndTwistBeyondLimit) {
    auto states = standingStill();
    states[1].q = Quat(Eigen::AngleAxisd(0.03, Vec3(1, 1, 0).normalized()));  // belly, fixed to pelvis and chest
    EXPECT_NEAR(measureStates(states, 1).jointAngErr, 0.03, 1e-12);
    states = standingStill();
    states[3].q = Quat(Eigen::AngleAxisd(0.3 * std::numbers::pi, Vec3::UnitZ()));  // head twisted 0.3π, limit 0.25π
    EXPECT_NEAR(measureStates(states, 1).limitViol, 0.05 * std::numbers::pi, 1e-12);
}

TEST(BenchMetrics, FallingRagdollLosesPotentialEnergyWithoutGain) {
    RunMetrics metrics(1);
    const double dt = kTimeStep;
    auto start = standingStill();
    for (BodyState& b : start) b.x.z() += 2;
    metrics.setInitial(start);
    for (int s = 1; s <= 30; ++s) {
        auto states = start;
        const double t = s * dt;
        for (BodyState& b : states) {
            b.x.z() -= 0.5 * kGravity * t * t;
            b.v.z() = -kGravity * t;
        }
        metrics.addStep(states, 1e-5, -1);
    }
    // Exact free fall keeps E constant: any gain is round-off.
    EXPECT_LT(metrics.energyGainMax(), 1e-9);
    EXPECT_FALSE(metrics.restStep().has_value());
    EXPECT_NEAR(metrics.last().kinetic + metrics.last().potential, potentialEnergy() + 70 * kGravity * 2, 1e-9);
    EXPECT_NE(metrics.json("af", "exact", "single", false).find("\"contact_depth_max_m\": null"), std::string::npos);
}

TEST(BenchMetrics, EnergyRiseAboveTheRunningMinimumIsGain) {
    RunMetrics metrics(1);
    auto states = standingStill();
    metrics.addStep(states, 1e-5, 0);
    for (BodyState& b : states) b.x.z() -= 0.1;  // E drops by 70 g 0.1
    metrics.addStep(states, 1e-5, 0);
    for (BodyState& b : states) b.x.z() += 0.05;  // then rises by half of that
    metrics.addStep(states, 1e-5, 0);
    EXPECT_NEAR(metrics.energyGainMax(), 70 * kGravity * 0.05, 1e-9);
}

TEST(BenchMetrics, RestStepIsTheFirstOfTheStillSteps) {
    RunMetrics metrics(1);
    auto still = standingStill();
    auto moving = still;
    moving[6].w = Vec3(0, 0.2, 0);  // above 0.1 rad/s
    metrics.addStep(moving, 1e-5, 0);
    metrics.addStep(still, 1e-5, 0);
    metrics.addStep(moving, 1e-5, 0);
    metrics.addStep(still, 1e-5, 0);
    metrics.addStep(still, 1e-5, 0);
    ASSERT_TRUE(metrics.restStep().has_value());
    EXPECT_EQ(*metrics.restStep(), 3);
    metrics.addStep(moving, 1e-5, 0);
    EXPECT_FALSE(metrics.restStep().has_value());
}

TEST(BenchMetrics, SleepStepOnlyWhenReported) {
    RunMetrics metrics(1);
    const auto still = standingStill();
    for (const bool asleep : {false, false, true, true}) {
        metrics.addStep(still, 1e-5, 0);
        metrics.addSleep(asleep);
    }
    EXPECT_NE(metrics.json("af", "exact", "single", false).find("\"sleep_step\": 2"), std::string::npos);
}

TEST(BenchMetrics, FastOrFallenOrNaNBodiesExplode) {
    auto states = standingStill();
    states[0].v = Vec3(0, 0, -51);
    EXPECT_TRUE(measureStates(states, 1).exploded);
    states = standingStill();
    states[0].x.z() = -0.6;
    EXPECT_TRUE(measureStates(states, 1).exploded);
    states = standingStill();
    states[0].w.x() = std::nan("");
    EXPECT_TRUE(measureStates(states, 1).exploded);
    RunMetrics metrics(1);
    metrics.addStep(states, 1e-5, 0);
    metrics.addStep(standingStill(), 1e-5, 0);
    EXPECT_TRUE(metrics.exploded());  // once exploded, the run stays exploded
}

TEST(BenchMetrics, TimingStatistics) {
    RunMetrics metrics(1);
    const auto still = standingStill();
    for (const double s : {3e-6, 1e-6, 2e-6, 10e-6}) metrics.addStep(still, s, 0);
    const std::string json = metrics.json("ode", "dantzig", "single", true);
    EXPECT_NE(json.find("\"us_per_step_mean\": 4,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"us_per_step_median\": 2.5,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"us_per_step_max\": 10,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"wall_s\": 1.6e-05,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"partial\": true"), std::string::npos) << json;
}

TEST(BenchMetrics, MeanTimeIsSplitAtTheRestStep) {
    RunMetrics metrics(1);
    auto moving = standingStill();
    moving[3].w = Vec3(0, 0, 1);  // the head turning at 1 rad/s is not at rest
    const auto still = standingStill();
    metrics.addStep(moving, 30e-6, 0);
    metrics.addStep(moving, 50e-6, 0);
    for (int s = 0; s < 4; ++s) metrics.addStep(still, 2e-6, 0);
    ASSERT_EQ(metrics.restStep(), 2);
    const std::string json = metrics.json("af", "tree", "single", false);
    EXPECT_NE(json.find("\"us_per_step_mean_until_rest\": 40,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"us_per_step_mean_at_rest\": 2,"), std::string::npos) << json;

    RunMetrics neverRests(1);
    neverRests.addStep(moving, 4e-6, 0);
    neverRests.addStep(moving, 6e-6, 0);
    const std::string restless = neverRests.json("af", "tree", "single", false);
    EXPECT_NE(restless.find("\"us_per_step_mean_until_rest\": 5,"), std::string::npos) << restless;
    EXPECT_NE(restless.find("\"us_per_step_mean_at_rest\": null,"), std::string::npos) << restless;
}

}  // namespace
}  // namespace benchscene
