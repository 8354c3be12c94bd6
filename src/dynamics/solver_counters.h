#pragma once
// What a World's step did inside its solvers: pivots, sweeps and every fallback from one path to
// the next (docs/solver.md), beside the public StepReport (world.h). Internal: the counters
// tell how the solve went, which tests and benchmarks check and an embedder has no use for;
// read them through detail::WorldAccess (world_access.h).

namespace af {

struct SolverCounters {
    int pivots = 0;            // exact solver: pivots of the last velocity solve
    int iterations = 0;        // PGS: sweeps of the last velocity solve
    int shakeRefusals = 0;     // substeps whose SHAKE correction was refused (island_shake.cpp)
    int sparseFallbacks = 0;   // Tree solver: solves its sparse path gave up (tree factorisation used)
    int treeFallbacks = 0;     // Tree solver: substeps whose rows it could not serve (dense used)
    int largeIslands = 0;      // islands of the last substep solved by PGS for exceeding exactRowLimit
    int projectionPasses = 0;  // position projection passes of the last substep (all islands)
};

}  // namespace af
