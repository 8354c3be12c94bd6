// The frozen-box fallback; see frozen_boxes.h.

#include "frozen_boxes.h"

#include <algorithm>
#include <cmath>

namespace af {

FrozenBoxResult FrozenBoxFallback::solve(const LcpProblem& problem, std::span<Real> x, std::span<LcpRowState> states,
                                         LcpExactSolver& exact, LcpPgsSolver& pgs) {
    FrozenBoxResult result;
    result.estimate = pgs.solve(problem, x);
    const std::size_t n = static_cast<std::size_t>(problem.size);
    lo_.assign(problem.lo.begin(), problem.lo.end());
    hi_.assign(problem.hi.begin(), problem.hi.end());
    for (std::size_t i = 0; i < n && !problem.findex.empty(); ++i) {
        const int source = problem.findex[i];
        if (source < 0) continue;
        const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(source)]);
        lo_[i] = -box;
        hi_[i] = box;
    }
    LcpProblem frozen = problem;
    frozen.lo = lo_;
    frozen.hi = hi_;
    frozen.findex = {};
    frozen.mu = {};
    pgsAnswer_.assign(x.begin(), x.end());
    std::fill(states.begin(), states.end(), LcpRowState::Unknown);
    result.frozen = exact.solve(frozen, x, states);
    if (result.frozen.status != LcpStatus::Solved) std::copy(pgsAnswer_.begin(), pgsAnswer_.end(), x.begin());
    return result;
}

}  // namespace af
