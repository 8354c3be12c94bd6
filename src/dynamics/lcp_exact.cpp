// Exact solver, the passes: solve the current pattern (friction tied to its normals), check it,
// and pivot whatever the check released, until a pattern holds.
//
// A cold start begins with the unbounded rows clamped and everything else unprocessed; a warm
// start begins with the caller's guess. Either way each pass is
//   1. tied solve of the pattern and check of every processed row (lcp_exact_pattern.cpp);
//      done when nothing is released and nothing is left to pivot;
//   2. untied re-solves until the remaining processed rows are consistent with the values the
//      released rows now keep (each round only shrinks the processed set);
//   3. Dantzig pivoting of the unprocessed rows with fixed bounds (lcp_exact_pivot.cpp).
// Without coupling the second pass only confirms the first (or, after a warm start that held,
// the first pass is the only one). With coupling, step 1 is what makes friction bounds agree
// with the final normals rather than with the normals of the moment a friction row was pivoted.

#include "dynamics/lcp_internal.h"

namespace af {


LcpExactSolver::LcpExactSolver(const LcpExactSettings& settings) : impl_(std::make_unique<Impl>()) {
    impl_->settings = settings;
}

LcpExactSolver::~LcpExactSolver() = default;
LcpExactSolver::LcpExactSolver(LcpExactSolver&&) noexcept = default;
LcpExactSolver& LcpExactSolver::operator=(LcpExactSolver&&) noexcept = default;

void LcpExactSolver::reserve(int n) { impl_->reserve(n); }

const LcpExactSettings& LcpExactSolver::settings() const { return impl_->settings; }

void LcpExactSolver::setSettings(const LcpExactSettings& settings) { impl_->settings = settings; }

LcpResult LcpExactSolver::solve(const LcpProblem& problem, std::span<Real> outX,
                                std::span<LcpRowState> ioStates) {
    Impl&     s = *impl_;
    LcpResult result;
    const std::size_t n = problem.size > 0 ? static_cast<std::size_t>(problem.size) : 0;
    if (!lcpValidate(problem) || outX.size() != n || (!ioStates.empty() && ioStates.size() != n)) {
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    if (n == 0) {
        return result;
    }

    s.load(problem, ioStates);
    LcpStatus status = LcpStatus::Solved;
    for (int pass = 1;; ++pass) {
        result.couplingPasses = pass;
        s.solvePattern(true);
        int released = s.checkAndRelease(true);
        if (released == 0 && s.nP == s.n) {
            break;
        }
        if (pass >= s.settings.maxCouplingPasses) {
            status = LcpStatus::NotConverged;  // released rows stay unprocessed: reported failed
            break;
        }
        while (released > 0) {
            s.solvePattern(false);
            released = s.checkAndRelease(false);
        }
        s.pivotUnprocessed(pass % 2 == 0);
        if (s.pivotLimitHit) {
            s.solvePattern(false);
            status = LcpStatus::PivotLimit;
            break;
        }
    }
    s.finish(problem, outX, ioStates, result, status);
    return result;
}

}  // namespace af
