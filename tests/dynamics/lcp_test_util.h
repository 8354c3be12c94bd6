#pragma once
// Small helpers shared by the LCP test files.

#include "lcp_reference.h"

#include <gtest/gtest.h>

#include <vector>

namespace af::test {

struct ExactRun {
    LcpResult                result;
    std::vector<Real>        x;
    std::vector<LcpRowState> states;
};

/// Solves with states returned; `warm` (if not empty) is the warm-start guess.
inline ExactRun solveExact(LcpExactSolver& solver, const DenseLcp& p, std::vector<LcpRowState> warm = {}) {
    ExactRun run;
    run.x.assign(p.n, 0);
    run.states = warm.empty() ? std::vector<LcpRowState>(p.n, LcpRowState::Unknown) : std::move(warm);
    run.result = solver.solve(p.view(), run.x, run.states);
    return run;
}

/// x solves p: bounds and complementarity within tol, by the independent measure.
inline ::testing::AssertionResult isSolution(const DenseLcp& p, const std::vector<Real>& x, Real tol,
                                             Real extraCfm = 0) {
    const Violations v = measure(p, x, extraCfm);
    if (v.bound <= tol && v.complementarity <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "bound violation " << v.bound << ", complementarity violation "
                                         << v.complementarity << " (tolerance " << tol << ")";
}

inline ::testing::AssertionResult near(const std::vector<Real>& x, const std::vector<Real>& expected, Real tol) {
    const Real d = maxAbsDifference(x, expected);
    if (d <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "max |x − expected| = " << d << " > " << tol;
}

}  // namespace af::test
