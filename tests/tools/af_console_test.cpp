// af-console run as a user runs it: `+command` arguments, scripts on stdin and through --exec,
// errors on stderr with the exit status a script can test, --strict, quit, and the session's
// commands and cvars (src/console/session.h) reached through the program.

#include "tool_run.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using ConsoleRun = af::test::ToolRun;
using af::test::readAll;
using af::test::scratchDir;
using af::test::writeAll;

// af-console with `input` as its stdin and stdout and stderr captured apart.
ConsoleRun afConsole(const std::string& arguments, const std::string& input = "") {
    return af::test::runTool(std::string(AF_CONSOLE_PATH) + " " + arguments, input);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(AfConsole, PlusCommandArgumentsRunAsDoomsEngineRunsThem) {
    const ConsoleRun run = afConsole("+echo hello world +echo again");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "hello world\nagain\n");
    EXPECT_EQ(run.err, "");
}

TEST(AfConsole, AScriptOnStdinRunsLineByLineInOrder) {
    const ConsoleRun run = afConsole("", "echo one\necho two; echo three\n// a comment\n\necho four");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "one\ntwo\nthree\nfour\n");
}

TEST(AfConsole, ExecRunsBeforePlusCommandsWhichRunBeforeStdin) {
    const std::filesystem::path script = scratchDir() / "first.cfg";
    writeAll(script, "echo from exec\n");
    const ConsoleRun run = afConsole("--exec '" + script.string() + "' +echo from plus", "echo from stdin\n");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "from exec\nfrom plus\nfrom stdin\n");
}

TEST(AfConsole, AnUnknownCommandIsReportedOnStderrTheRunGoesOnAndExitsOne) {
    const ConsoleRun run = afConsole("", "echo before\nnoSuchCommand\necho after\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "before\nafter\n");
    EXPECT_TRUE(contains(run.err, "stdin:2: error: unknown command 'noSuchCommand'")) << run.err;
}

TEST(AfConsole, StrictStopsAtTheFirstErrorWithStatusOne) {
    const ConsoleRun run = afConsole("--strict", "echo before\nnoSuchCommand\necho after\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "before\n") << "a line after the error ran";
    EXPECT_TRUE(contains(run.err, "unknown command 'noSuchCommand'")) << run.err;
}

TEST(AfConsole, StrictStopsAtAnErrorInsideACommandLineOfSeveralCommands) {
    const ConsoleRun run = afConsole("--strict +echo a +noSuchCommand +echo b", "echo c\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "a\n");
    EXPECT_TRUE(contains(run.err, "command line: error: unknown command 'noSuchCommand'")) << run.err;
}

TEST(AfConsole, AnErrorInAnExecScriptIsPlacedInTheScript) {
    const std::filesystem::path script = scratchDir() / "broken.cfg";
    writeAll(script, "echo fine\n\nset noSuchCvar 1\n");
    const ConsoleRun run = afConsole("--exec '" + script.string() + "'");
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "fine\n");
    EXPECT_TRUE(contains(run.err, script.string() + ":3: error:")) << run.err;
}

TEST(AfConsole, ExecOfAMissingFileIsAnError) {
    const ConsoleRun run = afConsole("--exec /nonexistent/af_console_script.cfg", "echo still runs\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_TRUE(contains(run.err, "/nonexistent/af_console_script.cfg")) << run.err;
    EXPECT_EQ(run.out, "still runs\n") << "without --strict the run goes on";
}

TEST(AfConsole, AnUnterminatedQuoteOnStdinIsLocatedByLineAndColumn) {
    const ConsoleRun run = afConsole("", "echo ok\necho \"open\necho next\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "ok\nnext\n");
    EXPECT_TRUE(contains(run.err, "stdin:2:6: error:")) << run.err;
}

TEST(AfConsole, QuitEndsTheRunAtOnceAndExitSpellsItToo) {
    ConsoleRun run = afConsole("", "echo a; quit; echo b\necho c\n");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "a\n");
    run = afConsole("+echo a +exit", "echo b\n");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "a\n");
}

TEST(AfConsole, HelpExitsZeroAndNamesTheOptions) {
    const ConsoleRun run = afConsole("--help");
    EXPECT_EQ(run.status, 0);
    for (const char* option : {"--root", "--exec", "--strict", "+command"}) EXPECT_TRUE(contains(run.out, option)) << option;
}

TEST(AfConsole, AnUnknownOptionIsBadUsageWithStatusTwo) {
    const ConsoleRun run = afConsole("--no-such-option");
    EXPECT_EQ(run.status, 2);
    EXPECT_TRUE(contains(run.err, "--no-such-option")) << run.err;
}

TEST(AfConsole, ACvarSetOnStdinReadsBack) {
    const ConsoleRun run = afConsole("", "set g_dragDamping 0.25\ng_dragDamping\n");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_TRUE(contains(run.out, "g_dragDamping = 0.25")) << run.out;
}

TEST(AfConsole, ACvarOutOfItsRangeIsRefusedAndKeepsItsValue) {
    const ConsoleRun run = afConsole("", "g_dragDamping 7\ng_dragDamping\n");
    EXPECT_EQ(run.status, 1);
    EXPECT_TRUE(contains(run.out, "g_dragDamping = 0.5")) << run.out;
    EXPECT_TRUE(contains(run.err, "stdin:1: error:")) << run.err;
}

TEST(AfConsole, ASpawnedRagdollIsListedByItsName) {
    const ConsoleRun run = afConsole("+spawn ragdoll_humanoid +list");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_TRUE(contains(run.out, "ragdoll_humanoid_1")) << run.out;
}

// af-console at a terminal: a pseudo-terminal stands for the user, who waits for each `] `
// prompt before typing the next line. HOME is a scratch folder, so the history file is the
// test's own; TERM=dumb and no inputrc keep readline's output and keys predictable.
class Terminal {
public:
    explicit Terminal(const std::filesystem::path& home) {
        pid_ = forkpty(&master_, nullptr, nullptr, nullptr);
        if (pid_ == 0) {
            setenv("HOME", home.c_str(), 1);
            setenv("TERM", "dumb", 1);
            setenv("INPUTRC", "/dev/null", 1);
            execl(AF_CONSOLE_PATH, AF_CONSOLE_PATH, static_cast<char*>(nullptr));
            _exit(127);
        }
    }
    ~Terminal() {
        if (pid_ > 0 && !reaped_) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
        if (master_ >= 0) close(master_);
    }

    bool started() const { return pid_ > 0; }
    const std::string& screen() const { return screen_; }

    // Waits for the next prompt, then types `keys`; false if no prompt came within the timeout.
    bool typeAtPrompt(const std::string& keys) {
        if (!readUntilPrompts(++prompts_)) return false;
        return write(master_, keys.data(), keys.size()) == ssize_t(keys.size());
    }

    // Reads what is left and the exit status; -1 if the program did not end in time.
    int finish() {
        while (readSome()) {
        }
        for (int tries = 0; tries < 100; ++tries) {  // 5 s
            int status = 0;
            const pid_t done = waitpid(pid_, &status, WNOHANG);
            if (done < 0) return -1;
            if (done == pid_) {
                reaped_ = true;
                return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            }
            usleep(50'000);
        }
        return -1;
    }

private:
    static constexpr int kTimeoutMs = 20'000;  // the session loads its decls before the first prompt

    bool readUntilPrompts(std::size_t count) {
        while (countPrompts() < count)
            if (!readSome()) return false;
        return true;
    }
    // A prompt starts a line; readline also redraws it after `\r` when it recalls history, and
    // typing on at a redraw would reach the terminal between two lines, in cooked mode.
    std::size_t countPrompts() const {
        std::size_t n = 0;
        for (std::size_t at = screen_.find("] "); at != std::string::npos; at = screen_.find("] ", at + 2))
            if (at == 0 || screen_[at - 1] == '\n') ++n;
        return n;
    }
    // False at the end of the output (the program closed the terminal) or after the timeout.
    bool readSome() {
        pollfd fd{master_, POLLIN, 0};
        if (poll(&fd, 1, kTimeoutMs) <= 0) return false;
        char buffer[4096];
        const ssize_t n = read(master_, buffer, sizeof buffer);
        if (n <= 0) return false;
        screen_.append(buffer, std::size_t(n));
        return true;
    }

    pid_t pid_ = -1;
    int master_ = -1;
    bool reaped_ = false;
    std::size_t prompts_ = 0;
    std::string screen_;
};

TEST(AfConsole, AtATerminalItPromptsCompletesNamesWithTabAndKeepsHistoryAcrossRuns) {
    const std::filesystem::path home = scratchDir();
    std::filesystem::remove(home / ".af_console_history");
    {
        Terminal terminal(home);
        if (!terminal.started()) GTEST_SKIP() << "no pseudo-terminal here";
        ASSERT_TRUE(terminal.typeAtPrompt("set g_dragDamping 0.25\n")) << terminal.screen();
        // Tab completes the cvar's name; only the completed name prints the cvar.
        ASSERT_TRUE(terminal.typeAtPrompt("g_dragDam\t\n")) << terminal.screen();
        ASSERT_TRUE(terminal.typeAtPrompt("noSuchCommand\n")) << terminal.screen();
        ASSERT_TRUE(terminal.typeAtPrompt("quit\n")) << terminal.screen();
        EXPECT_EQ(terminal.finish(), 0) << "an error typed at the prompt is not the program's failure\n"
                                        << terminal.screen();
        EXPECT_TRUE(contains(terminal.screen(), "g_dragDamping = 0.25")) << terminal.screen();
        EXPECT_TRUE(contains(terminal.screen(), "error: unknown command 'noSuchCommand'")) << terminal.screen();
    }
    const std::string history = readAll(home / ".af_console_history");
    EXPECT_TRUE(contains(history, "set g_dragDamping 0.25\n")) << history;
    {
        // A new run: Ctrl-P four times goes back past quit, noSuchCommand and g_dragDamping to the set.
        Terminal terminal(home);
        ASSERT_TRUE(terminal.started());
        ASSERT_TRUE(terminal.typeAtPrompt("\x10\x10\x10\x10\n")) << terminal.screen();
        ASSERT_TRUE(terminal.typeAtPrompt("g_dragDamping\n")) << terminal.screen();
        ASSERT_TRUE(terminal.typeAtPrompt("\x04")) << terminal.screen();  // Ctrl-D ends the input
        EXPECT_EQ(terminal.finish(), 0) << terminal.screen();
        EXPECT_TRUE(contains(terminal.screen(), "g_dragDamping = 0.25")) << terminal.screen();
    }
}

// Tab after `drag ENTITY` completes the entity's body names (console_completion.h).
TEST(AfConsole, AtATerminalTabCompletesABodyNameAfterDragEntity) {
    Terminal terminal(scratchDir());
    if (!terminal.started()) GTEST_SKIP() << "no pseudo-terminal here";
    ASSERT_TRUE(terminal.typeAtPrompt("spawn ragdoll_humanoid\n")) << terminal.screen();
    ASSERT_TRUE(terminal.typeAtPrompt("drag ragdoll_humanoid_1 rha\t0 0 60\n")) << terminal.screen();
    ASSERT_TRUE(terminal.typeAtPrompt("quit\n")) << terminal.screen();
    EXPECT_EQ(terminal.finish(), 0) << terminal.screen();
    EXPECT_TRUE(contains(terminal.screen(), "dragging ragdoll_humanoid_1 rhand")) << terminal.screen();
}

}  // namespace

namespace {

// `screenshot FILE` writes a PNG of the world, and a write that cannot happen leaves nothing.
TEST(AfConsole, ScreenshotWritesAPictureOfTheWorld) {
    const std::filesystem::path picture = scratchDir() / "shot.png";
    const ConsoleRun run = afConsole("", "spawn ragdoll_humanoid\nwaitRest\nscreenshot \"" + picture.string() + "\"\n");
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string png = readAll(picture);
    ASSERT_GT(png.size(), 1000u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_FALSE(std::filesystem::exists(picture.string() + ".partial"));
    const ConsoleRun bad = afConsole("", "screenshot /no/such/folder/shot.png\n");
    EXPECT_EQ(bad.status, 1);
    EXPECT_TRUE(contains(bad.err, "screenshot")) << bad.err;
}

// The af_show* cvars that have a picture change it; the same world without them draws the same.
TEST(AfConsole, ScreenshotDrawsTheShowCvarsOverTheWorld) {
    const std::filesystem::path dir = scratchDir();
    const std::string scene = "spawn ragdoll_humanoid\nwaitRest\n";
    const auto shot = [&](const std::string& name, const std::string& cvars) {
        const ConsoleRun run = afConsole("", scene + cvars + "screenshot \"" + (dir / name).string() + "\"\n");
        EXPECT_EQ(run.status, 0) << run.err;
        return readAll(dir / name);
    };
    const std::string plain = shot("plain.png", ""), again = shot("again.png", "af_showTimings 1\n");
    const std::string marked = shot("marked.png", "af_showConstraints 1; af_showLimits 1; af_showTrees 1\n");
    EXPECT_EQ(plain, again) << "af_showTimings has no picture";
    EXPECT_NE(plain, marked);
    EXPECT_NE(plain, shot("masses.png", "af_showMass 1; af_showInertia 1\n"));
}

}  // namespace
