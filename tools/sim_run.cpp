#include "sim_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace af::sim {

RunResult run(Scene& scene, const RunOptions& options, const std::function<void(const World&)>& afterStep) {
    World& world = scene.world;
    RunResult result;
    const Real dt = world.settings().timeStep;
    const int maxSteps = static_cast<int>(std::ceil(options.seconds / dt - 1e-9));
    // Every pose is kept while running (a few kB per step), and the frames are picked evenly
    // over the run once its length is known.
    std::vector<Real> times;
    std::vector<std::vector<RigidPose>> poses;
    auto keepPoses = [&] {
        if (options.framesWanted <= 0) return;
        times.push_back(world.time());
        poses.push_back(world.bodyPoses());
    };
    keepPoses();

    const auto start = std::chrono::steady_clock::now();
    int stepsAfterRest = 0;
    while (result.steps < maxSteps) {
        world.step();
        ++result.steps;
        for (const RestoredFigure& r : world.lastStep().restored) result.restored.push_back({world.time(), r});
        for (const StuckFigure& s : world.lastStep().stuck) result.stuck.push_back({world.time(), s});
        const Real jointError = world.maxJointError();
        const Real kinetic = world.kineticEnergy();
        result.maxJointError = std::max(result.maxJointError, jointError);
        result.maxPenetration = std::max(result.maxPenetration, world.maxPenetration());
        result.maxLimitViolationDeg = std::max(result.maxLimitViolationDeg, world.maxLimitViolationDegrees());
        result.history.push_back({world.time(), kinetic, jointError});
        if (afterStep) afterStep(world);
        keepPoses();

        if (world.atRest()) {
            if (!result.restTime) result.restTime = world.time();
            if (++stepsAfterRest * dt >= options.afterRest) break;
        } else {
            result.restTime.reset();
            stepsAfterRest = 0;
        }
    }
    result.wallSeconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - start).count();
    const int kept = static_cast<int>(poses.size());
    const int frames = std::min(options.framesWanted, kept);
    for (int i = 0; i < frames; ++i) {
        const int at = frames == 1 ? kept - 1 : static_cast<int>(std::lround(Real(i) * (kept - 1) / (frames - 1)));
        result.frameTimes.push_back(times[static_cast<std::size_t>(at)]);
        result.frames.push_back(poses[static_cast<std::size_t>(at)]);
    }
    result.simulatedSeconds = world.time();
    result.finalKineticEnergy = world.kineticEnergy();
    result.solverFailures = world.solverFailures();
    return result;
}

}  // namespace af::sim
