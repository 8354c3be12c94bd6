// Projected Gauss–Seidel on the boxed LCP: each row in turn gets the x_i that zeroes its w_i with
// the others fixed (relaxed by ω), clamped to its box. A coupled row's box is ±mu·|x_j| with the
// value x_j has at that moment, so a normal visited earlier in the same sweep already counts.
// It is the coordinate-descent view of min ½xᵀAx − bᵀx over the box, hence convergent for a
// positive definite A and 0 < ω < 2; friction coupling breaks that argument but behaves in
// practice, as in every sequential-impulse engine.

#include "af/dynamics/lcp.h"

#include "dynamics/lcp_internal.h"

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

    result.status = LcpStatus::NotConverged;
    const Real omega = settings_.sor;
    for (int it = 1; it <= settings_.maxIterations; ++it) {
        Real maxChange = 0;
        Real maxAbs = 0;
        for (int i = 0; i < n; ++i) {
            const Real inv = invDiagonal_[i];
            if (inv == 0) {
                continue;
            }
            const Real w =
                lcp::dot(problem.a.data() + i * sn, ioX.data(), n) + cfmOf(i) * ioX[i] - problem.b[i];
            Real lo, hi;
            bounds(i, lo, hi);
            const Real next = std::clamp(ioX[i] - omega * w * inv, lo, hi);
            maxChange = std::max(maxChange, std::abs(next - ioX[i]));
            maxAbs = std::max(maxAbs, std::abs(next));
            ioX[i] = next;
        }
        result.iterations = it;
        result.lastChange = maxChange;
        if (maxChange <= settings_.tolerance * std::max(Real(1), maxAbs)) {
            result.status = LcpStatus::Solved;
            break;
        }
    }
    if (settings_.maxIterations <= 0) {
        result.status = LcpStatus::NotConverged;
    }
    result.residual = settings_.computeResidual ? lcpResidual(problem, ioX, settings_.cfm) : 0;
    return result;
}

}  // namespace af
