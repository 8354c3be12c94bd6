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
    // With the tree solver, a solve whose coupled friction the tree's pivoting did not settle is
    // tried again by the dense pivoting solve of all rows only on an island of at most this many
    // rows; a larger one keeps the tree's frozen-box answer (its joints held exactly). Measured:
    // after the tree failed, the dense solve settled a humanoid alone (177 rows, 1 057 pivots),
    // but never an island of several figures (stacks of 4 humanoids: 372 to 580 rows, 1 017 to
    // 17 748 pivots, all NotConverged; bench pile of 8: one such step cost 0.45 s).
    std::size_t denseRescueRows = 300;
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
        // Sweeps of a block's Schur complement each time the block is solved, when its auxiliary
        // rows are relaxed (beyond the pivot row limit, or past its pivot budget below):
        // warm-started, and inside the sweeps over the blocks, a few suffice.
        int relaxedSweeps = 10;
        // Pivots a block may spend in failed pivoting solves (tree and dense) within one solve,
        // per row of the block, before its later sweeps relax it. Measured: the pile of eight
        // humanoids that lands on itself (figure_blocks_test) needs up to 392 a row before a
        // retry settles; hostile soak piles spent up to 8 900 a row (20-37 s a step).
        int pivotsPerRow = 512;
    } blocks;
};

}  // namespace af
