// The LCP solvers on a ragdoll-sized problem (tests/dynamics/lcp_test_problems.h): 16 bodies,
// 15 joints (59 equality rows), 10 limit rows and 8 ground contacts with 2 friction rows each,
// 93 rows in all, dense A = J M⁻¹ Jᵀ with Doom's CFM values.
//
// Exact/Cold       no warm start
// Exact/WarmSame   warm-started from its own answer (the lower bound of a warm step)
// Exact/WarmNext   warm-started from the previous step's answer, b perturbed by 0.001
// Pgs/N            N sweeps from zero; PgsWarm/N from the previous step's x
// Counters: pivots and residual per solve (the natural residual, see src/dynamics/lcp.h).

#include "lcp_test_problems.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using af::LcpExactSolver;
using af::LcpPgsSettings;
using af::LcpPgsSolver;
using af::LcpRowState;
using af::Real;
using af::test::DenseLcp;
using af::test::makeRagdollProblem;

constexpr int kScenes = 8;  // different velocity draws, cycled, so one lucky pattern cannot flatter

struct Scene {
    DenseLcp                 previous, current;
    std::vector<Real>        previousX;
    std::vector<LcpRowState> previousStates, ownStates;
};

const std::vector<Scene>& scenes() {
    static const std::vector<Scene> all = [] {
        std::vector<Scene> s;
        LcpExactSolver     solver;
        for (int k = 0; k < kScenes; ++k) {
            Scene scene{makeRagdollProblem(k + 1), makeRagdollProblem(k + 1, 0.001), {}, {}, {}};
            const int n = scene.current.n;
            scene.previousX.assign(n, 0);
            scene.previousStates.assign(n, LcpRowState::Unknown);
            solver.solve(scene.previous.view(), scene.previousX, scene.previousStates);
            std::vector<Real> x(n, 0);
            scene.ownStates.assign(n, LcpRowState::Unknown);
            solver.solve(scene.current.view(), x, scene.ownStates);
            s.push_back(std::move(scene));
        }
        return s;
    }();
    return all;
}

enum class Start { Cold, WarmSame, WarmNext };

void exact(benchmark::State& state, Start start) {
    const std::vector<Scene>& all = scenes();
    const int                 n = all[0].current.n;
    LcpExactSolver            solver;
    solver.reserve(n);
    std::vector<Real>        x(n);
    std::vector<LcpRowState> states(n);
    long                     pivots = 0;
    Real                     residual = 0;
    long                     solves = 0;
    int                      k = 0;
    for (auto _ : state) {
        const Scene& scene = all[k];
        k = (k + 1) % kScenes;
        switch (start) {
            case Start::Cold: std::fill(states.begin(), states.end(), LcpRowState::Unknown); break;
            case Start::WarmSame: std::copy(scene.ownStates.begin(), scene.ownStates.end(), states.begin()); break;
            case Start::WarmNext:
                std::copy(scene.previousStates.begin(), scene.previousStates.end(), states.begin());
                break;
        }
        const af::LcpResult r = solver.solve(scene.current.view(), x, states);
        benchmark::DoNotOptimize(x.data());
        pivots += r.pivots;
        residual = std::max(residual, r.residual);
        ++solves;
    }
    state.counters["rows"] = n;
    state.counters["pivots"] = static_cast<double>(pivots) / static_cast<double>(solves);
    state.counters["residual"] = residual;
}

void pgs(benchmark::State& state, bool warm) {
    const std::vector<Scene>& all = scenes();
    const int                 n = all[0].current.n;
    LcpPgsSolver              solver(LcpPgsSettings{.maxIterations = static_cast<int>(state.range(0)), .tolerance = 0});
    solver.reserve(n);
    std::vector<Real> x(n);
    Real              residual = 0;
    int               k = 0;
    for (auto _ : state) {
        const Scene& scene = all[k];
        k = (k + 1) % kScenes;
        if (warm) {
            std::copy(scene.previousX.begin(), scene.previousX.end(), x.begin());
        } else {
            std::fill(x.begin(), x.end(), Real(0));
        }
        const af::LcpPgsResult r = solver.solve(scene.current.view(), x);
        benchmark::DoNotOptimize(x.data());
        residual = std::max(residual, r.residual);
    }
    state.counters["rows"] = n;
    state.counters["residual"] = residual;
}

void BM_Exact_Cold(benchmark::State& state) { exact(state, Start::Cold); }
void BM_Exact_WarmSame(benchmark::State& state) { exact(state, Start::WarmSame); }
void BM_Exact_WarmNext(benchmark::State& state) { exact(state, Start::WarmNext); }
void BM_Pgs(benchmark::State& state) { pgs(state, false); }
void BM_PgsWarm(benchmark::State& state) { pgs(state, true); }

BENCHMARK(BM_Exact_Cold)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Exact_WarmSame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Exact_WarmNext)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Pgs)->Arg(10)->Arg(20)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PgsWarm)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
