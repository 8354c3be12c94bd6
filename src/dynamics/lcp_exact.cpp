// Exact solver, the passes: solve the current pattern exactly, check it, and pivot whatever the
// check released, until a pattern holds.
//
// A cold start begins with the unbounded rows clamped and everything else unprocessed
// (uncoupled rows before coupled ones, so friction meets solved normals); a warm start begins
// with the caller's guess factorised. Each pass then
//   1. solves the pattern with friction rows tied to their normals and checks every processed
//      row against the bounds of the result (lcp_exact_pattern.cpp); done when nothing is
//      released and nothing is left to pivot;
//   2. repeats that solve-and-check on the smaller processed set until it holds (each round only
//      shrinks the set, so this ends);
//   3. drives the unprocessed rows by Dantzig pivoting (lcp_exact_pivot.cpp), in reverse order
//      on even passes: a pattern that failed to settle one way is approached from the other
//      side, which breaks the rare cycles of coupled problems.
// Without coupling, pass 2 merely confirms pass 1 (a warm start that holds needs one pass and
// no pivots). A coupled problem that does not settle within maxCouplingPasses is reported as
// NotConverged with the unsettled rows listed; the coupled problem can lack a solution when
// friction is strong, and it need not be unique.

#include "dynamics/lcp_internal.h"

namespace af {

namespace {

// Block-pivoting rounds tried before rows are released to Dantzig pivoting.
constexpr int kMaxFlipRounds = 8;

}  // namespace

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
        if (pass == 1) {
            // Single principal pivots on the worst row, while the number of wrong rows does not
            // grow: a nearly right warm start is repaired in about one pivot per changed row.
            int previous = s.n + 1;
            for (int round = 0; round < kMaxFlipRounds; ++round) {
                const int wrong = s.checkPattern(true, true);
                if (wrong == 0) {
                    break;
                }
                s.solvePattern(true);
                if (wrong > previous) {
                    break;
                }
                previous = wrong;
            }
        }
        int released = s.checkPattern(true, false);
        if (released == 0 && s.nP == s.n) {
            break;
        }
        if (pass >= s.settings.maxCouplingPasses) {
            status = LcpStatus::NotConverged;  // released rows stay unprocessed: reported failed
            break;
        }
        while (released > 0) {
            s.solvePattern(true);
            released = s.checkPattern(true, false);
        }
        s.pivotUnprocessed(pass);
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
