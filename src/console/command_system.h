#pragma once
// The console's commands: a registry of named commands and the cvars, and the runner that
// executes console text and scripts through them, as Doom's command system does
// (docs/doom-physics.md §5.1). Commands are found ignoring case and before cvars; a cvar's name
// alone prints it, followed by a value sets it. Built in: set, seta, toggle, reset, cvarlist,
// cmdlist, help, exec, echo. Everything printed goes to an Output, never to a terminal, and
// nothing thrown by a command escapes execute(): a failure is an error message, counted.

#include "console/command_line.h"
#include "console/cvars.h"

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace af::console {

using CommandStatus = Status;

// Where the console's text goes: one call per line, without its line break. A sink must not
// throw: execute() catches what commands throw, not what its own printing does.
class Output {
public:
    using Sink = std::function<void(std::string_view line)>;

    Output(Sink info, Sink error) : info_(std::move(info)), error_(std::move(error)) {}
    static Output discard() { return Output({}, {}); }

    void info(std::string_view line) const {
        if (info_) info_(line);
    }
    void error(std::string_view line) const {
        if (error_) error_(line);
    }

private:
    Sink info_;
    Sink error_;
};

// The words of one command, numbered as Doom's idCmdArgs numbers them: argv(0) is the
// command's name, argc() counts it, and a word past the end is empty.
class CommandArgs {
public:
    explicit CommandArgs(std::vector<std::string> words) : words_(std::move(words)) {}

    std::size_t argc() const { return words_.size(); }
    const std::string& argv(std::size_t i) const;
    // Words `from`… joined by single spaces (Doom's Args()), so `set name a b` sets "a b".
    std::string joined(std::size_t from) const;
    // argv(i) as a finite number; none for a word that is anything else, whole.
    std::optional<double> number(std::size_t i) const;
    const std::vector<std::string>& words() const { return words_; }

private:
    std::vector<std::string> words_;
};

// A handler prints to the Output and returns failure with a message (printed as an error by the
// system, with the place the command came from) or success.
using CommandHandler = std::function<CommandStatus(const CommandArgs&, const Output&)>;
// Candidates for the word being typed: `typed` holds the words before it, so the word is
// argument number typed.argc(). The system keeps those starting with `prefix` and sorts them.
using CommandCompleter = std::function<std::vector<std::string>(const CommandArgs& typed, std::string_view prefix)>;

struct CommandDefinition {
    std::string name;
    std::string usage;  // the arguments, as `help` prints them after the name: "NAME VALUE..."
    std::string help;
    std::size_t minArgs = 0;  // arguments, not counting the name
    std::optional<std::size_t> maxArgs;  // none: any number
    CommandHandler handler;
    CommandCompleter completer;  // optional
};

struct ExecuteResult {
    std::size_t commands = 0;  // commands run, those of scripts run by exec included
    std::size_t errors = 0;    // error messages printed, syntax errors included
    bool stopped = false;      // strict mode stopped at an error

    bool ok() const { return errors == 0; }
};

class CommandSystem {
public:
    // The text of a script file, or nothing when it cannot be read.
    using ScriptReader = std::function<std::optional<std::string>(const std::string& path)>;

    // The source name of typed text: its errors are `error: …` without a place.
    static constexpr std::string_view kTyped = "console";
    // Scripts that exec scripts stop here, so a script that execs itself is an error.
    static constexpr int kMaxExecDepth = 16;

    explicit CommandSystem(Output output = Output::discard());
    // The built-in commands hold `this`: a console stays where it was made.
    CommandSystem(const CommandSystem&) = delete;
    CommandSystem& operator=(const CommandSystem&) = delete;

    CVarSystem& cvars() { return cvars_; }
    const CVarSystem& cvars() const { return cvars_; }
    const Output& output() const { return output_; }
    void setOutput(Output output) { output_ = std::move(output); }
    // Replaces the reader exec uses (the default reads files); a fuzz target refuses them all.
    void setScriptReader(ScriptReader reader) { reader_ = std::move(reader); }
    // Strict: a run stops at its first error, scripts run by exec included.
    void setStrict(bool strict) { strict_ = strict; }

    // Throws std::invalid_argument when the name is taken by a command or a cvar, is not
    // letters, digits and `_`, or there is no handler: a programming error.
    void addCommand(CommandDefinition definition);
    // A cvar registered through the console, so its name cannot shadow or be shadowed by a
    // command (same errors as addCommand).
    CVar& addCVar(CVarDefinition definition);
    const CommandDefinition* findCommand(std::string_view name) const;

    // Runs every command of `text`. Errors are `source:line: error: …` (syntax errors
    // `source:line:col: …`) or, for typed text, `error: …`. A line with a syntax error is
    // not run; the other lines are, except in strict mode.
    ExecuteResult execute(std::string_view text, std::string_view source = kTyped);
    // Runs commands already split, such as parsePlusCommands gives.
    ExecuteResult execute(const std::vector<CommandText>& commands, std::string_view source);

    // The words that may complete the last word of `lineBeforeCursor`, sorted: command and
    // cvar names for the first word; cvar names after set, seta, toggle and reset, and command
    // names too after help; a cvar's values (0 and 1, or its allowed strings) after a cvar's
    // name or set NAME; otherwise the command's completer.
    std::vector<std::string> complete(std::string_view lineBeforeCursor) const;

private:
    void addBuiltins();  // command_builtins.cpp
    ExecuteResult run(const std::vector<CommandText>& commands, std::string_view source,
                      const std::vector<SyntaxError>& syntaxErrors);
    void runCommand(const CommandText& command, std::string_view source);
    CommandStatus dispatch(const CommandArgs& args);
    void reportError(std::string_view source, SourceLocation where, std::string_view message);
    void printCVar(const CVar& cvar) const;
    CommandStatus exec(const std::string& path);
    std::string unknownName(std::string_view what, std::string_view name) const;
    std::vector<std::string> names(bool commands, bool cvars) const;

    CVarSystem cvars_;
    std::map<std::string, CommandDefinition> commands_;  // by lower-case name
    Output output_;
    ScriptReader reader_;
    bool strict_ = false;
    // Counts since construction; a run's result is their growth, so the commands and errors of
    // scripts that exec runs count in the run that called exec.
    std::size_t commandsRun_ = 0;
    std::size_t errorsReported_ = 0;
    int execDepth_ = 0;
};

// A cvar's values for completion: 0 and 1 for a Bool, the allowed strings, else none.
std::vector<std::string> cvarValues(const CVar& cvar);

}  // namespace af::console
