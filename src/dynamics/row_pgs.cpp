#include "row_pgs.h"

#include "pgs_sweeps.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

Real along(const Vec3& l, const Vec3& a, const Vec3& v, const Vec3& w) { return l.dot(v) + a.dot(w); }

}  // namespace

LcpPgsResult RowPgs::solve(const ConstraintRows& rows, const RowSystem& system, std::size_t bodyCount,
                           std::span<Real> ioX, const LcpPgsSettings& settings) {
    LcpPgsResult result;
    const LcpProblem problem = system.problem();
    const std::size_t n = rows.size();
    if (static_cast<std::size_t>(problem.size) != n || ioX.size() != n || !(settings.sor > 0 && settings.sor < 2)) {
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    const bool coupled = !problem.findex.empty();
    auto bounds = [&](std::size_t i, Real& lo, Real& hi) {
        if (coupled && problem.findex[i] >= 0) {
            hi = problem.mu[i] * std::abs(ioX[static_cast<std::size_t>(problem.findex[i])]);
            lo = -hi;
        } else {
            lo = problem.lo[i];
            hi = problem.hi[i];
        }
    };
    auto cfmOf = [&](std::size_t i) { return settings.cfm + (problem.cfm.empty() ? Real(0) : problem.cfm[i]); };

    linear_.assign(bodyCount, Vec3::Zero());
    angular_.assign(bodyCount, Vec3::Zero());
    auto push = [&](std::size_t i, Real impulse) {
        const ConstraintRow& r = rows[i];
        const RowResponse& m = system.response(i);
        if (r.bodyA != kWorldBody) {
            linear_[static_cast<std::size_t>(r.bodyA)] += impulse * m.linearA;
            angular_[static_cast<std::size_t>(r.bodyA)] += impulse * m.angularA;
        }
        if (r.bodyB != kWorldBody) {
            linear_[static_cast<std::size_t>(r.bodyB)] += impulse * m.linearB;
            angular_[static_cast<std::size_t>(r.bodyB)] += impulse * m.angularB;
        }
    };
    invDiagonal_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        Real lo, hi;
        bounds(i, lo, hi);
        ioX[i] = std::clamp(ioX[i], lo, hi);
        const ConstraintRow& r = rows[i];
        const RowResponse& m = system.response(i);
        const Real diag = along(r.linearA, r.angularA, m.linearA, m.angularA) +
                          along(r.linearB, r.angularB, m.linearB, m.angularB) + cfmOf(i);
        invDiagonal_[i] = diag > 0 ? 1 / diag : 0;  // 0: the row cannot be relaxed; it stays put
        if (ioX[i] != 0) push(i, ioX[i]);
    }

    // w_i from the accumulated velocity changes of both bodies.
    auto wOf = [&](std::size_t i) {
        const ConstraintRow& r = rows[i];
        Real w = cfmOf(i) * ioX[i] - problem.b[i];
        if (r.bodyA != kWorldBody)
            w += along(r.linearA, r.angularA, linear_[static_cast<std::size_t>(r.bodyA)],
                       angular_[static_cast<std::size_t>(r.bodyA)]);
        if (r.bodyB != kWorldBody)
            w += along(r.linearB, r.angularB, linear_[static_cast<std::size_t>(r.bodyB)],
                       angular_[static_cast<std::size_t>(r.bodyB)]);
        return w;
    };
    pgsSweeps(ioX, invDiagonal_, settings, bounds, wOf, push, result);
    if (settings.computeResidual) {
        // The natural residual (lcp.h), with w from the accumulators of the final impulses.
        for (std::size_t i = 0; i < n; ++i) {
            Real lo, hi;
            bounds(i, lo, hi);
            result.residual = std::max(result.residual, std::abs(ioX[i] - std::clamp(ioX[i] - wOf(i), lo, hi)));
        }
    }
    return result;
}

}  // namespace af
