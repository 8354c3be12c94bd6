// Cost of one step of our humanoid hung from the world by its chest and shaken, for each
// solver: µs per 1/60 s step, joints, limits and joint friction included (no collision yet).

#include "af/dynamics/world.h"
#include "hung_humanoid.h"
#include "world_steps.h"

#include <benchmark/benchmark.h>

#include <random>
#include <string>

namespace {

af::World shaken(const af::Figure& figure, af::SolverKind solver) {
    af::WorldSettings settings;
    settings.solver = solver;
    settings.comeToRest = false;  // measure the step, not a sleeping figure
    af::World world(figure, settings);
    std::mt19937 rng(3);
    std::uniform_real_distribution<af::Real> spin(-6, 6);
    for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b) {
        const af::Vec3 angular = af::Vec3(spin(rng), spin(rng), spin(rng));
        world.setVelocity(b, world.bodies()[static_cast<std::size_t>(b)].linearVelocity, angular);
    }
    return world;
}

void BM_HumanoidStep(benchmark::State& state) {
    const af::SolverKind solver = static_cast<af::SolverKind>(state.range(0));
    const af::Figure figure = af::bench::hungHumanoid();
    // Ten simulated seconds from the same shaken start, again and again.
    af::bench::stepWorlds(state, [&] { return shaken(figure, solver); }, 600);
}
BENCHMARK(BM_HumanoidStep)->Apply(af::bench::eachSolver);

}  // namespace
