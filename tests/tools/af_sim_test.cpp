// af-sim run as a user runs it: the summary, its JSON keys, pictures, the baked animation, and
// clear failures on bad input.

#include "af/text/md5.h"

#include "text/map_text.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using SimRun = af::test::ToolRun;

// af-sim with its stderr in `out` after its stdout.
SimRun afSim(const std::string& arguments) { return af::test::runTool(std::string(AF_SIM_PATH) + " " + arguments + " 2>&1"); }

std::filesystem::path scratch(const std::string& name) { return af::test::scratchDir() / name; }

// A fresh mod folder in the scratch directory, with an empty af/ for an edited figure.
std::filesystem::path emptyMod(const std::string& name) {
    const std::filesystem::path mod = scratch(name);
    std::filesystem::remove_all(mod);
    std::filesystem::create_directories(mod / "af");
    return mod;
}

// The source tree's humanoid.af, to edit.
std::string sourceHumanoid() {
    std::ifstream original(std::string(AF_SOURCE_DIR) + "/af/humanoid.af");
    std::stringstream text;
    text << original.rdbuf();
    return text.str();
}

TEST(AfSim, DefaultRunDropsTheHumanoidOntoTheDefaultMapAndItRestsWithinFiveSeconds) {
    const SimRun run = afSim("--json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    for (const char* key : {"rest_time_s", "steps", "wall_s", "us_per_step", "max_joint_error", "max_penetration",
                            "max_limit_violation_deg", "final_kinetic_energy", "solver_failures", "invalid_motion", "bodies"})
        EXPECT_TRUE(j.contains(key)) << key;
    ASSERT_TRUE(j["rest_time_s"].is_number()) << "the humanoid never came to rest";
    EXPECT_LT(j["rest_time_s"].get<double>(), 5.0);
    EXPECT_TRUE(j["invalid_motion"].empty());
    EXPECT_EQ(j["final_kinetic_energy"].get<double>(), 0.0) << "a resting figure has no velocity";
    // One velocity solve of this landing (step 40: 181 rows, the coupled friction problem) defeats
    // the pivoting solvers and is answered by the counted frozen-box fallback (docs/solver.md,
    // "When a pivoting velocity solve fails"); the same drop built with other rounding of its spawn
    // vectors (1 ulp) had none. Pushes over 41 seeds have none: see the test after this one.
    EXPECT_LE(j["solver_failures"].get<int>(), 1);
    // Measured: joints 1.2e-10 units, limits 1.0e-9°, contacts end at the slop (0.05 units); the
    // settle projection leaves at most 2 % of the slop beyond it.
    EXPECT_LT(j["max_joint_error"].get<double>(), 1e-9);
    EXPECT_LT(j["max_limit_violation_deg"].get<double>(), 1e-7);
    EXPECT_LT(j["max_penetration"].get<double>(), 0.05 * 1.02);
    ASSERT_EQ(j["bodies"].size(), 16u);
    double mass = 0;
    for (const auto& b : j["bodies"]) {
        mass += b["mass"].get<double>();
        EXPECT_GT(b["position"][2].get<double>(), -1.0) << b["name"] << " ended below the floor";
        EXPECT_LT(b["position"][2].get<double>(), 40.0) << b["name"] << " did not come down";
    }
    EXPECT_NEAR(mass, 150, 1e-6) << "humanoid.af's totalMass";
}

// bench/seeds.sh 0 40 as a test: 41 pushed drops, 3368 steps, no failed solve, joints within
// 1.46e-10 units at worst (seed 15's landing opened them by 4.9 units before the fifth halving of
// the projection, island_project.cpp), every drop at rest.
TEST(AfSim, FortyOnePushedDropsFailNoSolveAndKeepTheirJointsClosed) {
    int failures = 0;
    double worstJoint = 0;
    for (int seed = 0; seed <= 40; ++seed) {
        const SimRun run = afSim("--seed " + std::to_string(seed) + " --json");
        ASSERT_EQ(run.status, 0) << "seed " << seed << ": " << run.out;
        const nlohmann::json j = nlohmann::json::parse(run.out);
        EXPECT_TRUE(j["rest_time_s"].is_number()) << "seed " << seed;
        failures += j["solver_failures"].get<int>();
        worstJoint = std::max(worstJoint, j["max_joint_error"].get<double>());
    }
    EXPECT_EQ(failures, 0);
    EXPECT_LT(worstJoint, 3e-10);
}

TEST(AfSim, PicturesAndTheBakedAnimationAreWrittenAndTheAnimationReadsBack) {
    const std::filesystem::path png = scratch("final.png"), plot = scratch("plot.png"), anim = scratch("fall.md5anim"),
                                lines = scratch("trajectory.jsonl");
    for (const auto& p : {png, plot, anim, lines}) std::filesystem::remove(p);
    const SimRun run = afSim("--no-map --seconds 2 --png " + png.string() + " --plot " + plot.string() + " --md5anim " +
                          anim.string() + " --trajectory " + lines.string() + " --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_GT(std::filesystem::file_size(png), 10000u);
    EXPECT_GT(std::filesystem::file_size(plot), 5000u);

    std::ifstream file(anim);
    std::stringstream text;
    text << file.rdbuf();
    const af::Md5AnimParseResult parsed = af::parseMd5Anim(text.str(), anim.string());
    ASSERT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    EXPECT_EQ(parsed.anim.frameCount, j["steps"].get<int>()) << "one frame per step";
    EXPECT_EQ(parsed.anim.frameRate, 60);
    ASSERT_EQ(parsed.anim.joints.size(), 25u);
    EXPECT_EQ(parsed.anim.joints[0].name, "origin");
    EXPECT_EQ(parsed.anim.joints[1].name, "pelvis");

    std::ifstream trajectory(lines);
    int count = 0;
    for (std::string line; std::getline(trajectory, line); ++count)
        EXPECT_EQ(nlohmann::json::parse(line)["bodies"].size(), 16u);
    EXPECT_EQ(count, j["steps"].get<int>());
}

TEST(AfSim, TwoRunsWithTheSameSeedGiveTheSameSummary) {
    const SimRun a = afSim("--no-map --seconds 1 --seed 7 --json");
    const SimRun b = afSim("--no-map --seconds 1 --seed 7 --json");
    ASSERT_EQ(a.status, 0) << a.out;
    nlohmann::json ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
    EXPECT_EQ(ja["bodies"], jb["bodies"]);
    const SimRun c = afSim("--no-map --seconds 1 --seed 8 --json");
    EXPECT_NE(ja["bodies"], nlohmann::json::parse(c.out)["bodies"]) << "the seed must change the push";
}

// Landing is chaotic and the coupled friction problem need not have one answer, so the solvers'
// runs are not compared pose by pose (tests/dynamics compares them without contacts); each run
// must hold its joints and come to rest. Measured (rest, worst joint error, deepest contact,
// worst limit overshoot): tree 1.68 s, 1.2e-10, 0.050, 1.0e-9 deg (and the one failure of the
// default run's test); exact 1.38 s, 8.5e-11, 0.050,
// 4.5e-9 deg; PGS (velocities only: the projection closes the joints to positionTolerance, 1e-10)
// 1.33 s, 7.6e-11, 0.050, 1.2e-9 deg. The contact slop is 0.05.
TEST(AfSim, TreeExactAndPgsRunsHoldTheirJointsAndComeToRest) {
    for (const char* solver : {"tree", "exact", "pgs"}) {
        const SimRun run = afSim(std::string("--solver ") + solver + " --json");
        ASSERT_EQ(run.status, 0) << solver << ": " << run.out;
        const nlohmann::json j = nlohmann::json::parse(run.out);
        ASSERT_TRUE(j["rest_time_s"].is_number()) << solver;
        EXPECT_LT(j["rest_time_s"].get<double>(), 2.5) << solver;
        EXPECT_LT(j["max_joint_error"].get<double>(), 5e-10) << solver;
        EXPECT_LT(j["max_penetration"].get<double>(), 0.1) << solver;
        EXPECT_LT(j["max_limit_violation_deg"].get<double>(), 5e-8) << solver;
        EXPECT_EQ(j["final_kinetic_energy"].get<double>(), 0.0) << solver;
        EXPECT_LE(j["solver_failures"].get<int>(), std::string(solver) == "tree" ? 1 : 0) << solver;
        EXPECT_TRUE(j["invalid_motion"].empty()) << solver;
    }
}

// Seed 15 lands with a forearm turning 85 rad/s: SHAKE is refused in the landing step and the
// projection starts from 4.4 units of drift. With 4 halvings a pass found no move lowering the
// largest violation and the projection gave up, the joints 4.92 units open (limits 65 deg past)
// for that step. Measured with 5 halvings: tree 6.5e-11 units and 3.7e-9 deg, exact 6.1e-11 and
// 3.2e-9 deg, no failed solve.
TEST(AfSim, TheHumanoidPushedBySeedFifteenKeepsItsJointsClosedThroughTheLanding) {
    for (const char* solver : {"tree", "exact"}) {
        const SimRun run = afSim(std::string("--seed 15 --solver ") + solver + " --json");
        ASSERT_EQ(run.status, 0) << solver << ": " << run.out;
        const nlohmann::json j = nlohmann::json::parse(run.out);
        ASSERT_TRUE(j["rest_time_s"].is_number()) << solver;
        EXPECT_LT(j["max_joint_error"].get<double>(), 2e-10) << solver;
        EXPECT_LT(j["max_limit_violation_deg"].get<double>(), 2e-8) << solver;
        EXPECT_EQ(j["solver_failures"].get<int>(), 0) << solver;
    }
}

TEST(AfSim, BadInputGetsAClearMessageAndANonzeroStatus) {
    const SimRun entity = afSim("--entity no_such_entity");
    EXPECT_NE(entity.status, 0);
    EXPECT_NE(entity.out.find("no_such_entity"), std::string::npos) << entity.out;

    const std::filesystem::path broken = scratch("broken.map");
    std::ofstream(broken) << "Version 2\n{\n\"classname\" \"worldspawn\"\n{\n brushDef3\n {\n  ( 0 0 1 0 ) ( ( 1 0 0 ) ( 0 1 0 ) ) \"m\" 0 0 0\n";
    const SimRun map = afSim("--map " + broken.string());
    EXPECT_NE(map.status, 0);
    EXPECT_NE(map.out.find("broken.map:"), std::string::npos) << map.out;

    const SimRun count = afSim("--count 0");
    EXPECT_NE(count.status, 0);
}

// Exit status 2 means "bad usage or bad input" whatever part of af-sim found it: a script tells a
// mistake in its own command line from a simulation that blew up (1) by the status alone.
TEST(AfSim, BadOptionsExitWithStatusTwoAndSayWhatIsWrong) {
    struct Case {
        const char* arguments;
        const char* mentioned;
    };
    for (const Case& c : {Case{"--no-such-option", "--no-such-option"}, Case{"--count 0", "--count"},
                          Case{"--count many", "--count"}, Case{"--solver fast", "fast"},
                          Case{"--seconds -1", "--seconds"}, Case{"--entity ragdoll_humanoid --figure humanoid", "--figure"},
                          Case{"--no-map --map maps/default.map", "--no-map"}, Case{"--png", "--png"}}) {
        const SimRun run = afSim(c.arguments);
        EXPECT_EQ(run.status, 2) << c.arguments << "\n" << run.out;
        EXPECT_NE(run.out.find(c.mentioned), std::string::npos) << c.arguments << "\n" << run.out;
        EXPECT_EQ(run.out.find("at rest"), std::string::npos) << c.arguments << ": nothing may run";
    }
    const SimRun unknown = afSim("--entity no_such_entity");
    EXPECT_EQ(unknown.status, 2) << unknown.out;
}

TEST(AfSim, HelpListsTheOptionsAndExitsWithStatusZero) {
    const SimRun run = afSim("--help");
    EXPECT_EQ(run.status, 0) << run.out;
    for (const char* option : {"--entity", "--figure", "--root", "--map", "--no-map", "--count", "--seconds", "--solver",
                               "--seed", "--json", "--png", "--frames", "--plot", "--trajectory", "--md5anim"})
        EXPECT_NE(run.out.find(option), std::string::npos) << option;
}

TEST(AfSim, CountDropsThatManyFiguresAndEachIsNamedByItsFigure) {
    const SimRun run = afSim("--no-map --count 3 --seconds 0.5 --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    ASSERT_EQ(j["bodies"].size(), 48u);
    std::array<int, 3> perFigure{};
    for (const auto& b : j["bodies"]) {
        const int figure = b["figure"].get<int>();
        ASSERT_GE(figure, 0);
        ASSERT_LT(figure, 3);
        ++perFigure[static_cast<std::size_t>(figure)];
    }
    EXPECT_EQ(perFigure, (std::array<int, 3>{16, 16, 16}));
    EXPECT_TRUE(j["invalid_motion"].empty());
    EXPECT_LT(j["max_joint_error"].get<double>(), 1e-3);
}

TEST(AfSim, FigureSpawnsABareDeclOnTheModelItsSettingsName) {
    const SimRun run = afSim("--figure chain --no-map --seconds 0.25 --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_NE(j["scene"].get<std::string>().find("chain"), std::string::npos) << j["scene"];
    std::ifstream decl(std::string(AF_SOURCE_DIR) + "/af/chain.af");
    std::stringstream text;
    text << decl.rdbuf();
    std::size_t bodies = 0;
    for (std::size_t at = text.str().find("\nbody "); at != std::string::npos; at = text.str().find("\nbody ", at + 1))
        ++bodies;
    ASSERT_GT(bodies, 1u);
    EXPECT_EQ(j["bodies"].size(), bodies) << "one body per body block of af/chain.af";
}

// A later --root replaces an earlier root's file of the same path, as Doom's search paths do.
TEST(AfSim, ALaterRootReplacesTheFigureOfAnEarlierOne) {
    const std::filesystem::path mod = emptyMod("mod");
    std::string edited = sourceHumanoid();
    const std::size_t at = edited.find("totalMass");
    ASSERT_NE(at, std::string::npos);
    const std::size_t end = edited.find('\n', at);
    edited.replace(at, end - at, "totalMass 75");
    std::ofstream(mod / "af/humanoid.af") << edited;

    const std::string source = std::string(AF_SOURCE_DIR);
    const SimRun run = afSim("--root " + source + " --root " + mod.string() + " --no-map --seconds 0.1 --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    double mass = 0;
    for (const auto& b : j["bodies"]) mass += b["mass"].get<double>();
    EXPECT_NEAR(mass, 75, 1e-6) << "the mod's humanoid.af, not the source tree's (150)";

    const SimRun alone = afSim("--root " + mod.string() + " --no-map --seconds 0.1");
    EXPECT_EQ(alone.status, 2) << "the mod alone has no entityDef\n" << alone.out;
    EXPECT_NE(alone.out.find("ragdoll_humanoid"), std::string::npos) << alone.out;
}

// Hands a thousand times denser than ours (0.3 -> 300, 1:200 against the forearms): the light
// torso whips between them, and on the ground SHAKE once took the figure's kinetic energy from
// 1.7e4 to 2.2e5, which the guard put back. Now it lands and rests without invalid motion
// (measured: at rest after 1.82 s, joints open up to 9.3 units in the fall, closed at rest).
TEST(AfSim, AHumanoidWithHandsAThousandTimesDenserLandsAndRestsWithoutInvalidMotion) {
    const std::filesystem::path mod = emptyMod("heavy-hands");
    std::string edited = sourceHumanoid();
    for (const char* hand : {"body \"lhand\"", "body \"rhand\""}) {
        const std::size_t body = edited.find(hand);
        ASSERT_NE(body, std::string::npos) << hand;
        const std::size_t at = edited.find("density", body);
        edited.replace(at, edited.find('\n', at) - at, "density 300");
    }
    std::ofstream(mod / "af/humanoid.af") << edited;

    const SimRun run = afSim("--root " + std::string(AF_SOURCE_DIR) + " --root " + mod.string() + " --seconds 20 --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_TRUE(j["invalid_motion"].empty()) << run.out;
    ASSERT_TRUE(j["rest_time_s"].is_number()) << "it never came to rest";
    EXPECT_LT(j["rest_time_s"].get<double>(), 3.0);
}

// A wall beside (0, 0), where the figure is dropped: the ground under the drop point is the floor,
// but the leaning figure reaches into the wall. It is lifted until no body is inside a brush, so
// it starts whole and lands with its joints closed (started inside, the projection would push
// the bodies out of the wall one by one and open the joints by units).
TEST(AfSim, AFigureThatWouldStartInsideABrushIsLiftedClearOfIt) {
    const std::filesystem::path map = scratch("wall.map");
    std::ofstream(map) << af::test::floorBesideWallMap();
    const SimRun run = afSim("--map " + map.string() + " --seconds 4 --json");
    ASSERT_EQ(run.status, 0) << run.out;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    // Dropped at (0, 0) the tilted humanoid would lean 12.2 units into the wall (x > -2).
    EXPECT_GT(j["lifted"].get<double>(), 12) << "not lifted clear of the wall";
    EXPECT_LT(j["max_joint_error"].get<double>(), 1e-6);
    EXPECT_LT(j["max_penetration"].get<double>(), 0.5);
}

TEST(AfSim, FramesWritesAContactSheetOfTheFall) {
    const std::filesystem::path sheet = scratch("frames.png");
    std::filesystem::remove(sheet);
    const SimRun run = afSim("--no-map --seconds 1 --frames " + sheet.string());
    ASSERT_EQ(run.status, 0) << run.out;
    ASSERT_TRUE(std::filesystem::exists(sheet));
    std::ifstream png(sheet, std::ios::binary);
    std::array<char, 8> signature{};
    png.read(signature.data(), signature.size());
    EXPECT_EQ(std::string(signature.data(), 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_GT(std::filesystem::file_size(sheet), 20000u) << "twelve poses drawn";
    EXPECT_NE(run.out.find("frames: " + sheet.string()), std::string::npos) << run.out;
}

}  // namespace
