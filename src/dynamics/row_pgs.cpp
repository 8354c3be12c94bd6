#include "row_pgs.h"

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

    result.status = LcpStatus::NotConverged;
    const Real omega = settings.sor;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        Real maxChange = 0;
        Real maxAbs = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const Real inv = invDiagonal_[i];
            if (inv == 0) continue;
            const ConstraintRow& r = rows[i];
            Real jdv = 0;
            if (r.bodyA != kWorldBody) {
                const std::size_t a = static_cast<std::size_t>(r.bodyA);
                jdv += along(r.linearA, r.angularA, linear_[a], angular_[a]);
            }
            if (r.bodyB != kWorldBody) {
                const std::size_t b = static_cast<std::size_t>(r.bodyB);
                jdv += along(r.linearB, r.angularB, linear_[b], angular_[b]);
            }
            const Real w = jdv + cfmOf(i) * ioX[i] - problem.b[i];
            Real lo, hi;
            bounds(i, lo, hi);
            const Real next = std::clamp(ioX[i] - omega * w * inv, lo, hi);
            const Real change = next - ioX[i];
            if (change != 0) push(i, change);
            maxChange = std::max(maxChange, std::abs(change));
            maxAbs = std::max(maxAbs, std::abs(next));
            ioX[i] = next;
        }
        result.iterations = it;
        result.lastChange = maxChange;
        if (maxChange <= settings.tolerance * std::max(Real(1), maxAbs)) {
            result.status = LcpStatus::Solved;
            break;
        }
    }
    if (settings.computeResidual) {
        // The natural residual (lcp.h), with w from the accumulators of the final impulses.
        for (std::size_t i = 0; i < n; ++i) {
            const ConstraintRow& r = rows[i];
            Real w = cfmOf(i) * ioX[i] - problem.b[i];
            if (r.bodyA != kWorldBody)
                w += along(r.linearA, r.angularA, linear_[static_cast<std::size_t>(r.bodyA)],
                           angular_[static_cast<std::size_t>(r.bodyA)]);
            if (r.bodyB != kWorldBody)
                w += along(r.linearB, r.angularB, linear_[static_cast<std::size_t>(r.bodyB)],
                           angular_[static_cast<std::size_t>(r.bodyB)]);
            Real lo, hi;
            bounds(i, lo, hi);
            result.residual = std::max(result.residual, std::abs(ioX[i] - std::clamp(ioX[i] - w, lo, hi)));
        }
    }
    return result;
}

}  // namespace af
