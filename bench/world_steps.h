#pragma once
// The step benchmarks' loop: one world.step() per iteration, the world rebuilt (untimed) from
// its start every `runLength` steps, so that every run measures the same stretch of simulation;
// rows and joint error of the last step as counters; and the solvers to run it with.

#include "af/dynamics/world.h"

#include <benchmark/benchmark.h>

namespace af::bench {

template <class MakeWorld>
void stepWorlds(benchmark::State& state, MakeWorld makeWorld, int runLength) {
    World world = makeWorld();
    int steps = 0;
    for (auto _ : state) {
        if (steps++ == runLength) {
            state.PauseTiming();
            world = makeWorld();
            steps = 1;
            state.ResumeTiming();
        }
        world.step();
    }
    state.counters["rows"] = world.lastStep().rows;
    state.counters["joint_error"] = world.maxJointError();
}

// One run per solver, named as SolverKind numbers them: BENCHMARK(...)->Apply(eachSolver).
inline void eachSolver(benchmark::internal::Benchmark* b) {
    b->Arg(static_cast<int>(SolverKind::Exact))
        ->Arg(static_cast<int>(SolverKind::Tree))
        ->Arg(static_cast<int>(SolverKind::Pgs))
        ->ArgName("solver(0=exact,1=tree,2=pgs)")
        ->Unit(benchmark::kMicrosecond);
}

}  // namespace af::bench
