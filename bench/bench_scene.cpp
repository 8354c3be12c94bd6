// Cost of one step of the benchmark ragdoll of docs/bench-scene.md, scene (a) `single` (16 boxes,
// 15 joints, dropped on the ground), collision included, for each solver: µs per 1/60 s step
// over the first 600 steps, restarted from the drop. Rest is off, so a figure that has come to
// rest is still solved every step.

#include "af_scene.h"
#include "world_steps.h"

#include <benchmark/benchmark.h>

namespace {

void BM_RagdollDropStep(benchmark::State& state) {
    const af::SolverKind solver = static_cast<af::SolverKind>(state.range(0));
    af::bench::stepWorlds(state, [&] { return benchscene::buildAfWorld("single", solver, false); }, benchscene::kSteps);
}
BENCHMARK(BM_RagdollDropStep)->Apply(af::bench::eachSolver);

}  // namespace
