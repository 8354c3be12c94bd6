#pragma once
// The answer of last resort for a coupled friction problem that the pivoting solver did not
// settle: never its impulses, which may be far from any solution. PGS estimates the normal
// impulses, the friction boxes are frozen at μ times those, and the pivoting solver solves that
// uncoupled problem, a convex one it always solves; if even that fails, PGS's bounded answer
// stands. Used by an island's velocity solve and by a figure's block (figure_blocks.h).

#include "lcp.h"

#include <span>
#include <vector>

namespace af {

struct FrozenBoxResult {
    LcpPgsResult estimate;  // PGS's, from x's start
    LcpResult frozen;       // the pivoting solve of the frozen problem (its answer kept if Solved)
};

class FrozenBoxFallback {
public:
    // x: PGS's start on input, the answer on output; states: the frozen solve's row states.
    FrozenBoxResult solve(const LcpProblem& problem, std::span<Real> x, std::span<LcpRowState> states,
                          LcpExactSolver& exact, LcpPgsSolver& pgs);

private:
    std::vector<Real> lo_, hi_, pgsAnswer_;
};

}  // namespace af
