// The exact solver's frozen-box phase on coupled friction problems the coupled passes alone do
// not settle: damped boxes must reach an answer of the coupled problem, checked by the
// independent measure and by lcpResidual, and what they cannot solve must still be reported.

#include "lcp_test_util.h"

#include <gtest/gtest.h>

namespace af {
namespace {

using namespace test;

constexpr Real kFallbackTol = 1e-8;

TEST(FrozenBoxFallback, DampedBoxesSolveMostCoupledProblemsThePassesAloneCannot) {
    // Eight contacts on a dense Gram matrix couple normals and friction far more strongly than
    // bodies do. Measured on these 2 000 cold starts: the coupled passes alone leave 18
    // unsettled; the undamped frozen boxes (8 passes, stopping when they cycled) solved 11 of
    // them, the damped ones (32 passes) 16.
    Rng            rng(2024);
    LcpExactSolver passesOnly;
    LcpExactSolver boxed(LcpExactSettings{.frictionBoxPasses = 32});
    int            unsettled = 0;
    int            rescued = 0;
    for (int k = 0; k < 2000; ++k) {
        const DenseLcp p = randomCoupledProblem(rng, 8, rng.below(3));
        const ExactRun plain = solveExact(passesOnly, p);
        const ExactRun run = solveExact(boxed, p);
        if (run.result.status == LcpStatus::Solved) {
            ASSERT_TRUE(isSolution(p, run.x, kFallbackTol)) << "problem " << k;
            ASSERT_LE(lcpResidual(p.view(), run.x), kFallbackTol) << "problem " << k;
        } else {
            EXPECT_EQ(run.result.status, LcpStatus::NotConverged) << "problem " << k;
            EXPECT_FALSE(run.result.failedRows.empty()) << "problem " << k;
        }
        if (plain.result.status == LcpStatus::Solved) continue;
        ++unsettled;
        if (run.result.status == LcpStatus::Solved) ++rescued;
    }
    EXPECT_GE(unsettled, 10);  // the set is hard for the coupled passes
    EXPECT_GE(rescued, unsettled - 3);
}

TEST(FrozenBoxFallback, DampedBoxesSettleFromAStaleGuessOnContactProblems) {
    // The world's way on physical problems of three to six contacts: the guess is the answer to
    // the problem before b moved by a step's worth. Every answer reported solved solves the
    // coupled problem.
    Rng            rng(606);
    LcpExactSolver plain;
    LcpExactSolver boxed(LcpExactSettings{.frictionBoxPasses = 32});
    int            solved = 0;
    for (int k = 0; k < 1000; ++k) {
        const DenseLcp before = randomContactProblem(rng, 3 + k % 4, rng.below(4));
        DenseLcp       after = before;
        for (Real& v : after.b) v += 0.5 * (rng.uniform() - 0.5);
        const ExactRun guess = solveExact(plain, before);
        if (guess.result.status != LcpStatus::Solved) continue;
        ExactRun run = guess;
        run.result = boxed.solve(after.view(), run.x, run.states);
        ASSERT_NE(run.result.status, LcpStatus::InvalidInput) << "problem " << k;
        if (run.result.status != LcpStatus::Solved) continue;
        ++solved;
        ASSERT_TRUE(isSolution(after, run.x, kFallbackTol)) << "problem " << k;
        ASSERT_LE(run.result.residual, kFallbackTol) << "problem " << k;
    }
    EXPECT_GE(solved, 995);
}

}  // namespace
}  // namespace af
