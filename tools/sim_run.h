#pragma once
// af-sim's run: steps a scene until every figure rests or the time runs out, measuring what a
// modder wants to know about the figure (joint error, penetration, limits, energy) on the way.

#include "sim_scene.h"

#include <functional>
#include <optional>
#include <vector>

namespace af::sim {

struct RunOptions {
    Real seconds = 10;  // simulated time limit
    // Keep running this long after the figures rest, to show that they stay at rest (a resting
    // world costs next to nothing).
    Real afterRest = 0;
    int framesWanted = 0;  // poses kept for a contact sheet, evenly spread over the run
};

struct Sample {
    Real time = 0;
    Real kineticEnergy = 0;
    Real maxJointError = 0;
};

struct RunResult {
    std::optional<Real> restTime;  // simulated seconds until every figure rested
    int steps = 0;
    Real simulatedSeconds = 0;
    Real wallSeconds = 0;
    Real maxJointError = 0;           // units, over the whole run
    Real maxPenetration = 0;          // units, over the whole run
    Real maxLimitViolationDeg = 0;    // degrees, over the whole run
    Real finalKineticEnergy = 0;
    int solverFailures = 0;
    // Figures whose motion a step made invalid (a NaN, or an explosion), put back by the world's
    // guard (StepReport::restored): when, which, why.
    struct Restore {
        Real time = 0;
        RestoredFigure figure;
    };
    std::vector<Restore> restored;
    // Figures that stood still with a joint open or a contact deep (StepReport::stuck), each
    // when it stopped so.
    struct Stuck {
        Real time = 0;
        StuckFigure figure;
    };
    std::vector<Stuck> stuck;
    std::vector<Sample> history;      // one per step
    std::vector<Real> frameTimes;     // the poses kept for pictures
    std::vector<std::vector<RigidPose>> frames;
};

// `afterStep` (optional) sees the world after every step: trajectories, baking.
RunResult run(Scene& scene, const RunOptions& options, const std::function<void(const World&)>& afterStep = {});

}  // namespace af::sim
