#pragma once
// What a World's step did inside its solvers: pivots, sweeps and every fallback from one path to
// the next (docs/solver.md), beside the public StepReport (world.h). Internal: the counters
// tell how the solve went, which tests and benchmarks check and an embedder has no use for;
// read them through detail::WorldAccess (world_access.h).

namespace af {

struct SolverCounters {
    int pivots = 0;            // exact solver: pivots of the last velocity solve
    int iterations = 0;        // PGS or figure blocks: sweeps of the last substep's solves, at most
    int shakeRefusals = 0;     // substeps whose SHAKE correction was refused (island_shake.cpp)
    int plainResolves = 0;     // velocity solves that gained energy, done again with plain targets (island_step.cpp)
    int sparseFallbacks = 0;   // Tree solver: solves its sparse path gave up (tree factorisation used)
    int treeFallbacks = 0;     // Tree solver: substeps whose rows it could not serve (dense used)
    int largeIslands = 0;      // velocity solves of the last substep beyond exactRowLimit (blocks or PGS)
    int projectionPasses = 0;  // position projection passes of the last substep (all islands)

    // One island's counters added to the step's: every count summed, the sweeps the most of any.
    void add(const SolverCounters& c) {
        pivots += c.pivots;
        iterations = iterations > c.iterations ? iterations : c.iterations;
        shakeRefusals += c.shakeRefusals;
        plainResolves += c.plainResolves;
        sparseFallbacks += c.sparseFallbacks;
        treeFallbacks += c.treeFallbacks;
        largeIslands += c.largeIslands;
        projectionPasses += c.projectionPasses;
    }
};

}  // namespace af
