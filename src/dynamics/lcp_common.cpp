// Shared by both LCP solvers: input validation, the natural residual, status names.

#include "lcp.h"

#include "dynamics/lcp_internal.h"

#include <algorithm>
#include <cmath>

namespace af {

const char* toString(LcpStatus status) {
    switch (status) {
        case LcpStatus::Solved: return "solved";
        case LcpStatus::Unsatisfiable: return "unsatisfiable rows";
        case LcpStatus::NotConverged: return "friction coupling did not converge";
        case LcpStatus::PivotLimit: return "pivot limit reached";
        case LcpStatus::InvalidInput: return "invalid input";
    }
    return "?";
}

bool lcpValidate(const LcpProblem& problem, const char** outMessage) {
    auto fail = [&](const char* message) {
        if (outMessage) {
            *outMessage = message;
        }
        return false;
    };
    if (problem.size < 0) {
        return fail("negative size");
    }
    const std::size_t n = static_cast<std::size_t>(problem.size);
    if (problem.a.size() != n * n) {
        return fail("a must hold size*size entries");
    }
    if (problem.b.size() != n || problem.lo.size() != n || problem.hi.size() != n) {
        return fail("b, lo and hi must hold size entries");
    }
    if (!problem.findex.empty() && (problem.findex.size() != n || problem.mu.size() != n)) {
        return fail("findex and mu must both hold size entries");
    }
    if (problem.findex.empty() && !problem.mu.empty()) {
        return fail("mu given without findex");
    }
    if (!problem.cfm.empty() && problem.cfm.size() != n) {
        return fail("cfm must be empty or hold size entries");
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Real diag = problem.a[i * n + i];
        if (!std::isfinite(diag) || diag < 0) {
            return fail("a diagonal entry is negative or not finite");
        }
        if (!std::isfinite(problem.b[i])) {
            return fail("b is not finite");
        }
        if (!problem.cfm.empty() && !(problem.cfm[i] >= 0 && std::isfinite(problem.cfm[i]))) {
            return fail("cfm must be finite and >= 0");
        }
        const int j = problem.findex.empty() ? -1 : problem.findex[i];
        if (j >= 0) {
            if (static_cast<std::size_t>(j) >= n || static_cast<std::size_t>(j) == i) {
                return fail("findex out of range or pointing at its own row");
            }
            if (problem.findex[static_cast<std::size_t>(j)] >= 0) {
                return fail("findex points at a coupled row");
            }
            if (!(problem.mu[i] >= 0 && std::isfinite(problem.mu[i]))) {
                return fail("mu must be finite and >= 0");
            }
        } else if (j < -1) {
            return fail("findex below -1");
        } else {
            const Real lo = problem.lo[i];
            const Real hi = problem.hi[i];
            if (!(lo <= hi) || lo == kLcpInfinity || hi == -kLcpInfinity) {
                return fail("bounds must satisfy lo <= hi, lo < +inf, hi > -inf");
            }
        }
    }
    return true;
}

Real lcpResidual(const LcpProblem& problem, std::span<const Real> x, Real extraCfm) {
    const int n = problem.size;
    Real      worst = 0;
    for (int i = 0; i < n; ++i) {
        const std::size_t row = static_cast<std::size_t>(i) * static_cast<std::size_t>(n);
        const Real cfm = extraCfm + (problem.cfm.empty() ? Real(0) : problem.cfm[i]);
        const Real w = lcp::dot(problem.a.data() + row, x.data(), n) + cfm * x[i] - problem.b[i];
        Real       lo = problem.lo[i];
        Real       hi = problem.hi[i];
        if (!problem.findex.empty() && problem.findex[i] >= 0) {
            hi = problem.mu[i] * std::abs(x[problem.findex[i]]);
            lo = -hi;
        }
        const Real r = std::abs(x[i] - std::clamp(x[i] - w, lo, hi));
        if (!(r <= worst)) {  // NaN propagates
            worst = r;
        }
    }
    return worst;
}

}  // namespace af
