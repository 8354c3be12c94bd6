// The exact solver on coupled LCPs captured from whole simulations, where a warm start led its
// passes somewhere a random test problem had not.

#include "lcp_test_util.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace af {
namespace {

using namespace test;

struct CapturedLcp {
    DenseLcp                 problem;
    std::vector<LcpRowState> guess;
};

// Reads the layout described in the file's header (strtod: the numbers are C99 hex floats).
CapturedLcp readCaptured(const std::string& path) {
    std::ifstream in(path);
    std::string   line;
    auto next = [&]() -> std::istringstream {
        while (std::getline(in, line) && line.starts_with('#')) {
        }
        return std::istringstream(line);
    };
    auto reals = [&](std::vector<Real>& into, std::size_t offset = 0) {
        std::istringstream row = next();
        std::string        token;
        for (std::size_t k = offset; row >> token; ++k) into.at(k) = std::strtod(token.c_str(), nullptr);
    };
    int n = 0;
    next() >> n;
    CapturedLcp c{DenseLcp(n), std::vector<LcpRowState>(static_cast<std::size_t>(n))};
    DenseLcp&   p = c.problem;
    std::vector<Real> upper(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        reals(upper, static_cast<std::size_t>(i));
        for (int j = i; j < n; ++j) p.at(i, j) = p.at(j, i) = upper[static_cast<std::size_t>(j)];
    }
    reals(p.b);
    reals(p.lo);
    reals(p.hi);
    p.cfm.assign(static_cast<std::size_t>(n), 0);
    reals(p.cfm);
    p.findex.assign(static_cast<std::size_t>(n), -1);
    std::istringstream findex = next();
    for (int& f : p.findex) findex >> f;
    p.mu.assign(static_cast<std::size_t>(n), 0);
    reals(p.mu);
    std::istringstream states = next();
    for (LcpRowState& s : c.guess) {
        int v = 0;
        states >> v;
        s = static_cast<LcpRowState>(v);
    }
    return c;
}

// af-sim --seed 34: from the island's guess (a step old, 58 rows of it wrong) the coupled passes
// released one friction row (170, of normal 168) and then it and a joint friction row (26) in
// turn, pass after pass, and the frozen-box passes diverged on the pattern they had settled on.
// A complementary solution exists: a cold start finds it in 24 pivots.
TEST(ExactLcpCaptured, SolvesTheHumanoidLandingItsWarmStartCycledOn) {
    const CapturedLcp c = readCaptured(AF_TEST_DIR "/dynamics/data/seed34_velocity_lcp.txt");
    ASSERT_EQ(c.problem.n, 183);
    ASSERT_TRUE(lcpValidate(c.problem.view()));
    LcpExactSolver solver(LcpExactSettings{.frictionBoxPasses = 32});  // World's settings
    const ExactRun run = solveExact(solver, c.problem, c.guess);
    EXPECT_EQ(run.result.status, LcpStatus::Solved);
    EXPECT_TRUE(run.result.failedRows.empty());
    EXPECT_LT(run.result.residual, 1e-11);
    // Impulses up to 4e3: complementary to rounding, by the independent measure too.
    EXPECT_TRUE(isSolution(c.problem, run.x, 1e-9));
}

}  // namespace
}  // namespace af
