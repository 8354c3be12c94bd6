// Fuzz target: any bytes run as console text must give counted errors, never a crash or an
// escaping exception; cvars keep values their checks allow (finite, in range), and completing
// any prefix of the text gives sorted candidates. exec reads no files: its reader refuses them.
// The same text then drives a ragdoll Session (session.h) over this source tree's mod folder,
// one command at a time, bounded so that one input stays fast: the clock commands together
// advance at most kMaxSteps steps, a spawn is skipped while kMaxRagdolls are in the world, and the
// files that map and the save commands name are put in a scratch folder, emptied for every input.

#include "console/command_line.h"
#include "console/command_system.h"
#include "console/session.h"

#include "af/text/strings.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace af::console;

// Long inputs only repeat what short ones test, slower.
constexpr std::size_t kMaxCompletedPrefixes = 64;
// A humanoid's step costs about a millisecond; the replay test runs hundreds of inputs.
constexpr double kMaxSteps = 20;
constexpr std::size_t kMaxRagdolls = 2;

// A number as the session reads one (the whole word, finite), or nothing.
std::optional<double> number(const std::string& word) {
    double v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

// The most steps a clock command may take, or nothing when it is no clock command or will be
// refused for its argument.
std::optional<double> stepsOf(const CommandText& command, double timeStep) {
    const std::string name = af::toLower(command.words.front());
    double argument = name == "waitrest" ? 10 : 1;  // the commands' defaults
    if (command.words.size() > 1) {
        const std::optional<double> given = number(command.words[1]);
        if (!given) return std::nullopt;
        argument = *given;
    }
    if (name == "step") return argument;
    if ((name == "run" && command.words.size() > 1) || name == "waitrest") return std::ceil(argument / timeStep);
    return std::nullopt;
}

// A file name of the word's letters, digits, `_`, `.` and `-`, inside `folder`.
std::string scratchFile(const fs::path& folder, const std::string& word) {
    std::string name = "f_";
    for (const char c : word.substr(0, 32))
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-') name += c;
    return (folder / name).string();
}

void runSession(std::string_view text) {
    static const fs::path folder = fs::temp_directory_path() / ("af_console_fuzz." + std::to_string(getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    fs::copy_file(fs::path(AF_DATA_DIR) / "maps" / "default.map", folder / "f_default.map");

    std::size_t errorLines = 0, errors = 0;
    CommandSystem console(Output({}, [&](std::string_view) { ++errorLines; }));
    console.setScriptReader([](const std::string&) { return std::nullopt; });
    Session session({AF_DATA_DIR}, console);
    double stepsLeft = kMaxSteps;
    for (CommandText command : splitCommands(text).commands) {
        const std::string name = af::toLower(command.words.front());
        if (const auto steps = stepsOf(command, session.world().settings().timeStep)) {
            if (!(*steps <= stepsLeft)) continue;
            stepsLeft -= std::max(0.0, *steps);
        }
        if (name == "spawn" && session.world().figureIds().size() >= kMaxRagdolls) continue;
        if ((name == "map" || name == "saveragdolls" || name == "saveselected") && command.words.size() > 1)
            command.words[1] = scratchFile(folder, command.words[1]);
        errors += console.execute(std::vector<CommandText>{command}, "fuzz.cfg").errors;
    }
    if (errors != errorLines) std::abort();
    fs::remove_all(folder);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::size_t errorLines = 0;
    CommandSystem console(Output({}, [&](std::string_view) { ++errorLines; }));
    console.setScriptReader([](const std::string&) { return std::nullopt; });
    console.addCVar(realCVar("g_gravity", 1066, {0, 10000}, "gravity", CVarFlags::Simulation));
    console.addCVar(intCVar("af_steps", 4, {1, 64}, "substeps"));
    console.addCVar(boolCVar("af_skipSelfCollision", false, "no self collision"));
    console.addCVar(stringCVar("af_solver", "tree", "primary solver", {"tree", "exact"}));
    console.addCVar(stringCVar("af_label", "", "any text", {}, CVarFlags::Archive));
    console.addCommand({"spawn", "DEF [KEY VALUE]...", "spawns", 1, std::nullopt,
                        [](const CommandArgs& args, const Output& out) {
                            if (args.argc() % 2 != 0) return CommandStatus::failure("a key without a value");
                            out.info("spawned " + args.argv(1));
                            return CommandStatus::success();
                        },
                        [](const CommandArgs&, std::string_view) { return std::vector<std::string>{"char_doomguy"}; }});

    const ExecuteResult result = console.execute(text, "fuzz.cfg");
    if (result.errors != errorLines) std::abort();
    const double gravity = console.cvars().find("g_gravity")->asReal();
    const std::int64_t steps = console.cvars().find("af_steps")->asInt();
    if (!std::isfinite(gravity) || gravity < 0 || gravity > 10000 || steps < 1 || steps > 64) std::abort();
    // Whatever was set, the archive is a script that runs without errors.
    if (!console.execute(console.cvars().archive(), "archive.cfg").ok()) std::abort();

    const std::size_t step = std::max<std::size_t>(1, size / kMaxCompletedPrefixes);
    for (std::size_t end = 0; end <= size; end += step) {
        const std::vector<std::string> candidates = console.complete(text.substr(0, end));
        for (std::size_t i = 1; i < candidates.size(); ++i)
            if (!(af::toLower(candidates[i - 1]) <= af::toLower(candidates[i])) || candidates[i - 1] == candidates[i])
                std::abort();
    }
    runSession(text);
    return 0;
}
