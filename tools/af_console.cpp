// af-console: the ragdoll console as a program, in the style of Doom's engine. It makes a
// Session (src/console/session.h) over the mod folders, runs an --exec script, then the
// `+command args` of its arguments, then reads commands: at a terminal through readline with
// Doom's `] ` prompt, history and tab completion; otherwise every line of stdin in order, so
// `af-console < script` runs a script.
//
// With no --root: this source tree, which holds def/, af/, models/ and maps/ as a mod folder.
//
// Exit status: 0 when every command ran; 1 when a command of a script (--exec, `+command`s,
// stdin that is not a terminal) failed, or at the first error of any kind under --strict;
// 2 for bad usage (an unknown option) or when the session cannot be made.

#include "command_line_usage.h"
#include "af_console_readline.h"
#include "console_completion.h"
#include "console_screenshot.h"

#include "console/command_line.h"
#include "console/command_system.h"
#include "console/session.h"

#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace {

using af::console::CommandStatus;
using af::console::CommandSystem;
using af::console::CommandText;

struct Options {
    std::vector<std::string> roots;
    std::string exec;
    bool strict = false;
};

// Runs console text one command at a time, so that `quit` stops what follows it at once (the
// command system would run the rest of the text first) and a strict run stops at its first error.
class Runner {
public:
    Runner(CommandSystem& console, bool strict) : console_(console), strict_(strict) {
        if (!console_.findCommand("quit")) addQuit("quit", "ends af-console");
        if (!console_.findCommand("exit")) addQuit("exit", "the same as quit");
    }

    // False once the run should end: quit, or an error under --strict.
    bool running() const { return !quit_ && !stopped_; }
    bool stoppedByError() const { return stopped_; }
    // Errors of scripted input; errors typed at the prompt are the user's to see, not the
    // program's result.
    std::size_t scriptErrors() const { return scriptErrors_; }

    // `text` is line `firstLine` onward of `source` (CommandSystem::kTyped for the prompt).
    void run(std::string_view text, std::string_view source, int firstLine = 1) {
        af::console::SplitResult split = af::console::splitCommands(text);
        for (const af::console::SyntaxError& error : split.errors) {
            reportSyntaxError(source, firstLine - 1 + error.where.line, error.where.column, error.message);
            if (!running()) return;
        }
        for (CommandText& command : split.commands) {
            command.where.line += firstLine - 1;
            run(command, source);
            if (!running()) return;
        }
    }

    void run(const CommandText& command, std::string_view source) {
        if (!running()) return;
        const af::console::ExecuteResult result = console_.execute(std::vector<CommandText>{command}, source);
        noteErrors(result.errors, source);
    }

    // An error of the program's own (a script that cannot be read), printed as the console's are.
    void reportError(const std::string& message) {
        console_.output().error("af-console: error: " + message);
        noteErrors(1, "");
    }

private:
    void addQuit(const std::string& name, const std::string& help) {
        console_.addCommand({name, "", help, 0, 0,
                             [this](const af::console::CommandArgs&, const af::console::Output&) {
                                 quit_ = true;
                                 return CommandStatus::success();
                             },
                             {}});
    }

    // The command system's form (command_system.cpp, reportError), which the commands of a line
    // split here would otherwise lose: `source:line:col: error: …`, or `error: … at column N`
    // for typed text.
    void reportSyntaxError(std::string_view source, int line, int column, const std::string& message) {
        std::string text;
        if (source == CommandSystem::kTyped) {
            text = "error: " + message + " at column " + std::to_string(column);
        } else {
            text = std::string(source) + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: " + message;
        }
        console_.output().error(text);
        noteErrors(1, source);
    }

    void noteErrors(std::size_t errors, std::string_view source) {
        if (errors == 0) return;
        if (source != CommandSystem::kTyped) scriptErrors_ += errors;
        if (strict_) stopped_ = true;
    }

    CommandSystem& console_;
    bool strict_;
    bool quit_ = false;
    bool stopped_ = false;
    std::size_t scriptErrors_ = 0;
};

std::optional<std::string> readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return std::nullopt;
    return text.str();
}

int runConsole(const Options& o, const std::vector<CommandText>& plusCommands) {
    // Info to stdout and errors to stderr; stdout is flushed before an error so that the two,
    // sent to one file (2>&1), stay in the order they happened.
    CommandSystem console(af::console::Output(
        [](std::string_view line) { std::cout << line << '\n'; },
        [](std::string_view line) {
            std::cout.flush();
            std::cerr << line << '\n';
        }));
    console.setStrict(o.strict);

    std::vector<std::filesystem::path> roots(o.roots.begin(), o.roots.end());
    if (roots.empty()) roots.emplace_back(AF_DATA_DIR);
    af::console::Session session(std::move(roots), console);
    af::console::addScreenshotCommand(console, session);
    Runner runner(console, o.strict);

    if (!o.exec.empty()) {
        if (const std::optional<std::string> text = readText(o.exec)) runner.run(*text, o.exec);
        else runner.reportError("cannot read the script '" + o.exec + "' given to --exec");
    }
    // `+command`s are placed nowhere in a file (their line is 0): the source names them.
    for (const CommandText& command : plusCommands) runner.run(command, "command line");

    if (runner.running()) {
        if (isatty(STDIN_FILENO)) {
            const auto complete = [&](std::string_view line) { return af::console::completeConsoleLine(console, session, line); };
            af::console::runTerminal(complete, {af::console::defaultHistoryFile()}, [&](const std::string& line) {
                runner.run(line, CommandSystem::kTyped);
                return runner.running();
            });
        } else {
            std::string line;
            for (int number = 1; runner.running() && std::getline(std::cin, line); ++number) {
                if (!line.empty() && line.back() == '\r') line.pop_back();  // a script written on Windows
                runner.run(line, "stdin", number);
            }
        }
    }
    std::cout.flush();
    return runner.stoppedByError() || runner.scriptErrors() > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Doom's `+command args` are not options: they and everything after them are taken here,
    // before CLI11 sees the arguments (parsePlusCommands keeps the program's own in front).
    std::vector<std::string> arguments(argv + 1, argv + argc);
    const af::console::PlusCommands plus = af::console::parsePlusCommands(arguments);

    Options o;
    CLI::App app{"The ragdoll console: Doom 3-style commands and cvars over a world of articulated figures."};
    app.name("af-console");
    app.add_option("--root", o.roots, "a mod folder laid out like Doom's base/ (repeat: lowest priority first)")
        ->type_name("DIR");
    app.add_option("--exec", o.exec, "run this script's commands first")->type_name("FILE");
    app.add_flag("--strict", o.strict, "stop at the first error, with exit status 1");
    app.footer("After the options, `+command args` run commands in order, as Doom's engine does\n"
               "(af-console +spawn ragdoll_humanoid +list). Then commands are read from the terminal,\n"
               "or from stdin when it is not one, until `quit` or the end of the input.");
    if (const auto exitStatus = af::tools::parseCommandLine(app, int(1 + plus.leading.size()), argv, "af-console"))
        return *exitStatus;
    try {
        return runConsole(o, plus.commands);
    } catch (const std::exception& e) {
        std::cerr << "af-console: " << e.what() << '\n';
        return 2;
    }
}
