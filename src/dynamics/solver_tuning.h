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
};

}  // namespace af
