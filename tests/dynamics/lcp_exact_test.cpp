// The exact LCP solver against brute-force enumeration of every complementarity pattern, on
// thousands of random small problems (deterministic seeds), and its warm start.
//
// Tolerances: solutions agree with the enumeration to 1e-9 and satisfy bounds and
// complementarity to 1e-9 (all problems are O(1) in scale, condition numbers up to ~10⁴).

#include "lcp_test_util.h"

#include <gtest/gtest.h>

namespace af {
namespace {

using namespace test;

constexpr Real kTol = 1e-9;

TEST(ExactLcp, MatchesBruteForceOnRandomUncoupledProblems) {
    // Every kind of row (equality, one-sided, boxed, fixed, boxes off zero), dense Gram matrices
    // and rank-deficient Jacobian ones made positive definite by CFM, n = 1…8.
    Rng            rng(20240601);
    LcpExactSolver solver;
    for (int k = 0; k < 3000; ++k) {
        const DenseLcp         p = randomUncoupledProblem(rng, 1 + k % 8);
        const BruteForceResult bf = bruteForce(p);
        ASSERT_EQ(bf.solutions.size(), 1u) << "positive definite and uncoupled: one solution (problem " << k << ")";
        const ExactRun run = solveExact(solver, p);
        ASSERT_EQ(run.result.status, LcpStatus::Solved) << "problem " << k;
        ASSERT_TRUE(near(run.x, bf.solutions[0], kTol)) << "problem " << k;
        ASSERT_TRUE(isSolution(p, run.x, kTol)) << "problem " << k;
        ASSERT_LE(run.result.residual, kTol) << "problem " << k;
    }
}

TEST(ExactLcp, SatisfiesCoupledFrictionBoundsOnRandomContactProblems) {
    // One or two bodies on the ground, one or two contacts with two friction rows each (mu up
    // to 1.2), up to two joint rows: the coupled bounds are those of the returned normals.
    Rng            rng(77);
    LcpExactSolver solver;
    int            unique = 0;
    for (int k = 0; k < 2000; ++k) {
        const DenseLcp         p = randomContactProblem(rng, 1 + k % 2, rng.below(3));
        const BruteForceResult bf = bruteForce(p);
        ASSERT_FALSE(bf.solutions.empty()) << "problem " << k;
        const ExactRun run = solveExact(solver, p);
        ASSERT_EQ(run.result.status, LcpStatus::Solved) << "problem " << k;
        ASSERT_TRUE(isSolution(p, run.x, kTol)) << "problem " << k;
        if (bf.solutions.size() == 1) {
            ++unique;
            ASSERT_TRUE(near(run.x, bf.solutions[0], kTol)) << "problem " << k;
        }
    }
    EXPECT_GT(unique, 1900);  // coupling rarely admits several solutions here
}

TEST(ExactLcp, FrozenFrictionBoxesSettleOnTheCoupledSolution) {
    // The world's way: frictionBoxPasses with a guess of states and impulses, here the answer to
    // the same problem with b moved (the next step), and with no guess. The result must solve the
    // coupled problem (the enumeration's solution when unique) whether or not the boxes settled.
    Rng            rng(515);
    LcpExactSolver plain;
    LcpExactSolver boxed(LcpExactSettings{.frictionBoxPasses = 8});
    int            unique = 0;
    for (int k = 0; k < 1000; ++k) {
        const DenseLcp before = randomContactProblem(rng, 1 + k % 2, rng.below(3));
        DenseLcp       after = before;
        for (Real& v : after.b) v += 0.05 * (rng.uniform() - 0.5);
        const ExactRun guess = solveExact(plain, before);
        ASSERT_EQ(guess.result.status, LcpStatus::Solved) << "problem " << k;
        ExactRun run;
        run.x = guess.x;
        run.states = guess.states;
        run.result = boxed.solve(after.view(), run.x, run.states);
        ASSERT_EQ(run.result.status, LcpStatus::Solved) << "problem " << k;
        ASSERT_TRUE(isSolution(after, run.x, kTol)) << "problem " << k;
        ASSERT_LE(run.result.residual, kTol) << "problem " << k;
        const BruteForceResult bf = bruteForce(after);
        // From no guess at all (every state Unknown, no impulses) the first pass cannot hold, so
        // the frozen-box phase always runs.
        ExactRun cold;
        cold.x.assign(after.n, 0);
        cold.states.assign(after.n, LcpRowState::Unknown);
        cold.result = boxed.solve(after.view(), cold.x, cold.states);
        ASSERT_EQ(cold.result.status, LcpStatus::Solved) << "problem " << k;
        ASSERT_TRUE(isSolution(after, cold.x, kTol)) << "problem " << k;
        if (bf.solutions.size() == 1) {
            ++unique;
            ASSERT_TRUE(near(run.x, bf.solutions[0], kTol)) << "problem " << k;
            ASSERT_TRUE(near(cold.x, bf.solutions[0], kTol)) << "problem " << k;
        }
    }
    EXPECT_GT(unique, 900);
}

TEST(ExactLcp, FrozenFrictionBoxesFromTheirOwnSolutionNeedNoPivots) {
    LcpExactSolver boxed(LcpExactSettings{.frictionBoxPasses = 8});
    for (int seed = 1; seed <= 10; ++seed) {
        const DenseLcp p = makeRagdollProblem(seed);
        const ExactRun cold = solveExact(boxed, p);
        ASSERT_EQ(cold.result.status, LcpStatus::Solved) << seed;
        ExactRun warm;
        warm.x = cold.x;
        warm.states = cold.states;
        warm.result = boxed.solve(p.view(), warm.x, warm.states);
        ASSERT_EQ(warm.result.status, LcpStatus::Solved) << seed;
        EXPECT_EQ(warm.result.pivots, 0) << seed;
        EXPECT_TRUE(near(warm.x, cold.x, 1e-9)) << seed;
    }
}

TEST(ExactLcp, SolvesDenseCoupledProblemsOrReportsTheRareOneThatDoesNotSettle) {
    // Random dense Gram matrices couple normals and friction far more strongly than bodies do.
    // The coupled problem is not a minimisation and pivoting can cycle on it; the passes break
    // most cycles. Measured: 10 of 80 000 such problems do not settle (1 of these 2 000); those
    // must be reported as such.
    Rng            rng(4242);
    LcpExactSolver solver;
    int            unsettled = 0;
    for (int k = 0; k < 2000; ++k) {
        const DenseLcp         p = randomCoupledProblem(rng, 1 + k % 2, rng.below(3));
        const BruteForceResult bf = bruteForce(p);
        ASSERT_FALSE(bf.solutions.empty()) << "problem " << k;
        const ExactRun run = solveExact(solver, p);
        if (run.result.status != LcpStatus::Solved) {
            ++unsettled;
            EXPECT_EQ(run.result.status, LcpStatus::NotConverged) << "problem " << k;
            EXPECT_FALSE(run.result.failedRows.empty()) << "problem " << k;
            continue;
        }
        ASSERT_TRUE(isSolution(p, run.x, kTol)) << "problem " << k;
        if (bf.solutions.size() == 1) {
            ASSERT_TRUE(near(run.x, bf.solutions[0], kTol)) << "problem " << k;
        }
    }
    RecordProperty("unsettled", unsettled);
    EXPECT_LE(unsettled, 2);
}

TEST(ExactLcp, WarmStartFromItsOwnSolutionNeedsNoPivots) {
    Rng            rng(99);
    LcpExactSolver solver;
    auto check = [&](const DenseLcp& p, const char* kind, int k) {
        const ExactRun cold = solveExact(solver, p);
        ASSERT_EQ(cold.result.status, LcpStatus::Solved) << kind << ' ' << k;
        const ExactRun warm = solveExact(solver, p, cold.states);
        ASSERT_EQ(warm.result.status, LcpStatus::Solved) << kind << ' ' << k;
        EXPECT_EQ(warm.result.pivots, 0) << kind << ' ' << k;
        EXPECT_EQ(warm.result.couplingPasses, 1) << kind << ' ' << k;
        EXPECT_EQ(warm.states, cold.states) << kind << ' ' << k;
        // Same pattern, factorised in another order: equal up to rounding (ragdoll x reach ~50).
        EXPECT_TRUE(near(warm.x, cold.x, 1e-10 * std::max<Real>(1, maxAbsDifference(cold.x, std::vector<Real>(p.n)))))
            << kind << ' ' << k;
    };
    for (int k = 0; k < 500; ++k) {
        check(randomUncoupledProblem(rng, 1 + k % 8), "uncoupled", k);
        check(randomContactProblem(rng, 1 + k % 2, rng.below(3)), "contact", k);
    }
    for (int seed = 1; seed <= 10; ++seed) {
        check(makeRagdollProblem(seed), "ragdoll", seed);
    }
}

TEST(ExactLcp, WarmStartAfterASmallChangePivotsAboutOncePerChangedRow) {
    // The next step of a ragdoll: b perturbed by up to 0.001. Cold solves take ~36 pivots.
    LcpExactSolver solver;
    long           coldPivots = 0;
    long           warmPivots = 0;
    long           changedRows = 0;
    for (int seed = 1; seed <= 40; ++seed) {
        const DenseLcp before = makeRagdollProblem(seed);
        const DenseLcp after = makeRagdollProblem(seed, 0.001);
        const ExactRun first = solveExact(solver, before);
        const ExactRun cold = solveExact(solver, after);
        const ExactRun warm = solveExact(solver, after, first.states);
        ASSERT_EQ(cold.result.status, LcpStatus::Solved) << seed;
        ASSERT_EQ(warm.result.status, LcpStatus::Solved) << seed;
        EXPECT_LE(warm.result.residual, 1e-9) << seed;
        coldPivots += cold.result.pivots;
        warmPivots += warm.result.pivots;
        for (int i = 0; i < after.n; ++i) {
            changedRows += first.states[i] != cold.states[i] ? 1 : 0;
        }
    }
    RecordProperty("coldPivots", static_cast<int>(coldPivots));
    RecordProperty("warmPivots", static_cast<int>(warmPivots));
    RecordProperty("changedRows", static_cast<int>(changedRows));
    EXPECT_LE(warmPivots, 2 * changedRows);
    EXPECT_LE(4 * warmPivots, coldPivots);
}

TEST(ExactLcp, WarmStartFromAWrongGuessStillFindsTheSolution) {
    Rng            rng(1234);
    LcpExactSolver solver;
    for (int k = 0; k < 1000; ++k) {
        const DenseLcp p = k % 2 == 0 ? randomUncoupledProblem(rng, 1 + k % 8) : randomContactProblem(rng, 1 + k % 2, rng.below(3));
        std::vector<LcpRowState> guess(p.n);
        for (LcpRowState& g : guess) {
            g = static_cast<LcpRowState>(rng.below(4));  // Unknown, Free, AtLower or AtUpper
        }
        const BruteForceResult bf = bruteForce(p);
        const ExactRun         run = solveExact(solver, p, guess);
        ASSERT_EQ(run.result.status, LcpStatus::Solved) << "problem " << k;
        ASSERT_TRUE(isSolution(p, run.x, kTol)) << "problem " << k;
        if (bf.solutions.size() == 1) {
            ASSERT_TRUE(near(run.x, bf.solutions[0], kTol)) << "problem " << k;
        }
    }
}

TEST(ExactLcp, SolvesTheRagdollSizedProblem) {
    // 93 rows: 59 joint rows, 10 limits, 8 contacts with 2 friction rows each (bench_lcp's scene).
    LcpExactSolver solver;
    for (int seed = 1; seed <= 20; ++seed) {
        const DenseLcp p = makeRagdollProblem(seed);
        const ExactRun run = solveExact(solver, p);
        ASSERT_EQ(run.result.status, LcpStatus::Solved) << seed;
        EXPECT_TRUE(isSolution(p, run.x, 1e-9)) << seed;
        EXPECT_LE(run.result.pivots, 2 * p.n) << seed;  // typically ~35; sliding feet cost more
    }
}

TEST(ExactLcp, IsBitForBitRepeatable) {
    // A solver that has seen other problems gives the same bits as a fresh one.
    const DenseLcp p = makeRagdollProblem(3);
    LcpExactSolver fresh;
    LcpExactSolver used;
    Rng            rng(5);
    for (int k = 0; k < 20; ++k) {
        solveExact(used, randomContactProblem(rng, 2, 2));
    }
    const ExactRun a = solveExact(fresh, p);
    const ExactRun b = solveExact(used, p);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.states, b.states);
    EXPECT_EQ(a.result.pivots, b.result.pivots);
}

}  // namespace
}  // namespace af
