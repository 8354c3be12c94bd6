// Running console text (command_system.h): split it, report its syntax errors, then find each
// command by name (commands first, then cvars, as Doom's idCmdSystem does), check its argument
// count against its usage, and run it, turning failures and exceptions into counted errors.
// The built-in commands are in command_builtins.cpp.

#include "console/command_system.h"
#include "console/console_text.h"

#include "af/text/strings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace af::console {

namespace {


// Edit distance ignoring case, for "did you mean"; gives up (returns limit + 1) as soon as the
// lengths alone differ by more than `limit`, so long junk words cost nothing.
std::size_t editDistance(std::string_view a, std::string_view b, std::size_t limit) {
    const std::size_t gap = a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
    if (gap > limit) return limit + 1;
    const std::string x = toLower(a), y = toLower(b);
    std::vector<std::size_t> row(y.size() + 1);
    for (std::size_t j = 0; j <= y.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= x.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= y.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (x[i - 1] == y[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[y.size()];
}

// "takes 2 or more arguments, not 1"
std::string countProblem(const CommandDefinition& command, std::size_t given) {
    const std::size_t min = command.minArgs;
    std::string expected;
    if (!command.maxArgs) expected = std::to_string(min) + " or more arguments";
    else if (*command.maxArgs == 0) expected = "no arguments";
    else if (*command.maxArgs == min) expected = std::to_string(min) + (min == 1 ? " argument" : " arguments");
    else expected = std::to_string(min) + " to " + std::to_string(*command.maxArgs) + " arguments";
    return quoted(command.name) + " takes " + expected + ", not " + std::to_string(given) + " (usage: " +
           command.name + (command.usage.empty() ? "" : " " + command.usage) + ")";
}

}  // namespace

const std::string& CommandArgs::argv(std::size_t i) const {
    static const std::string kNone;
    return i < words_.size() ? words_[i] : kNone;
}

std::optional<double> CommandArgs::number(std::size_t i) const {
    const std::string& word = argv(i);
    double v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::string CommandArgs::joined(std::size_t from) const {
    std::string out;
    for (std::size_t i = from; i < words_.size(); ++i) out += (i == from ? "" : " ") + words_[i];
    return out;
}

std::vector<std::string> cvarValues(const CVar& cvar) {
    if (cvar.type() == CVarType::Bool) return {"0", "1"};
    return cvar.allowedValues();
}

CommandSystem::CommandSystem(Output output) : output_(std::move(output)) { addBuiltins(); }

void CommandSystem::addCommand(CommandDefinition definition) {
    if (!isConsoleName(definition.name))
        throw std::invalid_argument("command name " + quoted(definition.name) + " is not letters, digits and '_'");
    if (!definition.handler) throw std::invalid_argument("command " + quoted(definition.name) + " has no handler");
    std::string key = toLower(definition.name);
    if (commands_.contains(key) || cvars_.find(key))
        throw std::invalid_argument("console name " + quoted(definition.name) + " is already taken");
    commands_.emplace(std::move(key), std::move(definition));
}

CVar& CommandSystem::addCVar(CVarDefinition definition) {
    if (findCommand(definition.name))
        throw std::invalid_argument("console name " + quoted(definition.name) + " is already taken");
    return cvars_.add(std::move(definition));
}

const CommandDefinition* CommandSystem::findCommand(std::string_view name) const {
    const auto it = commands_.find(toLower(name));
    return it == commands_.end() ? nullptr : &it->second;
}

ExecuteResult CommandSystem::execute(std::string_view text, std::string_view source) {
    SplitResult split = splitCommands(text);
    return run(split.commands, source, split.errors);
}

ExecuteResult CommandSystem::execute(const std::vector<CommandText>& commands, std::string_view source) {
    return run(commands, source, {});
}

ExecuteResult CommandSystem::run(const std::vector<CommandText>& commands, std::string_view source,
                                 const std::vector<SyntaxError>& syntaxErrors) {
    const std::size_t commandsBefore = commandsRun_, errorsBefore = errorsReported_;
    for (const SyntaxError& error : syntaxErrors) reportError(source, error.where, error.message);
    ExecuteResult result;
    for (const CommandText& command : commands) {
        if (strict_ && errorsReported_ > errorsBefore) {
            result.stopped = true;
            break;
        }
        runCommand(command, source);
    }
    result.commands = commandsRun_ - commandsBefore;
    result.errors = errorsReported_ - errorsBefore;
    return result;
}

void CommandSystem::runCommand(const CommandText& command, std::string_view source) {
    ++commandsRun_;
    CommandStatus status = CommandStatus::success();
    try {
        status = dispatch(CommandArgs(command.words));
    } catch (const std::exception& e) {
        status = CommandStatus::failure(quoted(command.words.front()) + " failed: " + e.what());
    } catch (...) {
        status = CommandStatus::failure(quoted(command.words.front()) + " failed");
    }
    // A command's errors are placed by line: its column would only say where the line starts.
    if (!status.ok()) reportError(source, {command.where.line, 0}, status.message());
}

CommandStatus CommandSystem::dispatch(const CommandArgs& args) {
    const std::string& name = args.argv(0);
    if (const CommandDefinition* command = findCommand(name)) {
        const std::size_t given = args.argc() - 1;
        if (given < command->minArgs || (command->maxArgs && given > *command->maxArgs))
            return CommandStatus::failure(countProblem(*command, given));
        return command->handler(args, output_);
    }
    if (const CVar* cvar = cvars_.find(name)) {
        if (args.argc() == 1) {
            printCVar(*cvar);
            return CommandStatus::success();
        }
        return cvars_.set(name, args.joined(1));  // Doom sets a cvar to all the words after it
    }
    return CommandStatus::failure(unknownName("command", name));
}

void CommandSystem::reportError(std::string_view source, SourceLocation where, std::string_view message) {
    ++errorsReported_;
    std::string line;
    if (source == kTyped) {
        line = "error: " + std::string(message);
        if (where.column > 0) line += " at column " + std::to_string(where.column);
    } else {
        line = std::string(source);
        if (where.line > 0) line += ":" + std::to_string(where.line);
        if (where.column > 0) line += ":" + std::to_string(where.column);
        line += ": error: " + std::string(message);
    }
    output_.error(line);
}

void CommandSystem::printCVar(const CVar& cvar) const {
    std::string details = cvar.describeType() + "; default " + cvar.defaultText();
    if (hasFlag(cvar.flags(), CVarFlags::ReadOnly)) details += "; read-only";
    if (hasFlag(cvar.flags(), CVarFlags::Archive)) details += "; archived";
    if (hasFlag(cvar.flags(), CVarFlags::Simulation)) details += "; changes the simulation";
    output_.info(cvar.name() + " = " + cvar.text());
    output_.info("  " + details);
    if (!cvar.help().empty()) output_.info("  " + cvar.help());
}

std::string CommandSystem::unknownName(std::string_view what, std::string_view name) const {
    constexpr std::size_t kMaxEdits = 2;
    std::string message = "unknown " + std::string(what) + " " + quoted(name);
    std::string best;
    std::size_t bestDistance = kMaxEdits + 1;
    for (const std::string& candidate : names(what != "cvar", true)) {
        const std::size_t d = editDistance(name, candidate, kMaxEdits);
        // A suggestion must keep some of the name: "x" is not a misspelt "set".
        if (d < bestDistance && d < name.size()) best = candidate, bestDistance = d;
    }
    if (!best.empty()) message += "; did you mean " + quoted(best) + "?";
    return message;
}

std::vector<std::string> CommandSystem::names(bool commands, bool cvars) const {
    std::vector<std::string> out;
    if (commands)
        for (const auto& [key, command] : commands_) out.push_back(command.name);
    if (cvars)
        for (const CVar* cvar : cvars_.list()) out.push_back(cvar->name());
    return out;
}

std::vector<std::string> CommandSystem::complete(std::string_view lineBeforeCursor) const {
    const PartialCommand typed = splitForCompletion(lineBeforeCursor);
    std::vector<std::string> candidates;
    if (typed.words.empty()) {
        candidates = names(true, true);
    } else if (const CommandDefinition* command = findCommand(typed.words.front())) {
        if (command->completer) candidates = command->completer(CommandArgs(typed.words), typed.partial);
    } else if (const CVar* cvar = cvars_.find(typed.words.front()); cvar && typed.words.size() == 1) {
        candidates = cvarValues(*cvar);
    }
    std::erase_if(candidates, [&](const std::string& c) {
        return c.size() < typed.partial.size() || !equalsIgnoreCase(c.substr(0, typed.partial.size()), typed.partial);
    });
    // Ignoring case, as names are found; the exact spelling breaks ties so the order is fixed.
    std::sort(candidates.begin(), candidates.end(), [](const std::string& a, const std::string& b) {
        return std::pair(toLower(a), a) < std::pair(toLower(b), b);
    });
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return candidates;
}

}  // namespace af::console
