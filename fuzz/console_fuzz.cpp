// Fuzz target: any bytes run as console text must give counted errors, never a crash or an
// escaping exception; cvars keep values their checks allow (finite, in range), and completing
// any prefix of the text gives sorted candidates. exec reads no files: its reader refuses them.

#include "console/command_system.h"

#include "af/text/strings.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

// Long inputs only repeat what short ones test, slower.
constexpr std::size_t kMaxCompletedPrefixes = 64;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace af::console;
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
    return 0;
}
