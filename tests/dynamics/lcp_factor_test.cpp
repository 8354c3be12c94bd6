// The incremental LDLᵀ of the exact LCP solver: after any sequence of appends and removals it
// must factorise exactly the matrix of the rows it holds, and refuse rows that depend on them.

#include "dynamics/lcp_internal.h"
#include "lcp_test_problems.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace af {
namespace {

using test::MatX;
using test::Rng;

// L D Lᵀ rebuilt from the factor's rows.
MatX product(const lcp::Ldlt& f) {
    const int m = f.size();
    MatX      l = MatX::Identity(m, m);
    MatX      d = MatX::Zero(m, m);
    for (int r = 0; r < m; ++r) {
        for (int c = 0; c < r; ++c) {
            l(r, c) = f.row(r)[c];
        }
        d(r, r) = f.pivot(r);
    }
    return l * d * l.transpose();
}

TEST(LcpFactor, AppendsAndRemovalsKeepFactorisingTheRowsHeld) {
    Rng rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const int  n = 2 + rng.below(14);
        const MatX a = test::randomGram(rng, n);
        lcp::Ldlt  f;
        f.reserve(n);
        f.reset(n);
        std::vector<Real> scratch(3 * n);
        std::vector<int>  held;  // the original rows, in factor order
        for (int step = 0; step < 4 * n; ++step) {
            const bool grow = held.empty() || (static_cast<int>(held.size()) < n && rng.chance(0.6));
            if (grow) {
                int r = rng.below(n);
                while (std::find(held.begin(), held.end(), r) != held.end()) {
                    r = (r + 1) % n;
                }
                std::vector<Real> row(held.size());
                for (std::size_t k = 0; k < held.size(); ++k) {
                    row[k] = a(r, held[k]);
                }
                ASSERT_TRUE(f.append(row.data(), a(r, r), 1e-12 * a(r, r), scratch.data()));
                held.push_back(r);
            } else {
                const int p = rng.below(static_cast<int>(held.size()));
                f.remove(p, scratch.data());
                held.erase(held.begin() + p);
            }
            const int m = static_cast<int>(held.size());
            ASSERT_EQ(f.size(), m);
            MatX expected(m, m);
            for (int i = 0; i < m; ++i) {
                for (int j = 0; j < m; ++j) {
                    expected(i, j) = a(held[i], held[j]);
                }
            }
            if (m == 0) {
                continue;
            }
            const Real err = (product(f) - expected).cwiseAbs().maxCoeff();
            ASSERT_LE(err, 1e-12 * std::max<Real>(1, expected.cwiseAbs().maxCoeff()))
                << "trial " << trial << " step " << step;
        }
    }
}

TEST(LcpFactor, SolvesWithTheMatrixOfTheRowsHeld) {
    Rng        rng(11);
    const int  n = 9;
    const MatX a = test::randomGram(rng, n);
    lcp::Ldlt  f;
    f.reserve(n);
    f.reset(n);
    std::vector<Real> scratch(3 * n);
    for (int r = 0; r < n; ++r) {
        ASSERT_TRUE(f.append(&a(0, r), a(r, r), 0, scratch.data()));  // column r = row r
    }
    f.remove(3, scratch.data());
    f.remove(0, scratch.data());
    const std::vector<int> held = {1, 2, 4, 5, 6, 7, 8};
    std::vector<Real>      v(held.size());
    for (std::size_t k = 0; k < held.size(); ++k) {
        v[k] = rng.uniform(-1, 1);
    }
    std::vector<Real> x = v;
    f.solve(x.data());
    for (std::size_t i = 0; i < held.size(); ++i) {
        Real sum = 0;
        for (std::size_t j = 0; j < held.size(); ++j) {
            sum += a(held[i], held[j]) * x[j];
        }
        EXPECT_NEAR(sum, v[i], 1e-12);
    }
}

TEST(LcpFactor, RefusesARowThatDependsOnTheRowsHeld) {
    // Rows 0 and 2 are equal: a redundant joint row without CFM.
    const MatX a = (MatX(3, 3) << 2, 1, 2, 1, 3, 1, 2, 1, 2).finished();
    lcp::Ldlt  f;
    f.reserve(3);
    f.reset(3);
    std::vector<Real> scratch(9);
    ASSERT_TRUE(f.append(&a(0, 0), a(0, 0), 1e-12 * a(0, 0), scratch.data()));
    ASSERT_TRUE(f.append(&a(0, 1), a(1, 1), 1e-12 * a(1, 1), scratch.data()));
    EXPECT_FALSE(f.append(&a(0, 2), a(2, 2), 1e-12 * a(2, 2), scratch.data()));
    EXPECT_EQ(f.size(), 2);
}

}  // namespace
}  // namespace af
