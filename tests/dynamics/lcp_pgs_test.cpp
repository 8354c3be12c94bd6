// Projected Gauss–Seidel, measured against the exact solver: where it converges, how friction is
// projected, and that it says how far it got when it runs out of sweeps.

#include "lcp_test_util.h"

#include <gtest/gtest.h>

namespace af {
namespace {

using namespace test;

// Diagonally dominant enough for PGS to converge fast: MᵀM/n + I.
DenseLcp wellConditionedProblem(Rng& rng, int n) {
    DenseLcp p = randomUncoupledProblem(rng, n);
    p.cfm.clear();
    const MatX m = randomGram(rng, n) / Real(n) + MatX::Identity(n, n);
    setMatrix(p, m);
    return p;
}

TEST(PgsLcp, ConvergesToTheExactSolutionOnWellConditionedProblems) {
    Rng            rng(31);
    LcpExactSolver exact;
    LcpPgsSolver   pgs(LcpPgsSettings{.maxIterations = 2000, .tolerance = 1e-14});
    for (int k = 0; k < 300; ++k) {
        const DenseLcp    p = wellConditionedProblem(rng, 1 + k % 30);
        const ExactRun    reference = solveExact(exact, p);
        std::vector<Real> x(p.n, 0);
        const LcpPgsResult r = pgs.solve(p.view(), x);
        ASSERT_EQ(r.status, LcpStatus::Solved) << "problem " << k;
        EXPECT_LT(r.iterations, 2000) << "problem " << k;
        EXPECT_LE(r.residual, 1e-10) << "problem " << k;
        EXPECT_TRUE(near(x, reference.x, 1e-9)) << "problem " << k;
    }
}

TEST(PgsLcp, ConvergesToTheExactSolutionWithModerateFriction) {
    Rng            rng(32);
    LcpExactSolver exact;
    LcpPgsSolver   pgs(LcpPgsSettings{.maxIterations = 5000, .tolerance = 1e-14});
    for (int k = 0; k < 200; ++k) {
        DenseLcp p = randomCoupledProblem(rng, 1 + k % 2, rng.below(3));
        setMatrix(p, randomGram(rng, p.n) / Real(p.n) + MatX::Identity(p.n, p.n));
        p.cfm.clear();
        for (Real& m : p.mu) {
            m *= 0.5;
        }
        const BruteForceResult bf = bruteForce(p);
        std::vector<Real>      x(p.n, 0);
        const LcpPgsResult     r = pgs.solve(p.view(), x);
        ASSERT_EQ(r.status, LcpStatus::Solved) << "problem " << k;
        EXPECT_TRUE(isSolution(p, x, 1e-9)) << "problem " << k;
        if (bf.solutions.size() == 1) {
            EXPECT_TRUE(near(x, bf.solutions[0], 1e-9)) << "problem " << k;
            EXPECT_TRUE(near(solveExact(exact, p).x, bf.solutions[0], 1e-9)) << "problem " << k;
        }
    }
}

TEST(PgsLcp, OverRelaxationReachesTheSameSolution) {
    Rng          rng(33);
    LcpPgsSolver plain(LcpPgsSettings{.maxIterations = 2000, .tolerance = 1e-14});
    LcpPgsSolver over(LcpPgsSettings{.maxIterations = 2000, .tolerance = 1e-14, .sor = 1.3});
    for (int k = 0; k < 100; ++k) {
        const DenseLcp    p = wellConditionedProblem(rng, 2 + k % 20);
        std::vector<Real> a(p.n, 0);
        std::vector<Real> b(p.n, 0);
        ASSERT_EQ(plain.solve(p.view(), a).status, LcpStatus::Solved);
        ASSERT_EQ(over.solve(p.view(), b).status, LcpStatus::Solved);
        EXPECT_TRUE(near(a, b, 1e-9)) << "problem " << k;
    }
}

TEST(PgsLcp, WarmStartFromTheExactSolutionStopsAfterOneSweep) {
    const DenseLcp p = makeRagdollProblem(6);
    LcpExactSolver exact;
    const ExactRun reference = solveExact(exact, p);
    ASSERT_EQ(reference.result.status, LcpStatus::Solved);
    LcpPgsSolver       pgs(LcpPgsSettings{.tolerance = 1e-8});
    std::vector<Real>  x = reference.x;
    const LcpPgsResult r = pgs.solve(p.view(), x);
    EXPECT_EQ(r.status, LcpStatus::Solved);
    EXPECT_EQ(r.iterations, 1);
    EXPECT_TRUE(near(x, reference.x, 1e-6));
}

TEST(PgsLcp, ClampsFrictionToTheNormalValueOfTheSameSweep) {
    // A = I: one sweep gives the normal its value, then each friction row is clamped by it.
    DenseLcp p(3);
    p.a = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    p.b = {2, 5, -5};
    p.lo[0] = 0;
    p.couple(1, 0, 0.5);
    p.couple(2, 0, 0.25);
    LcpPgsSolver       pgs(LcpPgsSettings{.maxIterations = 1});
    std::vector<Real>  x(3, 0);
    const LcpPgsResult r = pgs.solve(p.view(), x);
    EXPECT_EQ(x[0], 2);
    EXPECT_EQ(x[1], 1);     // 0.5 · 2
    EXPECT_EQ(x[2], -0.5);  // −0.25 · 2
    EXPECT_EQ(r.residual, 0);
}

TEST(PgsLcp, ReportsHowFarItGotWhenSweepsRunOut) {
    // The ragdoll's mass ratios make A ill-conditioned: PGS is far from done after 10 sweeps,
    // and closer, not there, after 200. The exact solver's answer is the yardstick.
    const DenseLcp p = makeRagdollProblem(6);
    LcpExactSolver exact;
    const ExactRun reference = solveExact(exact, p);
    Real           previousResidual = kLcpInfinity;
    for (const int sweeps : {10, 200}) {
        LcpPgsSolver       pgs(LcpPgsSettings{.maxIterations = sweeps});
        std::vector<Real>  x(p.n, 0);
        const LcpPgsResult r = pgs.solve(p.view(), x);
        EXPECT_EQ(r.status, LcpStatus::NotConverged);
        EXPECT_EQ(r.iterations, sweeps);
        EXPECT_EQ(r.residual, lcpResidual(p.view(), x));
        EXPECT_GT(r.residual, 1e-6);
        EXPECT_LT(r.residual, previousResidual);
        previousResidual = r.residual;
        RecordProperty("residualAfter" + std::to_string(sweeps), std::to_string(r.residual));
        RecordProperty("errorAfter" + std::to_string(sweeps), std::to_string(maxAbsDifference(x, reference.x)));
    }
}

TEST(PgsLcp, RejectsARelaxationFactorOutsideZeroToTwo) {
    DenseLcp p(1);
    p.a = {1};
    std::vector<Real> x(1, 0);
    EXPECT_EQ(LcpPgsSolver(LcpPgsSettings{.sor = 2}).solve(p.view(), x).status, LcpStatus::InvalidInput);
    EXPECT_EQ(LcpPgsSolver(LcpPgsSettings{.sor = 0}).solve(p.view(), x).status, LcpStatus::InvalidInput);
}

}  // namespace
}  // namespace af
