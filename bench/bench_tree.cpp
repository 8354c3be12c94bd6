// The velocity solve of our humanoid hung from the world by its chest and shaken, dense exact
// against the tree solver, cold and warm-started: µs per solve of one step's rows (16 bodies,
// 16 joints with 67 equality rows, joint friction on every joint, limits as they come: about
// 100 rows). The scenes are 60 consecutive steps of a simulation (tree solver, one position
// pass per step), taken after the figure has swung into its limits; they are solved in order,
// so a warm start comes from the step before.
//
// Dense/Cold, Dense/Warm   RowSystem (A = J M⁻¹ Jᵀ) + LcpExactSolver, warm from the previous
//                          step's row states when the row count did not change (as World does)
// Tree/Cold, Tree/Warm     TreeSolver::factor + solveVelocity
// Tree/FactorOnly          TreeSolver::factor: the tree and the Schur complement
// Tree/FactorPositionOnly  the same for the position problem alone (friction rows left out)
// Tree/VelocityOnly, Tree/PositionOnly
//                          solveVelocity or solvePosition alone, again and again on one
//                          factorised pose (warm from itself): the part of a solve after factor
// Counters: rows, auxiliary rows (the LCP's size), pivots per solve, heap allocations per solve.

#include "dynamics/tree_solver.h"

#include "allocation_counter.h"
#include "dynamics/row_system.h"
#include "hung_humanoid.h"

#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

namespace {

using af::Real;

constexpr Real kDt = Real(1) / 60;
constexpr int kScenes = 60;
constexpr int kSettle = 20;  // steps before the first scene

struct Scene {
    std::vector<af::RigidBody> bodies;  // velocities predicted, before the constraint impulses
    af::ConstraintRows rows;
    std::vector<af::JointRowRange> ranges;
};

struct Scenes {
    std::vector<af::RigidBody> spawn;
    std::vector<af::Joint> joints;
    std::vector<Scene> steps;
};

void writeRows(const std::vector<af::Joint>& joints, const std::vector<af::RigidBody>& bodies, Scene& out) {
    out.rows.clear();
    out.ranges.clear();
    for (const af::Joint& j : joints) out.ranges.push_back(af::writeJointRows(j, bodies, af::JointRowSettings{}, out.rows));
}

const Scenes& scenes() {
    static const Scenes all = [] {
        Scenes s;
        const af::Figure figure = af::bench::hungHumanoid();
        for (const af::FigureBody& b : figure.bodies)
            s.spawn.push_back(af::RigidBody::dynamic(b.mass, b.inertia, b.pose.position, af::Quat(b.pose.rotation)));
        s.joints = af::makeJoints(figure);
        std::vector<af::RigidBody> bodies = s.spawn;
        std::mt19937 rng(3);
        std::uniform_real_distribution<Real> spin(-6, 6);
        for (af::RigidBody& b : bodies) b.angularVelocity = af::Vec3(spin(rng), spin(rng), spin(rng));
        af::TreeSolver solver;
        solver.setStructure(bodies, s.joints);
        Scene scratch;
        for (int i = 0; i < kSettle + kScenes; ++i) {
            for (af::RigidBody& b : bodies) af::integrateVelocity(b, af::Vec3(0, 0, -1066), kDt, af::IntegrationSettings{});
            writeRows(s.joints, bodies, scratch);
            if (i >= kSettle) s.steps.push_back({bodies, scratch.rows, scratch.ranges});
            solver.factor(scratch.rows, scratch.ranges, bodies);
            solver.solveVelocity(scratch.rows, bodies);
            solver.applyImpulses(bodies);
            const std::span<const Real> lambda = solver.impulses();
            for (std::size_t k = 0; k < s.joints.size(); ++k) {
                Real sum = 0;
                for (int r = 0; r < scratch.ranges[k].equalityRows; ++r)
                    sum += lambda[static_cast<std::size_t>(scratch.ranges[k].first + r)] *
                           lambda[static_cast<std::size_t>(scratch.ranges[k].first + r)];
                s.joints[k].lastImpulse = std::sqrt(sum);
            }
            for (af::RigidBody& b : bodies) af::integratePosition(b, kDt);
            writeRows(s.joints, bodies, scratch);
            solver.factor(scratch.rows, scratch.ranges, bodies, af::TreeProblems::PositionOnly);
            solver.solvePosition(scratch.rows);
            solver.applyDisplacements(bodies);
        }
        return s;
    }();
    return all;
}

void report(benchmark::State& state, long pivots, long allocations, long solves, int rows, int auxiliary) {
    state.counters["rows"] = rows;
    if (auxiliary >= 0) state.counters["aux_rows"] = auxiliary;
    state.counters["pivots"] = static_cast<double>(pivots) / static_cast<double>(solves);
    state.counters["allocs"] = static_cast<double>(allocations) / static_cast<double>(solves);
}

void dense(benchmark::State& state, bool warm) {
    const Scenes& all = scenes();
    af::RowSystem system;
    af::LcpExactSolver solver;
    std::vector<af::LcpRowState> previous;
    long pivots = 0, solves = 0, allocations = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        const Scene& scene = all.steps[k];
        k = (k + 1) % all.steps.size();
        const long before = af::test::gAllocations.load();
        system.build(scene.rows, scene.bodies);
        system.setVelocityRhs(scene.rows, scene.bodies);
        const std::span<af::LcpRowState> states = system.states();
        std::fill(states.begin(), states.end(), af::LcpRowState::Unknown);
        if (warm && previous.size() == states.size()) std::copy(previous.begin(), previous.end(), states.begin());
        const af::LcpResult r = solver.solve(system.problem(), system.solution(), states);
        previous.assign(states.begin(), states.end());
        allocations += af::test::gAllocations.load() - before;
        benchmark::DoNotOptimize(system.solution().data());
        pivots += r.pivots;
        ++solves;
    }
    report(state, pivots, allocations, solves, static_cast<int>(all.steps.back().rows.size()), -1);
}

enum class TreeCase { Cold, Warm, FactorOnly, FactorPositionOnly };

void tree(benchmark::State& state, TreeCase which) {
    const Scenes& all = scenes();
    af::TreeSolver solver;
    solver.setStructure(all.spawn, all.joints);
    for (const Scene& scene : all.steps) {  // warm-up: buffers reach their size
        solver.factor(scene.rows, scene.ranges, scene.bodies);
        solver.solveVelocity(scene.rows, scene.bodies);
    }
    long pivots = 0, solves = 0, allocations = 0;
    int auxiliary = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        const Scene& scene = all.steps[k];
        k = (k + 1) % all.steps.size();
        const long before = af::test::gAllocations.load();
        solver.factor(scene.rows, scene.ranges, scene.bodies,
                      which == TreeCase::FactorPositionOnly ? af::TreeProblems::PositionOnly
                                                            : af::TreeProblems::VelocityAndPosition);
        af::TreeSolveResult r;
        if (which == TreeCase::Cold) solver.resetWarmStart();
        if (which == TreeCase::Cold || which == TreeCase::Warm) r = solver.solveVelocity(scene.rows, scene.bodies);
        allocations += af::test::gAllocations.load() - before;
        benchmark::DoNotOptimize(solver.impulses().data());
        pivots += r.pivots;
        auxiliary = std::max(auxiliary, r.auxiliaryRows);
        ++solves;
    }
    report(state, pivots, allocations, solves, static_cast<int>(all.steps.back().rows.size()),
           which == TreeCase::Cold || which == TreeCase::Warm ? auxiliary : -1);
}

void treeSolveOnly(benchmark::State& state, bool position) {
    const Scenes& all = scenes();
    const Scene& scene = all.steps[all.steps.size() / 2];
    af::TreeSolver solver;
    solver.setStructure(all.spawn, all.joints);
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    af::TreeSolveResult r = position ? solver.solvePosition(scene.rows) : solver.solveVelocity(scene.rows, scene.bodies);
    long pivots = 0, solves = 0, allocations = 0;
    for (auto _ : state) {
        const long before = af::test::gAllocations.load();
        r = position ? solver.solvePosition(scene.rows) : solver.solveVelocity(scene.rows, scene.bodies);
        allocations += af::test::gAllocations.load() - before;
        benchmark::DoNotOptimize(solver.impulses().data());
        pivots += r.pivots;
        ++solves;
    }
    report(state, pivots, allocations, solves, static_cast<int>(scene.rows.size()), r.auxiliaryRows);
}

void BM_Dense_Cold(benchmark::State& state) { dense(state, false); }
void BM_Dense_Warm(benchmark::State& state) { dense(state, true); }
void BM_Tree_Cold(benchmark::State& state) { tree(state, TreeCase::Cold); }
void BM_Tree_Warm(benchmark::State& state) { tree(state, TreeCase::Warm); }
void BM_Tree_FactorOnly(benchmark::State& state) { tree(state, TreeCase::FactorOnly); }
void BM_Tree_FactorPositionOnly(benchmark::State& state) { tree(state, TreeCase::FactorPositionOnly); }
void BM_Tree_VelocityOnly(benchmark::State& state) { treeSolveOnly(state, false); }
void BM_Tree_PositionOnly(benchmark::State& state) { treeSolveOnly(state, true); }

BENCHMARK(BM_Dense_Cold)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dense_Warm)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_Cold)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_Warm)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_FactorOnly)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_FactorPositionOnly)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_VelocityOnly)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tree_PositionOnly)->Unit(benchmark::kMicrosecond);

}  // namespace
