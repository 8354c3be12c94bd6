#pragma once
// How a World's islands tune their LCP solvers: the knobs of the pivoting solves (the dense one,
// the tree solver's auxiliary LCP and the sparse path) and of PGS. Internal: an embedder picks a
// solver (WorldSettings::solver) and never needs these; tests and benchmarks set them through
// detail::WorldAccess (world_access.h).

#include "lcp.h"

namespace af {

struct SolverTuning {
    // frictionBoxPasses: a tumbling figure's coupled friction drives cost far more than a few
    // plain boxed solves (lcp.h, LcpExactSettings::frictionBoxPasses).
    LcpExactSettings exact{.frictionBoxPasses = 32};
    LcpPgsSettings pgs;
    // Block Gauss–Seidel over an island's figures (figure_blocks.h): at most maxSweeps passes of
    // the blocks. The contacts between figures are iterated until a sweep changes none of them
    // by more than velocityShare of the slop crossed in a step (velocities), or positionShare of
    // the violation the projection's pass removes (positions). Each is of the order that the
    // other half of the step corrects: a velocity error of 1e-3·slop/dt leaves 1e-3 of the slop
    // for the projection, and each projection pass then removes 99 % of what is left.
    struct Blocks {
        int maxSweeps = 100;
        Real velocityShare = 1e-3;
        Real positionShare = 0.01;
    } blocks;
};

}  // namespace af
