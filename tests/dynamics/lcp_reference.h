#pragma once
// Independent references for the LCP tests: brute-force enumeration of complementarity patterns
// and a residual measure that does not share code with the solvers.

#include "lcp_test_problems.h"

#include <vector>

namespace af::test {

struct BruteForceResult {
    std::vector<std::vector<Real>> solutions;  ///< distinct solutions (farther apart than 1e-7)
    long                           patterns = 0;
};

/// Tries every pattern (each row free, at its lower bound or at its upper bound; for a coupled
/// row "at a bound" means x_i = ∓mu_i·x_j, assuming x_j ≥ 0 as for a contact normal), solves the
/// linear system the pattern defines, and keeps the solutions that satisfy all bounds and
/// complementarity conditions within `tol`. At most 10 rows (3¹⁰ patterns).
BruteForceResult bruteForce(const DenseLcp& problem, Real tol = 1e-9);

struct Violations {
    Real bound = 0;            ///< how far x lies outside its box (coupled boxes from x itself)
    Real complementarity = 0;  ///< per row, the distance to the nearest valid case, maximised
};

/// With w = (A + diag(cfm) + extraCfm·I) x − b: for each row the smallest of |w| (free),
/// |x − lo| + max(0, −w) (at lower) and |x − hi| + max(0, w) (at upper, finite bounds only).
Violations measure(const DenseLcp& problem, const std::vector<Real>& x, Real extraCfm = 0);

Real maxAbsDifference(const std::vector<Real>& u, const std::vector<Real>& v);

}  // namespace af::test
