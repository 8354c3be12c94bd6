#include "lcp_reference.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace af::test {

namespace {

constexpr int kMaxRows = 10;
using SmallMat = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;
using SmallVec = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxRows, 1>;

enum Choice { kFree, kLower, kUpper };

Real effective(const DenseLcp& p, int i, int j) {
    return p.at(i, j) + (i == j && !p.cfm.empty() ? p.cfm[i] : Real(0));
}

void rowBounds(const DenseLcp& p, const std::vector<Real>& x, int i, Real& lo, Real& hi) {
    if (p.isCoupled(i)) {
        hi = p.mu[i] * std::abs(x[p.findex[i]]);
        lo = -hi;
    } else {
        lo = p.lo[i];
        hi = p.hi[i];
    }
}

}  // namespace

Real maxAbsDifference(const std::vector<Real>& u, const std::vector<Real>& v) {
    Real d = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        d = std::max(d, std::abs(u[i] - v[i]));
    }
    return d;
}

Violations measure(const DenseLcp& p, const std::vector<Real>& x, Real extraCfm) {
    Violations v;
    for (int i = 0; i < p.n; ++i) {
        Real w = -p.b[i] + extraCfm * x[i];
        for (int j = 0; j < p.n; ++j) {
            w += effective(p, i, j) * x[j];
        }
        Real lo, hi;
        rowBounds(p, x, i, lo, hi);
        v.bound = std::max({v.bound, lo - x[i], x[i] - hi});
        Real best = std::abs(w);
        if (std::isfinite(lo)) {
            best = std::min(best, std::abs(x[i] - lo) + std::max(Real(0), -w));
        }
        if (std::isfinite(hi)) {
            best = std::min(best, std::abs(x[i] - hi) + std::max(Real(0), w));
        }
        v.complementarity = std::max(v.complementarity, best);
    }
    return v;
}

BruteForceResult bruteForce(const DenseLcp& p, Real tol) {
    BruteForceResult result;
    const int        n = p.n;
    if (n > kMaxRows) {
        throw std::invalid_argument("bruteForce: at most 10 rows");
    }
    std::vector<int> options(n);
    for (int i = 0; i < n; ++i) {
        const bool coupled = p.isCoupled(i);
        options[i] = 1 + (coupled || std::isfinite(p.lo[i]) ? 1 : 0) + (coupled || std::isfinite(p.hi[i]) ? 1 : 0);
    }
    std::vector<int>  choice(n, 0);
    std::vector<Real> x(n);
    SmallMat          m(n, n);
    SmallVec          rhs(n);
    for (;;) {
        ++result.patterns;
        // One linear equation per row, according to its choice.
        m.setZero();
        for (int i = 0; i < n; ++i) {
            const bool coupled = p.isCoupled(i);
            int        c = choice[i];
            if (c == 1 && !coupled && !std::isfinite(p.lo[i])) {
                c = kUpper;  // a row with only an upper bound: its second option is the upper one
            }
            if (c == kFree) {
                for (int j = 0; j < n; ++j) {
                    m(i, j) = effective(p, i, j);
                }
                rhs(i) = p.b[i];
            } else {
                m(i, i) = 1;
                if (coupled) {
                    m(i, p.findex[i]) = (c == kLower ? 1 : -1) * p.mu[i];
                    rhs(i) = 0;
                } else {
                    rhs(i) = c == kLower ? p.lo[i] : p.hi[i];
                }
            }
        }
        const Eigen::FullPivLU<SmallMat> lu(m);
        if (lu.isInvertible()) {
            const SmallVec sol = lu.solve(rhs);
            for (int i = 0; i < n; ++i) {
                x[i] = sol(i);
            }
            // Valid when inside every box and every bounded choice has w of the right sign.
            bool ok = true;
            for (int i = 0; i < n && ok; ++i) {
                Real lo, hi;
                rowBounds(p, x, i, lo, hi);
                if (x[i] < lo - tol || x[i] > hi + tol) {
                    ok = false;
                    break;
                }
                Real w = -p.b[i];
                for (int j = 0; j < n; ++j) {
                    w += effective(p, i, j) * x[j];
                }
                int c = choice[i];
                if (c == 1 && !p.isCoupled(i) && !std::isfinite(p.lo[i])) {
                    c = kUpper;
                }
                if (c == kFree) {
                    ok = std::abs(w) <= tol;
                } else if (std::abs(lo - hi) > tol) {  // a fixed row accepts any w
                    ok = c == kLower ? w >= -tol : w <= tol;
                }
            }
            if (ok) {
                const bool known = std::any_of(result.solutions.begin(), result.solutions.end(),
                                               [&](const std::vector<Real>& s) { return maxAbsDifference(s, x) <= 1e-7; });
                if (!known) {
                    result.solutions.push_back(x);
                }
            }
        }
        // Next pattern (mixed-radix counter).
        int i = 0;
        while (i < n && ++choice[i] == options[i]) {
            choice[i] = 0;
            ++i;
        }
        if (i == n) {
            break;
        }
    }
    return result;
}

}  // namespace af::test
