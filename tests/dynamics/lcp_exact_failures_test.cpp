// The exact LCP solver on degenerate and broken input: redundant rows with and without CFM,
// rows no x can satisfy, the pivot and pass caps, malformed problems, and the promise that a
// solve allocates nothing once the workspace is reserved.

#include "allocation_counter.h"
#include "lcp_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace af {
namespace {

using namespace test;

// Two bodies, a ball joint written twice (6 rows, rank 3) and a contact with friction.
DenseLcp redundantJointProblem(Real cfm) {
    Rng  rng(3);
    MatX j = MatX::Zero(9, 12);
    for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 12; ++c) {
            j(k, c) = rng.uniform(-1, 1);
        }
        j.row(3 + k) = j.row(k);  // the same joint row again
    }
    for (int r = 6; r < 9; ++r) {
        for (int c = 0; c < 6; ++c) {
            j(r, c) = rng.uniform(-1, 1);
        }
    }
    DenseLcp p(9);
    setMatrix(p, j * j.transpose());
    for (int r = 0; r < 9; ++r) {
        p.b[r] = rng.uniform(-1, 1);
    }
    for (int k = 0; k < 3; ++k) {
        p.b[3 + k] = p.b[k];  // consistent: the copies ask for the same velocity
    }
    p.lo[6] = 0;
    p.b[6] = 1;
    p.couple(7, 6, 0.8);
    p.couple(8, 6, 0.8);
    if (cfm > 0) {
        p.cfm.assign(9, cfm);
    }
    return p;
}

TEST(ExactLcpDegenerate, SolvesRedundantJointRowsWithCfm) {
    const DenseLcp         p = redundantJointProblem(1e-6);
    const BruteForceResult bf = bruteForce(p);
    ASSERT_EQ(bf.solutions.size(), 1u);
    LcpExactSolver solver;
    const ExactRun run = solveExact(solver, p);
    ASSERT_EQ(run.result.status, LcpStatus::Solved);
    EXPECT_TRUE(run.result.failedRows.empty());
    EXPECT_TRUE(isSolution(p, run.x, 1e-9));
    EXPECT_TRUE(near(run.x, bf.solutions[0], 1e-7));  // the CFM makes the split of the load unique but stiff
    // CFM shares the load between the two copies equally.
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(run.x[k], run.x[3 + k], 1e-6);
    }
}

TEST(ExactLcpDegenerate, SettingsCfmActsLikePerRowCfm) {
    const DenseLcp withRows = redundantJointProblem(1e-6);
    const DenseLcp bare = redundantJointProblem(0);
    LcpExactSolver perRow;
    LcpExactSolver global(LcpExactSettings{.cfm = 1e-6});
    const ExactRun a = solveExact(perRow, withRows);
    const ExactRun b = solveExact(global, bare);
    ASSERT_EQ(b.result.status, LcpStatus::Solved);
    EXPECT_TRUE(isSolution(bare, b.x, 1e-9, 1e-6));
    EXPECT_TRUE(near(a.x, b.x, 1e-9));
}

TEST(ExactLcpDegenerate, HoldsConsistentRedundantRowsWithoutCfm) {
    // Without CFM the copy cannot be factorised; it is consistent, so it is held at its start
    // value with w = 0 and the solve still succeeds.
    const DenseLcp p = redundantJointProblem(0);
    LcpExactSolver solver;
    const ExactRun run = solveExact(solver, p);
    ASSERT_EQ(run.result.status, LcpStatus::Solved);
    EXPECT_TRUE(isSolution(p, run.x, 1e-9));
    for (int r = 0; r < 6; ++r) {
        EXPECT_EQ(run.states[r], LcpRowState::Free) << r;
    }
}

TEST(ExactLcpDegenerate, ReportsInconsistentRedundantRowsInsteadOfHidingThem) {
    // x0 + x1 = 1 and x0 + x1 = 2: no x satisfies both equality rows.
    DenseLcp p(2);
    p.a = {1, 1, 1, 1};
    p.b = {1, 2};
    LcpExactSolver solver;
    const ExactRun run = solveExact(solver, p);
    EXPECT_EQ(run.result.status, LcpStatus::Unsatisfiable);
    ASSERT_EQ(run.result.failedRows.size(), 1u);
    EXPECT_EQ(run.states[run.result.failedRows[0]], LcpRowState::Failed);
    EXPECT_TRUE(std::isfinite(run.x[0]) && std::isfinite(run.x[1]));
    EXPECT_GT(run.result.residual, 0.1);
}

TEST(ExactLcpDegenerate, StopsAtThePivotCapAndListsTheRowsLeft) {
    const DenseLcp p = makeRagdollProblem(1);  // needs about 30 pivots from cold
    LcpExactSolver solver(LcpExactSettings{.maxPivots = 5});
    const ExactRun run = solveExact(solver, p);
    EXPECT_EQ(run.result.status, LcpStatus::PivotLimit);
    EXPECT_EQ(run.result.pivots, 5);
    ASSERT_FALSE(run.result.failedRows.empty());
    for (const int row : run.result.failedRows) {
        EXPECT_EQ(run.states[row], LcpRowState::Failed) << row;
    }
    for (const Real v : run.x) {
        EXPECT_TRUE(std::isfinite(v));
    }
}

TEST(ExactLcpDegenerate, ReportsFrictionThatDidNotSettleWithinThePassCap) {
    // This ragdoll step needs several passes to settle its sliding contacts; allow only one.
    const DenseLcp p = makeRagdollProblem(2);
    LcpExactSolver solver(LcpExactSettings{.maxCouplingPasses = 1});
    const ExactRun run = solveExact(solver, p);
    EXPECT_EQ(run.result.status, LcpStatus::NotConverged);
    EXPECT_EQ(run.result.couplingPasses, 1);
    EXPECT_FALSE(run.result.failedRows.empty());
}

TEST(ExactLcpDegenerate, RejectsMalformedProblems) {
    LcpExactSolver solver;
    auto           status = [&](const DenseLcp& p) { return solveExact(solver, p).result.status; };
    DenseLcp       good(3);
    good.a = {2, 0, 0, 0, 2, 0, 0, 0, 2};
    ASSERT_EQ(status(good), LcpStatus::Solved);

    DenseLcp p = good;
    p.lo[1] = 1;
    p.hi[1] = 0;
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "lo > hi";
    p = good;
    p.couple(1, 1, 0.5);
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "row coupled to itself";
    p = good;
    p.couple(1, 0, 0.5);
    p.couple(2, 1, 0.5);
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "coupled to a coupled row";
    p = good;
    p.couple(1, 0, -0.5);
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "negative mu";
    p = good;
    p.b[0] = std::nan("");
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "NaN in b";
    p = good;
    p.cfm = {0, -1, 0};
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "negative cfm";
    p = good;
    p.a[4] = -1;
    EXPECT_EQ(status(p), LcpStatus::InvalidInput) << "negative diagonal";

    std::vector<Real> shortX(2);
    EXPECT_EQ(solver.solve(good.view(), shortX).status, LcpStatus::InvalidInput) << "x too short";
    const char* message = nullptr;
    p = good;
    p.lo[0] = kLcpInfinity;
    EXPECT_FALSE(lcpValidate(p.view(), &message));
    EXPECT_NE(message, nullptr);
}

TEST(ExactLcpDegenerate, AllocatesNothingInsideASolveAfterReserve) {
    const DenseLcp cold = makeRagdollProblem(4);
    const DenseLcp next = makeRagdollProblem(4, 0.01);
    LcpExactSolver solver;
    LcpPgsSolver   pgs;
    solver.reserve(cold.n);
    pgs.reserve(cold.n);
    std::vector<Real>        x(cold.n, 0);
    std::vector<LcpRowState> states(cold.n, LcpRowState::Unknown);
    const LcpProblem         coldView = cold.view();
    const LcpProblem         nextView = next.view();

    const long before = test::gAllocations.load();
    const LcpResult first = solver.solve(coldView, x, states);
    const LcpResult second = solver.solve(nextView, x, states);
    const LcpPgsResult third = pgs.solve(nextView, x);
    const long after = test::gAllocations.load();
    EXPECT_EQ(first.status, LcpStatus::Solved);
    EXPECT_EQ(second.status, LcpStatus::Solved);
    EXPECT_NE(third.status, LcpStatus::InvalidInput);
    EXPECT_EQ(after - before, 0);
}

}  // namespace
}  // namespace af
