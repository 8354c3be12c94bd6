#pragma once
// The step benchmarks' loop: one world.step() per iteration, the world rebuilt (untimed) from
// its start every `runLength` steps, so that every run measures the same stretch of simulation;
// rows and joint error of the last step as counters.

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

}  // namespace af::bench
