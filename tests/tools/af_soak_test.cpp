// af-soak run as a user runs it: a short seeded soak passes with its table, a replayed drop gives
// the numbers of its row in the full run, and bad usage is refused.

#include "tool_run.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

using SoakRun = af::test::ToolRun;

// af-soak with its stderr in `out` after its stdout.
SoakRun afSoak(const std::string& arguments) { return af::test::runTool(std::string(AF_SOAK_PATH) + " " + arguments + " 2>&1"); }

std::vector<std::string> linesStartingWith(const std::string& text, const std::string& prefix) {
    std::vector<std::string> found;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) found.push_back(line);
    return found;
}

// The rows of one case: its name fills the first column, 18 characters and a space.
std::vector<std::string> rowsOf(const std::string& text, std::string caseName) {
    caseName.resize(19, ' ');
    return linesStartingWith(text, caseName);
}

// A row without its first column (the case name): seed, figure, bodies, step and the measures.
std::string measures(const std::string& row) { return row.substr(18); }

std::string seedOf(const std::string& row) {
    std::istringstream in(measures(row));
    std::string seed;
    in >> seed;
    return seed;
}

// Short drops, so that the sanitizer run stays quick: seeds 76..86 are piles of up to 14 figures,
// generated chains and the sample figures, broken poses and launches (see --list), 0.7 s in all
// here. No wall budget: a drop stopped by it would not replay to the same row.
constexpr const char* kShortSoak = "--drops 11 --seed 76 --seconds 0.5 --max-wall 0 --list";
constexpr int kShortSoakDrops = 11;
constexpr const char* kShortSoakSeconds = "0.5";

// The drops a step made invalid (Doom's explicit springs, stiffened, at the longest steps explode)
// are caught by the world's guard inside that step: the soak lists them as "put back" and exits
// 1 for them, but nothing non-finite or exploded ever reaches the world it measures.
TEST(AfSoak, ShortSeededSoakPrintsItsWorstCasesAndTotalsAndNoNaNOrExplosionGetsPastTheGuard) {
    const SoakRun run = afSoak(kShortSoak);
    const bool putBack = !rowsOf(run.out, "put back").empty();
    const bool restedOpen = !rowsOf(run.out, "rested open").empty();
    ASSERT_EQ(run.status, putBack || restedOpen ? 1 : 0) << run.out;
    EXPECT_EQ(rowsOf(run.out, "drop").size(), static_cast<std::size_t>(kShortSoakDrops)) << run.out;
    for (const char* row : {"energy ratio", "joint error", "joint error end", "penetration", "penetration end",
                            "slowest rest", "failed solves"})
        EXPECT_EQ(rowsOf(run.out, row).size(), 1u) << row << "\n" << run.out;
    EXPECT_NE(run.out.find("totals: " + std::to_string(kShortSoakDrops) + " drops"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(" 0 NaN/inf, 0 explosions, "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(", 0 threw, 0 refused"), std::string::npos) << run.out;

    // The worst-energy case is the drop whose row has the largest energy ratio.
    const std::string worstSeed = seedOf(rowsOf(run.out, "energy ratio").front());
    double largest = -1;
    std::string largestSeed;
    for (const std::string& row : rowsOf(run.out, "drop")) {
        std::istringstream in(measures(row));
        std::string seed, figure, bodies, step, energy;
        in >> seed >> figure >> bodies >> step >> energy;
        if (std::stod(energy) > largest) largest = std::stod(energy), largestSeed = seed;
    }
    EXPECT_EQ(worstSeed, largestSeed) << run.out;
}

TEST(AfSoak, ReplayingASeedGivesTheNumbersOfItsRowInTheFullRun) {
    const SoakRun run = afSoak(kShortSoak);
    ASSERT_NE(run.status, 2) << run.out;
    for (const char* worstCase : {"energy ratio", "joint error end", "penetration end", "slowest rest"}) {
        const std::string row = rowsOf(run.out, worstCase).front();
        const SoakRun replay = afSoak(std::string("--seconds ") + kShortSoakSeconds + " --max-wall 0 --replay " + seedOf(row));
        ASSERT_NE(replay.status, 2) << replay.out;
        const std::vector<std::string> replayed = rowsOf(replay.out, "replay");
        ASSERT_EQ(replayed.size(), 1u) << replay.out;
        EXPECT_EQ(measures(replayed.front()), measures(row)) << worstCase;
        EXPECT_NE(replay.out.find("time step 1/"), std::string::npos) << "the replay says how the drop was made\n" << replay.out;
    }
}

TEST(AfSoak, TwoJobsGiveTheSameRowsAsOne) {
    const SoakRun one = afSoak("--drops 6 --seed 45 --seconds 0.3 --max-wall 0 --list");
    const SoakRun two = afSoak("--drops 6 --seed 45 --seconds 0.3 --max-wall 0 --list --jobs 2");
    ASSERT_NE(one.status, 2) << one.out;
    ASSERT_EQ(two.status, one.status) << two.out;
    EXPECT_EQ(rowsOf(one.out, "drop"), rowsOf(two.out, "drop"));
}

// CI's soak fails on what must never happen (NaN, explosions, exceptions, refused figures), not on
// drops the guard put back or that rested open: those are findings of hostile starts. Seeds
// 99..101 over 2 s: built with GCC, a lamp at 1/203 s is put back in its second second (which
// drops the guard catches depends on the compiler's rounding: clang's lamp is not put back).
TEST(AfSoak, FailOnChoosesWhichFailuresSetTheExitStatus) {
    const std::string drops = "--drops 3 --seed 99 --seconds 2 --max-wall 0 --list";
    const SoakRun all = afSoak(drops);
    ASSERT_NE(all.status, 2) << all.out;
    const bool putBack = !rowsOf(all.out, "put back").empty();
    const bool restedOpen = !rowsOf(all.out, "rested open").empty();
    EXPECT_EQ(all.status, putBack || restedOpen ? 1 : 0) << all.out;
    const SoakRun putBackOnly = afSoak(drops + " --fail-on put-back");
    EXPECT_EQ(putBackOnly.status, putBack ? 1 : 0) << putBackOnly.out;
    const SoakRun hard = afSoak(drops + " --fail-on nan,explosion,threw,refused");
    EXPECT_EQ(hard.status, 0) << hard.out;
    EXPECT_EQ(rowsOf(hard.out, "drop"), rowsOf(all.out, "drop")) << "--fail-on changed the drops";
}

// Seed 10 launches a chain into the step brushes: in its third step the fixed joint and the
// brush's contacts form a loop whose warm-start impulses (1e10 to 1e12) made the softness hold ask
// its joints to part, and the solve gained 54 times its energy, which the guard put back. The
// solve is now done again with plain targets (docs/solver.md, the step's contact rows).
TEST(AfSoak, AChainLaunchedIntoABrushIsNotPutBack) {
    const SoakRun run = afSoak("--replay 10 --seconds 0.2 --max-wall 0 --fail-on put-back");
    EXPECT_EQ(run.status, 0) << run.out;
    EXPECT_NE(run.out.find("origin inside the step brushes"), std::string::npos) << "seed 10 is no longer that drop\n" << run.out;
}

// Seed 1000 starts a chain of mass ratios up to 1:4430 inside the step brushes in a broken pose:
// in its second step SHAKE moved no point more than 0.017 units and took the kinetic energy from
// 5.1e3 to 5.3e6, a held limit's share of the move cancelling the joints' (docs/solver.md,
// SHAKE). The guard put it back, to rest with a joint 0.69 open. Such a move is now refused: the
// chain gets out of the brush and rests with its joints closed.
TEST(AfSoak, ALopsidedChainStartedInABrushGetsOutAndRestsClosed) {
    const SoakRun run = afSoak("--replay 1000 --seconds 1 --max-wall 0 --fail-on put-back,rested-open");
    EXPECT_EQ(run.status, 0) << run.out;
    EXPECT_NE(run.out.find("origin inside the step brushes"), std::string::npos) << "seed 1000 is no longer that drop\n" << run.out;
    const std::vector<std::string> rows = rowsOf(run.out, "replay");
    ASSERT_EQ(rows.size(), 1u) << run.out;
    std::istringstream in(measures(rows[0]));
    std::string seed, figure, bodies, step, energy, joint, jointEnd, pen, penEnd, rest;
    in >> seed >> figure >> bodies >> step >> energy >> joint >> jointEnd >> pen >> penEnd >> rest;
    EXPECT_LT(std::stod(jointEnd), 1e-9) << run.out;
    EXPECT_NE(rest, "-") << "the chain did not come to rest\n" << run.out;
}

// Seed 7937 starts Doom's lamp inside the step brushes in a broken pose, where no pose outside
// them keeps the spring within its maxLength: the projection cannot finish, and on its way it
// stretched the spring from 13 to 9.0e5 units of energy, which flung the lamp the next step at 15
// times what its start and gravity could supply. An unfinished projection now stores in springs
// at most what lifting its bodies as far would cost (docs/solver.md, the position projection):
// the lamp stays in the brush, stuck, and never moves faster than its fall could make it.
TEST(AfSoak, ALampItsSpringHoldsInsideABrushIsNotFlung) {
    const SoakRun run = afSoak("--replay 7937 --seconds 0.5 --max-wall 0 --fail-on nan,explosion");
    EXPECT_EQ(run.status, 0) << run.out;
    EXPECT_NE(run.out.find("drop 7937: lamp"), std::string::npos) << "seed 7937 is no longer that drop\n" << run.out;
    EXPECT_NE(run.out.find("origin inside the step brushes"), std::string::npos) << run.out;
    const std::vector<std::string> rows = rowsOf(run.out, "replay");
    ASSERT_EQ(rows.size(), 1u) << run.out;
    std::istringstream in(measures(rows[0]));
    std::string seed, figure, bodies, step, energy, joint, jointEnd, pen, penEnd;
    in >> seed >> figure >> bodies >> step >> energy >> joint >> jointEnd >> pen >> penEnd;
    // Which drop a seed makes depends on the compiler's rounding: clang's lamp of this seed starts
    // elsewhere in the brushes, gets out and falls (no explosion: the status above). The bound is
    // for the lamp that stays in the brush, which its spring would otherwise fling.
    if (std::stod(penEnd) > 1) {
        EXPECT_LT(std::stod(energy), 1.0) << "more kinetic energy than the start and gravity supplied\n" << run.out;
    }
}

// Seed 639 drops four humanoids inside each other at 1/29 s: one of them, 591 rows with its
// contacts, has those relaxed by sweeps on the tree's Schur complement (docs/solver.md, islands of
// many figures), warm-started. From impulses of a hostile step the sweeps ended with 4.4e9 of
// kinetic energy from 1.0e5, plain targets or not, and the guard put the figures back. A re-solve with plain targets now starts cold, from no impulse: sweeps
// that only lower the kinetic energy then cannot gain it.
TEST(AfSoak, HumanoidsDroppedInsideEachOtherAreNotPutBack) {
    const SoakRun run = afSoak("--replay 639 --seconds 0.3 --max-wall 0 --fail-on put-back");
    EXPECT_EQ(run.status, 0) << run.out;
    EXPECT_NE(run.out.find("humanoid*4"), std::string::npos) << "seed 639 is no longer that drop\n" << run.out;
}

TEST(AfSoak, BadUsageExitsTwoWithAMessage) {
    for (const char* arguments : {"--drops 0", "--no-such-option", "--seconds -1", "--jobs 0", "--max-wall -1", "--map /no/such.map",
                                  "--fail-on nothing"}) {
        const SoakRun run = afSoak(arguments);
        EXPECT_EQ(run.status, 2) << arguments << "\n" << run.out;
        EXPECT_NE(run.out.find("af-soak"), std::string::npos) << arguments << "\n" << run.out;
    }
}

}  // namespace
