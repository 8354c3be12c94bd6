// Running a built program as a user runs it, from a test: its exit status and what it printed,
// with a scratch folder of the running test's own.

#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace af::test {

struct ToolRun {
    int status = -1;  // the exit status; -1 when killed by a signal
    std::string out;
    std::string err;
};

// A folder for the running test alone: ctest runs the tests of one program in parallel processes,
// and the process id keeps two build trees testing at once apart.
inline std::filesystem::path scratchDir() {
    const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "af_tests" /
                                      (std::string(test->test_suite_name()) + "." + test->name() + "." +
                                       std::to_string(getpid()));
    // Emptied on a test's first call: a run long ago under the same process id (ids are reused)
    // left its files there, which a test writing with no --force then meets.
    static std::filesystem::path emptied;
    if (dir != emptied) {
        std::filesystem::remove_all(dir);
        emptied = dir;
    }
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void writeAll(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Runs a shell command with `input` as its stdin (a file, so never a terminal) and its stdout and
// stderr captured apart. A command that ends in `2>&1` has both in `out`.
inline ToolRun runTool(const std::string& command, const std::string& input = "") {
    const std::filesystem::path dir = scratchDir();
    writeAll(dir / "stdin", input);
    const std::string shell = "{ " + command + "; } < '" + (dir / "stdin").string() + "' > '" + (dir / "stdout").string() +
                              "' 2> '" + (dir / "stderr").string() + "'";
    const int status = std::system(shell.c_str());
    ToolRun run;
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = readAll(dir / "stdout");
    run.err = readAll(dir / "stderr");
    return run;
}

}  // namespace af::test
