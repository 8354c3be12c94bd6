// The commands every console has (command_system.h): set, seta, toggle, reset, cvarlist,
// cmdlist, help, exec and echo, with Doom's names and arguments (docs/doom-physics.md §5.1).
// Differences from Doom: set refuses unknown cvars instead of creating string cvars (never a
// silent default), and the lists filter by prefix rather than by wildcard.

#include "console/command_system.h"
#include "console/console_text.h"

#include "af/text/strings.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace af::console {

namespace {

std::optional<std::string> readFile(const std::string& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Doom's exec adds `.cfg` to a name without an extension (idStr::DefaultFileExtension).
std::string withDefaultExtension(std::string path) {
    const std::size_t slash = path.find_last_of("/\\");
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) path += ".cfg";
    return path;
}

// Pads names to one column so the listings read as a table.
std::size_t widestOf(const std::vector<std::string>& names) {
    std::size_t width = 0;
    for (const std::string& name : names) width = std::max(width, name.size());
    return width;
}


std::string flagNote(const CVar& cvar) {
    std::string note;
    if (hasFlag(cvar.flags(), CVarFlags::ReadOnly)) note += " read-only";
    if (hasFlag(cvar.flags(), CVarFlags::Archive)) note += " archived";
    if (hasFlag(cvar.flags(), CVarFlags::Simulation)) note += " simulation";
    return note.empty() ? note : "  [" + note.substr(1) + "]";
}

}  // namespace

void CommandSystem::addBuiltins() {
    reader_ = readFile;
    // Completers: cvar names for the first argument, then that cvar's values.
    const CommandCompleter cvarThenValues = [this](const CommandArgs& typed, std::string_view) {
        if (typed.argc() == 1) return names(false, true);
        const CVar* cvar = cvars_.find(typed.argv(1));
        return cvar ? cvarValues(*cvar) : std::vector<std::string>{};
    };
    const CommandCompleter cvarNames = [this](const CommandArgs& typed, std::string_view) {
        return typed.argc() == 1 ? names(false, true) : std::vector<std::string>{};
    };
    const auto printSet = [this](const std::string& name) {
        if (const CVar* cvar = cvars_.find(name)) output_.info(cvar->name() + " = " + cvar->text());
    };
    const auto needCVar = [this](const std::string& name) {
        return cvars_.find(name) ? CommandStatus::success() : CommandStatus::failure(unknownName("cvar", name));
    };

    addCommand({"set", "NAME VALUE...", "sets a cvar; the words after its name are its value", 2, std::nullopt,
                [=, this](const CommandArgs& args, const Output&) {
                    if (CommandStatus known = needCVar(args.argv(1)); !known.ok()) return known;
                    return cvars_.set(args.argv(1), args.joined(2));
                },
                cvarThenValues});
    addCommand({"seta", "NAME VALUE...", "sets a cvar and marks it archived (see CVarSystem::archive)", 2,
                std::nullopt,
                [=, this](const CommandArgs& args, const Output&) {
                    if (CommandStatus known = needCVar(args.argv(1)); !known.ok()) return known;
                    CommandStatus status = cvars_.set(args.argv(1), args.joined(2));
                    if (status.ok()) cvars_.markArchived(*cvars_.find(args.argv(1)));
                    return status;
                },
                cvarThenValues});
    addCommand({"toggle", "NAME [VALUE...]",
                "flips a bool, turns a number between 0 and 1 (or 0 and VALUE), or cycles through the VALUEs", 1,
                std::nullopt,
                [=, this](const CommandArgs& args, const Output&) {
                    if (CommandStatus known = needCVar(args.argv(1)); !known.ok()) return known;
                    const std::vector<std::string> values(args.words().begin() + 2, args.words().end());
                    CommandStatus status = cvars_.toggle(args.argv(1), values);
                    if (status.ok()) printSet(args.argv(1));
                    return status;
                },
                cvarThenValues});
    addCommand({"reset", "NAME", "sets a cvar back to its default", 1, 1,
                [=, this](const CommandArgs& args, const Output&) {
                    if (CommandStatus known = needCVar(args.argv(1)); !known.ok()) return known;
                    return cvars_.reset(args.argv(1));
                },
                cvarNames});
    addCommand({"cvarlist", "[PREFIX]", "lists the cvars whose names start with PREFIX, with their values", 0, 1,
                [this](const CommandArgs& args, const Output& out) {
                    const std::vector<const CVar*> cvars = cvars_.list(args.argv(1));
                    std::vector<std::string> listed;
                    for (const CVar* cvar : cvars) listed.push_back(cvar->name());
                    const std::size_t width = widestOf(listed);
                    for (const CVar* cvar : cvars)
                        out.info(padded(cvar->name(), width) + "  " + cvar->text() + flagNote(*cvar));
                    out.info(std::to_string(cvars.size()) + (cvars.size() == 1 ? " cvar" : " cvars"));
                    return CommandStatus::success();
                },
                cvarNames});
    addCommand({"cmdlist", "[PREFIX]", "lists the commands whose names start with PREFIX", 0, 1,
                [this](const CommandArgs& args, const Output& out) {
                    const std::string prefix = toLower(args.argv(1));
                    std::vector<std::string> listed = names(true, false);
                    std::erase_if(listed, [&](const std::string& n) { return !toLower(n).starts_with(prefix); });
                    const std::size_t width = widestOf(listed);
                    for (const std::string& name : listed)
                        out.info(padded(name, width) + "  " + findCommand(name)->help);
                    out.info(std::to_string(listed.size()) + (listed.size() == 1 ? " command" : " commands"));
                    return CommandStatus::success();
                },
                [this](const CommandArgs& typed, std::string_view) {
                    return typed.argc() == 1 ? names(true, false) : std::vector<std::string>{};
                }});
    addCommand({"help", "NAME", "a command's usage and help, or a cvar's type, default, value and help", 1, 1,
                [this](const CommandArgs& args, const Output& out) {
                    if (const CommandDefinition* command = findCommand(args.argv(1))) {
                        out.info("usage: " + command->name + (command->usage.empty() ? "" : " " + command->usage));
                        if (!command->help.empty()) out.info("  " + command->help);
                        return CommandStatus::success();
                    }
                    if (const CVar* cvar = cvars_.find(args.argv(1))) {
                        printCVar(*cvar);
                        return CommandStatus::success();
                    }
                    return CommandStatus::failure(unknownName("command or cvar", args.argv(1)));
                },
                [this](const CommandArgs& typed, std::string_view) {
                    return typed.argc() == 1 ? names(true, true) : std::vector<std::string>{};
                }});
    addCommand({"exec", "FILE", "runs the commands of a script (FILE.cfg when FILE has no extension)", 1, 1,
                [this](const CommandArgs& args, const Output&) { return exec(withDefaultExtension(args.argv(1))); },
                {}});
    addCommand({"echo", "[TEXT...]", "prints its arguments", 0, std::nullopt,
                [](const CommandArgs& args, const Output& out) {
                    out.info(args.joined(1));
                    return CommandStatus::success();
                },
                {}});
}

// The script's errors are reported, placed in the script, by the nested run; exec itself fails
// only when the script cannot be run at all.
CommandStatus CommandSystem::exec(const std::string& path) {
    if (execDepth_ >= kMaxExecDepth)
        return CommandStatus::failure("exec of '" + path + "' nested deeper than " + std::to_string(kMaxExecDepth) +
                                      " scripts (does a script exec itself?)");
    const std::optional<std::string> text = reader_ ? reader_(path) : std::nullopt;
    if (!text) return CommandStatus::failure("cannot read script '" + path + "'");
    ++execDepth_;
    struct Leave {
        int& depth;
        ~Leave() { --depth; }
    } leave{execDepth_};
    execute(*text, path);
    return CommandStatus::success();
}

}  // namespace af::console
