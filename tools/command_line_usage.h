#pragma once
// How every af tool reads its options: CLI11 parses them; --help prints the usage and exits 0;
// anything else it refuses is one line on stderr, "TOOL: error: …", and exit status 2, which a
// script can tell apart from the tools' own 0 and 1 (CLI11's own codes, 105, 109, …, would say
// nothing to it beyond "bad usage").

#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <optional>
#include <string_view>

namespace af::tools {

// Parses argv into `app`, then runs `validate` (which may throw CLI::ValidationError for checks
// across options). Returns the exit status when the program is to stop now, nothing otherwise.
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, const char* const* argv, std::string_view tool,
                                           const std::function<void()>& validate = {}) {
    try {
        app.parse(argc, argv);
        if (validate) validate();
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << tool << ": error: " << e.what() << "\nRun with --help for the options.\n";
        return 2;
    }
    return std::nullopt;
}

}  // namespace af::tools
