#pragma once
// A Session on a console of its own, for the console's tests: what it prints is kept, information
// and errors apart; and the scratch files and reads those tests share.

#include "console/command_system.h"
#include "console/session.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace af::console::test {

struct SessionConsole {
    std::string info, errors;
    CommandSystem commands{Output([this](std::string_view l) { info += std::string(l) + "\n"; },
                                  [this](std::string_view l) { errors += std::string(l) + "\n"; })};
    Session session;

    explicit SessionConsole(std::vector<std::filesystem::path> roots = {AF_SOURCE_DIR})
        : session(std::move(roots), commands) {}
    ExecuteResult run(std::string_view text) { return commands.execute(text, "test.cfg"); }
};

// `name` in a folder of the system's temporary folder (created).
inline std::filesystem::path scratchFile(const std::string& folder, const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / folder;
    std::filesystem::create_directories(dir);
    return dir / name;
}

inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace af::console::test
