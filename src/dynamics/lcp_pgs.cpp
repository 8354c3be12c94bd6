// Projected Gauss–Seidel on the boxed LCP: each row in turn gets the x_i that zeroes its w_i with
// the others fixed (relaxed by ω), clamped to its box. A coupled row's box is ±mu·|x_j| with the
// value x_j has at that moment, so a normal visited earlier in the same sweep already counts.
// It is the coordinate-descent view of min ½xᵀAx − bᵀx over the box, hence convergent for a
// positive definite A and 0 < ω < 2; friction coupling breaks that argument but behaves in
// practice, as in every sequential-impulse engine.

#include "lcp.h"

#include "dynamics/lcp_internal.h"
#include "dynamics/pgs_sweeps.h"

#include <algorithm>
#include <cmath>

namespace af {

LcpPgsSolver::LcpPgsSolver(const LcpPgsSettings& settings) : settings_(settings) {}

void LcpPgsSolver::reserve(int n) {
    if (invDiagonal_.size() < static_cast<std::size_t>(n)) {
        invDiagonal_.resize(static_cast<std::size_t>(n));
    }
}

LcpPgsResult LcpPgsSolver::solve(const LcpProblem& problem, std::span<Real> ioX) {
    LcpPgsResult result;
    const int    n = problem.size;
    if (!lcpValidate(problem) || ioX.size() != static_cast<std::size_t>(n) ||
        !(settings_.sor > 0 && settings_.sor < 2)) {
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    reserve(n);
    const std::size_t sn = static_cast<std::size_t>(n);
    const bool        hasCoupling = !problem.findex.empty();
    auto bounds = [&](int i, Real& lo, Real& hi) {
        if (hasCoupling && problem.findex[i] >= 0) {
            hi = problem.mu[i] * std::abs(ioX[problem.findex[i]]);
            lo = -hi;
        } else {
            lo = problem.lo[i];
            hi = problem.hi[i];
        }
    };
    for (int i = 0; i < n; ++i) {
        Real lo, hi;
        bounds(i, lo, hi);
        ioX[i] = std::clamp(ioX[i], lo, hi);
    }
    auto cfmOf = [&](int i) { return settings_.cfm + (problem.cfm.empty() ? Real(0) : problem.cfm[i]); };
    for (int i = 0; i < n; ++i) {
        const Real diag = problem.a[i * sn + i] + cfmOf(i);
        invDiagonal_[i] = diag > 0 ? 1 / diag : 0;  // 0: the row cannot be relaxed; it stays put
    }

    pgsSweeps(
        ioX, invDiagonal_, settings_,
        [&](std::size_t i, Real& lo, Real& hi) { bounds(static_cast<int>(i), lo, hi); },
        [&](std::size_t i) {
            return lcp::dot(problem.a.data() + i * sn, ioX.data(), n) + cfmOf(static_cast<int>(i)) * ioX[i] - problem.b[i];
        },
        [](std::size_t, Real) {}, result);
    result.residual = settings_.computeResidual ? lcpResidual(problem, ioX, settings_.cfm) : 0;
    return result;
}

}  // namespace af
