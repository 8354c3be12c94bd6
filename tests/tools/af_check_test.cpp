// af-check as a user runs it: exit status, what goes to stdout and stderr, --format and --json.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct ToolRun {
    int status = -1;
    std::string out;
    std::string err;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs af-check from the source tree, so paths in its output are the ones written here.
ToolRun afCheck(const std::string& args) {
    static int counter = 0;
    // ctest runs tests of this program in parallel processes: the name must be unique to each.
    const std::string errPath =
        testing::TempDir() + "af_check_err_" + std::to_string(getpid()) + "_" + std::to_string(counter++);
    const std::string command = std::string("cd ") + AF_SOURCE_DIR + " && " + AF_CHECK_PATH + " " + args + " 2>" + errPath;
    ToolRun run;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return run;
    std::array<char, 4096> buffer;
    for (std::size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) run.out.append(buffer.data(), n);
    const int raw = pclose(pipe);
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.err = slurp(errPath);
    std::remove(errPath.c_str());
    return run;
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
    std::istringstream golden(slurp(std::string(AF_SOURCE_DIR) + "/tests/golden/bad_syntax.diag"));
    for (std::string line; std::getline(golden, line);) expected += "tests/golden/" + line + "\n";
    EXPECT_EQ(r.err, expected);
    EXPECT_NE(r.out.find("tests/golden/bad_syntax.af: FAILED"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("af/chain.af: ok"), std::string::npos) << r.out;
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
    EXPECT_EQ(r.out, slurp(std::string(AF_SOURCE_DIR) + "/tests/golden/every_keyword.out"));
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
    EXPECT_EQ(d["message"], "density must be greater than 0, found -1");
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
