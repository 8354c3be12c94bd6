// af-check as a user runs it: exit status, what goes to stdout and stderr, --format and --json.

#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using af::test::readAll;
using af::test::ToolRun;

// Runs af-check from the source tree, so paths in its output are the ones written here.
ToolRun afCheck(const std::string& args) {
    return af::test::runTool(std::string("cd ") + AF_SOURCE_DIR + " && " + AF_CHECK_PATH + " " + args);
}

TEST(AfCheck, SampleFiguresLoadWithExitZero) {
    const ToolRun r = afCheck("af/humanoid.af af/chain.af af/lamp.af");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("af/humanoid.af: ok, humanoid ("), std::string::npos) << r.out;
}

TEST(AfCheck, AnErrorGivesExitOneAndPositionedDiagnostics) {
    const ToolRun r = afCheck("af/chain.af tests/golden/bad_syntax.af");
    EXPECT_EQ(r.status, 1);
    // The golden diagnostics, with the path af-check was given.
    std::string expected;
    std::istringstream golden(readAll(std::string(AF_SOURCE_DIR) + "/tests/golden/bad_syntax.diag"));
    for (std::string line; std::getline(golden, line);) expected += "tests/golden/" + line + "\n";
    EXPECT_EQ(r.err, expected);
    EXPECT_NE(r.out.find("tests/golden/bad_syntax.af: FAILED"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("af/chain.af: ok"), std::string::npos) << r.out;
}

// --strict is a lint: a file Doom 3 loads only with warnings (here later games' names) fails.
TEST(AfCheck, StrictMakesEveryWarningAnError) {
    const ToolRun plain = afCheck("tests/golden/family_contents_names.af");
    EXPECT_EQ(plain.status, 0) << plain.err;
    EXPECT_NE(plain.err.find(":5:20: warning: unknown contents name 'movableclip'"), std::string::npos) << plain.err;
    EXPECT_NE(plain.out.find("family_contents_names.af: ok"), std::string::npos) << plain.out;

    const ToolRun strict = afCheck("--strict tests/golden/family_contents_names.af af/chain.af");
    EXPECT_EQ(strict.status, 1);
    EXPECT_NE(strict.err.find(":5:20: error: unknown contents name 'movableclip'"), std::string::npos) << strict.err;
    EXPECT_EQ(strict.err.find("warning:"), std::string::npos) << strict.err;
    EXPECT_NE(strict.out.find("family_contents_names.af: FAILED"), std::string::npos) << strict.out;
    EXPECT_NE(strict.out.find("af/chain.af: ok"), std::string::npos) << strict.out;
    EXPECT_EQ(afCheck("--strict --format tests/golden/family_contents_names.af").out, "");
}

TEST(AfCheck, MissingFileIsAnErrorNotACrash) {
    const ToolRun r = afCheck("no/such/file.af");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "no/such/file.af: error: cannot open the file for reading\n");
}

TEST(AfCheck, BadUsageGivesExitTwo) {
    EXPECT_EQ(afCheck("").status, 2);
    EXPECT_EQ(afCheck("--no-such-option af/chain.af").status, 2);
    EXPECT_EQ(afCheck("--format --json af/chain.af").status, 2);
}

TEST(AfCheck, FormatPrintsTheCanonicalText) {
    const ToolRun r = afCheck("--format tests/golden/every_keyword.af");
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, readAll(std::string(AF_SOURCE_DIR) + "/tests/golden/every_keyword.out"));
}

TEST(AfCheck, FormatOfAFileWithErrorsPrintsNothing) {
    const ToolRun r = afCheck("--format tests/golden/bad_semantics.af");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(r.err.empty());
}

TEST(AfCheck, JsonHasOneRecordPerFileWithTheFullData) {
    const ToolRun r = afCheck("--json af/lamp.af tests/golden/bad_semantics.af");
    EXPECT_EQ(r.status, 1);
    std::istringstream lines(r.out);
    std::string first, second, third;
    std::getline(lines, first);
    std::getline(lines, second);
    EXPECT_FALSE(std::getline(lines, third));

    const auto lamp = nlohmann::json::parse(first);
    EXPECT_EQ(lamp["file"], "af/lamp.af");
    EXPECT_EQ(lamp["ok"], true);
    ASSERT_EQ(lamp["decls"].size(), 1u);
    EXPECT_EQ(lamp["decls"][0]["name"], "lamp");
    EXPECT_FALSE(lamp["decls"][0]["bodies"].empty());
    EXPECT_EQ(lamp["decls"][0]["bodies"][0]["joint"], "origin");
    EXPECT_TRUE(lamp["diagnostics"].empty());

    const auto bad = nlohmann::json::parse(second);
    EXPECT_EQ(bad["ok"], false);
    ASSERT_FALSE(bad["diagnostics"].empty());
    const auto& d = bad["diagnostics"][0];
    EXPECT_EQ(d["line"], 5);
    EXPECT_EQ(d["col"], 11);
    EXPECT_EQ(d["severity"], "error");
    EXPECT_EQ(d["message"], "density must be greater than 0, found -1 (a body without mass cannot be simulated)");
}

// Contents and clipMask names of later games are kept for the writer, so the data shows them too,
// after the names Doom 3 knows, as the writer puts them.
TEST(AfCheck, JsonListsContentsNamesOfLaterGames) {
    const ToolRun r = afCheck("--json tests/golden/family_contents_names.af");
    EXPECT_EQ(r.status, 0) << r.err;
    const auto decl = nlohmann::json::parse(r.out)["decls"][0];
    EXPECT_EQ(decl["settings"]["contents"], nlohmann::json::array({"corpse", "movableclip"}));
    EXPECT_EQ(decl["settings"]["clipMask"], nlohmann::json::array({"solid", "monsterclip", "flyerhiveclip"}));
    // Doom 3's moveableclip, which every body's clipMask has, is not Quake 4's movableclip.
    EXPECT_EQ(decl["bodies"][0]["clipMask"], nlohmann::json::array({"moveableclip", "movableclip"}));
    EXPECT_EQ(decl["bodies"][1]["contents"], nlohmann::json::array({"body", "FlyerHiveClip"}));
}

// A hand-written file and its canonical form mean the same, so their data must be equal.
TEST(AfCheck, SameMeaningGivesSameJson) {
    const auto a = nlohmann::json::parse(afCheck("--json tests/golden/every_keyword.af").out);
    const auto b = nlohmann::json::parse(afCheck("--json tests/golden/every_keyword.out").out);
    EXPECT_EQ(a["decls"], b["decls"]);
    EXPECT_EQ(a["decls"][0]["settings"]["friction"]["linear"], 0.02);
    EXPECT_EQ(a["decls"][0]["bodies"][0]["origin"]["kind"], "joint");
}

}  // namespace

namespace {

TEST(AfCheckFigure, HumanoidShowsItsMassBodiesAndOneTree) {
    const ToolRun r = afCheck("--figure humanoid");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("total mass 150 (totalMass 150)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bodies (16)"), std::string::npos);
    EXPECT_NE(r.out.find("  pelvis  box  624  "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("hinge \"lknee\"  lshin -> lthigh  anchor ( 0, 5.5, 19 )"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("trees (1)"), std::string::npos);
}

TEST(AfCheckFigure, EntityDefLeadsToTheSameFigure) {
    const ToolRun byEntity = afCheck("--entity ragdoll_humanoid");
    EXPECT_EQ(byEntity.status, 0) << byEntity.err;
    EXPECT_EQ(byEntity.out, afCheck("--figure humanoid").out);
}

TEST(AfCheckFigure, JsonHasMassesAndNoDiagnostics) {
    const ToolRun r = afCheck("--json --figure humanoid");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["ok"], true);
    EXPECT_NEAR(j["totalMass"].get<double>(), 150.0, 1e-9);
    EXPECT_EQ(j["bodies"].size(), 16u);
    EXPECT_EQ(j["constraints"].size(), 15u);
    EXPECT_EQ(j["trees"].size(), 1u);
    EXPECT_TRUE(j["diagnostics"].empty());
    double sum = 0;
    for (const auto& b : j["bodies"]) sum += b["mass"].get<double>();
    EXPECT_NEAR(sum, 150.0, 1e-9);
}

TEST(AfCheckFigure, UnknownFigureIsAnError) {
    const ToolRun r = afCheck("--figure nosuchfigure");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("nosuchfigure"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(AfCheckFigure, FilesAndFigureTogetherIsBadUsage) {
    EXPECT_EQ(afCheck("--figure humanoid af/chain.af").status, 2);
    EXPECT_EQ(afCheck("--figure humanoid --format").status, 2);
}

// A mod folder that overrides the humanoid with a deliberately broken copy: the figure still
// builds, and each problem is a warning at its place in the copy.
TEST(AfCheckFigure, BrokenCopyInAModFolderGivesWarnings) {
    const std::string mod = testing::TempDir() + "af_check_mod_" + std::to_string(getpid());
    std::filesystem::create_directories(mod + "/af");
    std::string text = readAll(std::string(AF_SOURCE_DIR) + "/af/humanoid.af");
    auto replaceOnce = [&](const std::string& from, const std::string& to) {
        const std::size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
    };
    replaceOnce("origin bonecenter( \"neck\", \"headtop\" )", "origin bonecenter( \"neck\", \"hedtop\" )");
    replaceOnce("body1 \"lhand\"\n\tbody2 \"lloarm\"", "body1 \"lhand\"\n\tbody2 \"nowhere\"");
    std::ofstream(mod + "/af/humanoid.af", std::ios::binary) << text;

    const ToolRun r = afCheck("--figure humanoid --root . --root " + mod);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("humanoid.af:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("warning: joint \"hedtop\" is not in the skeleton"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("warning: ballAndSocketJoint \"lwrist\": body2 \"nowhere\" is not a body"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("warning: the bodies form 2 separate trees"), std::string::npos) << r.err;
    std::filesystem::remove_all(mod);
}

}  // namespace
