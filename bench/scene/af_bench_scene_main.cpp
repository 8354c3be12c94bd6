// af-bench-scene: our engine on the ragdoll benchmark of docs/bench-scene.md, printing one JSON
// object of RunMetrics (engine "af", variant = solver). Only world.step() is timed. The solvers'
// fallback counters it prints are internal to the library (src/dynamics/world_access.h).

#include "af_scene.h"
#include "counted_step.h"
#include "dynamics/world_access.h"
#include "metrics.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Run the ragdoll benchmark scene (bench-scene.md) with the af engine; prints one JSON object."};
    std::string scene = "single";
    std::string solver = "tree";
    std::string sleep = "off";
    int steps = benchscene::kSteps;
    double maxSeconds = 0;
    app.add_option("--scene", scene, "single, grid4, grid16 or pile")
        ->check(CLI::IsMember({"single", "grid4", "grid16", "pile"}));
    int count = 0;
    int threads = 1;
    app.add_option("--threads", threads, "threads that step independent islands (WorldSettings::threads)")
        ->check(CLI::Range(1, 256));
    app.add_option("--count", count, "ragdolls of the pile (default 32)")->check(CLI::PositiveNumber);
    app.add_option("--solver", solver, "tree (the default), exact or pgs")->check(CLI::IsMember({"exact", "tree", "pgs"}));
    app.add_option("--steps", steps, "steps of 1/60 s")->check(CLI::PositiveNumber);
    app.add_option("--max-seconds", maxSeconds, "stop (partial) once the run has taken this long; 0: no limit")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--sleep", sleep, "let figures come to rest (on) or keep them awake (off)")
        ->check(CLI::IsMember({"on", "off"}));
    CLI11_PARSE(app, argc, argv);

    const std::map<std::string, af::SolverKind> solvers = {
        {"exact", af::SolverKind::Exact}, {"tree", af::SolverKind::Tree}, {"pgs", af::SolverKind::Pgs}};
    const bool sleeping = sleep == "on";
    af::World world = benchscene::buildAfWorld(scene, solvers.at(solver), sleeping, count);
    af::WorldSettings settings = world.settings();
    settings.threads = threads;
    world.setSettings(settings);
    const int ragdolls = static_cast<int>(world.figureIds().size());
    benchscene::RunMetrics metrics(ragdolls);
    std::vector<benchscene::BodyState> states;
    benchscene::readStates(world, states);
    metrics.setInitial(states);

    const Clock::time_point start = Clock::now();
    bool partial = false;
    int sparseFallbacks = 0, treeFallbacks = 0, projectionPasses = 0, shakeRefusals = 0, plainResolves = 0;
    for (int s = 0; s < steps; ++s) {
        if (maxSeconds > 0 && seconds(Clock::now() - start) > maxSeconds) {
            partial = true;
            break;
        }
        const Clock::time_point t0 = Clock::now();
        {
            const benchscene::CountedStep counted;
            world.step();
        }
        const Clock::time_point t1 = Clock::now();
        const af::SolverCounters& counters = af::detail::WorldAccess::counters(world);
        sparseFallbacks += counters.sparseFallbacks;
        treeFallbacks += counters.treeFallbacks;
        projectionPasses += counters.projectionPasses;
        shakeRefusals += counters.shakeRefusals;
        plainResolves += counters.plainResolves;
        benchscene::readStates(world, states);
        metrics.addStep(states, seconds(t1 - t0), world.maxPenetration());
        if (sleeping) metrics.addSleep(world.atRest());
    }
    const std::string extra = "\"twist_limited\": true, \"solver_failures\": " +
                              std::to_string(world.solverFailures()) +
                              ", \"sparse_fallbacks\": " + std::to_string(sparseFallbacks) +
                              ", \"tree_fallbacks\": " + std::to_string(treeFallbacks) +
                              ", \"projection_passes\": " + std::to_string(projectionPasses) +
                              ", \"shake_refusals\": " + std::to_string(shakeRefusals) +
                              ", \"plain_resolves\": " + std::to_string(plainResolves) +
                              ", \"sleep\": " + (sleeping ? "true" : "false");
    // A run on more threads is a variant of its own: "tree×2".
    const std::string variant = threads > 1 ? solver + "\u00d7" + std::to_string(threads) : solver;
    std::cout << metrics.json("af", variant, scene, partial, extra) << "\n";
    return 0;
}
