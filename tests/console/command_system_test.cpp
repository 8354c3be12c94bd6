#include "console/command_system.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace af::console {
namespace {

using Lines = std::vector<std::string>;

// A console whose output is captured, with a cvar and a command like those af-console registers.
struct Console : ::testing::Test {
    Console() {
        console.setOutput(Output([this](std::string_view l) { info.emplace_back(l); },
                                 [this](std::string_view l) { errors.emplace_back(l); }));
        console.addCVar(realCVar("g_gravity", 1066, {0, 10000}, "gravity, units/s²", CVarFlags::Simulation));
        console.addCVar(boolCVar("af_skipSelfCollision", false, "no self collision"));
        console.addCommand({"spawn", "DEF [KEY VALUE]...", "spawns an entity", 1, std::nullopt,
                            [this](const CommandArgs& args, const Output& out) {
                                if (args.argc() % 2 != 0) return CommandStatus::failure("a key without a value");
                                spawned.push_back(args.argv(1));
                                out.info("spawned " + args.argv(1));
                                return CommandStatus::success();
                            },
                            [](const CommandArgs& typed, std::string_view) {
                                return typed.argc() == 1 ? Lines{"char_doomguy", "char_marine", "monster_imp"} : Lines{};
                            }});
        console.addCommand({"crash", "", "throws", 0, 0,
                            [](const CommandArgs&, const Output&) -> CommandStatus { throw std::runtime_error("boom"); },
                            {}});
    }

    // A script in a folder of this test's own.
    std::string writeScript(const std::string& name, const std::string& text) {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "af_console" / test->name();
        std::filesystem::create_directories(dir);
        const std::filesystem::path path = dir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }

    double gravity() { return console.cvars().find("g_gravity")->asReal(); }

    CommandSystem console;
    Lines info, errors, spawned;
};

TEST_F(Console, RunsEveryCommandOfTheText) {
    const ExecuteResult result = console.execute("spawn char_doomguy; set g_gravity 500\necho hello  \"big world\"");
    EXPECT_TRUE(result.ok());
    EXPECT_EQ(result.commands, 3u);
    EXPECT_EQ(spawned, Lines{"char_doomguy"});
    EXPECT_EQ(gravity(), 500);
    EXPECT_EQ(info, (Lines{"spawned char_doomguy", "hello big world"}));
}

TEST_F(Console, ACvarNameAlonePrintsItAndWithAValueSetsIt) {
    EXPECT_TRUE(console.execute("G_Gravity 800").ok());
    EXPECT_EQ(gravity(), 800);
    EXPECT_TRUE(console.execute("g_gravity").ok());
    EXPECT_EQ(info, (Lines{"g_gravity = 800", "  real in [0, 10000]; default 1066; changes the simulation",
                           "  gravity, units/s²"}));
}

TEST_F(Console, BadValuesAreErrorsAndChangeNothing) {
    const ExecuteResult result = console.execute("set g_gravity nan\ng_gravity -3\nset g_gravity 1 2");
    EXPECT_EQ(result.errors, 3u);
    EXPECT_EQ(errors, (Lines{"error: 'g_gravity' needs a finite number, not 'nan'",
                             "error: 'g_gravity' must be at least 0, not -3",
                             "error: 'g_gravity' needs a number, not '1 2'"}));
    EXPECT_EQ(gravity(), 1066);
}

TEST_F(Console, UnknownCommandsAreErrorsWithTheNearestName) {
    const ExecuteResult result = console.execute("spwan x\nfrobnicate\nset g_gravty 3");
    EXPECT_EQ(result.errors, 3u);
    EXPECT_EQ(errors, (Lines{"error: unknown command 'spwan'; did you mean 'spawn'?", "error: unknown command 'frobnicate'",
                             "error: unknown cvar 'g_gravty'; did you mean 'g_gravity'?"}));
}

TEST_F(Console, ArgumentCountsAreCheckedBeforeTheHandlerAndQuoteTheUsage) {
    EXPECT_EQ(console.execute("spawn; set g_gravity; reset a b; crash now").errors, 4u);
    EXPECT_EQ(errors, (Lines{"error: 'spawn' takes 1 or more arguments, not 0 (usage: spawn DEF [KEY VALUE]...)",
                             "error: 'set' takes 2 or more arguments, not 1 (usage: set NAME VALUE...)",
                             "error: 'reset' takes 1 argument, not 2 (usage: reset NAME)",
                             "error: 'crash' takes no arguments, not 1 (usage: crash)"}));
    EXPECT_TRUE(spawned.empty());
}

TEST_F(Console, AHandlersFailureAndExceptionAreCountedErrors) {
    const ExecuteResult result = console.execute("spawn a key; crash; echo after");
    EXPECT_EQ(result.errors, 2u);
    EXPECT_EQ(errors, (Lines{"error: a key without a value", "error: 'crash' failed: boom"}));
    EXPECT_EQ(info, Lines{"after"});
}

TEST_F(Console, ToggleResetAndSetaWorkThroughTheConsole) {
    EXPECT_TRUE(console.execute("toggle af_skipSelfCollision; toggle g_gravity 0 1066 300").ok());
    EXPECT_TRUE(console.cvars().find("af_skipSelfCollision")->asBool());
    EXPECT_EQ(gravity(), 300);
    EXPECT_EQ(info, (Lines{"af_skipSelfCollision = 1", "g_gravity = 300"}));
    EXPECT_TRUE(console.execute("reset g_gravity; seta af_skipSelfCollision 0").ok());
    EXPECT_EQ(gravity(), 1066);
    EXPECT_EQ(console.cvars().archive(), "seta af_skipSelfCollision \"0\"\n");
}

TEST_F(Console, HelpShowsAUsageOrACvarsTypeDefaultAndValue) {
    ASSERT_TRUE(console.execute("help SPAWN; set g_gravity 2; help g_gravity").ok());
    EXPECT_EQ(info, (Lines{"usage: spawn DEF [KEY VALUE]...", "  spawns an entity", "g_gravity = 2",
                           "  real in [0, 10000]; default 1066; changes the simulation", "  gravity, units/s²"}));
    EXPECT_EQ(console.execute("help nothing").errors, 1u);
}

TEST_F(Console, ListsAreSortedAndFilteredByPrefix) {
    ASSERT_TRUE(console.execute("cvarlist; cmdlist s").ok());
    EXPECT_EQ(info, (Lines{"af_skipSelfCollision  0", "g_gravity             1066  [simulation]", "2 cvars",
                           "set    sets a cvar; the words after its name are its value",
                           "seta   sets a cvar and marks it archived (see CVarSystem::archive)",
                           "spawn  spawns an entity", "3 commands"}));
}

TEST_F(Console, ScriptErrorsNameTheFileAndLine) {
    const std::string path = writeScript("script.cfg", "set g_gravity 10 // fine\n\nset g_gravity nan\necho \"open\n");
    const ExecuteResult result = console.execute("exec " + path);
    EXPECT_EQ(result.errors, 2u);
    EXPECT_EQ(result.commands, 3u);  // exec and the script's two
    EXPECT_EQ(errors, (Lines{path + ":4:6: error: unterminated quote",
                             path + ":3: error: 'g_gravity' needs a finite number, not 'nan'"}));
    EXPECT_EQ(gravity(), 10);
}

TEST_F(Console, ExecAddsCfgToANameWithoutExtensionAndRefusesMissingFiles) {
    const std::string path = writeScript("gravity.cfg", "set g_gravity 7");
    EXPECT_TRUE(console.execute("exec " + path.substr(0, path.size() - 4)).ok());
    EXPECT_EQ(gravity(), 7);
    EXPECT_EQ(console.execute("exec /nonexistent/x.cfg").errors, 1u);
    EXPECT_EQ(errors, Lines{"error: cannot read script '/nonexistent/x.cfg'"});
}

TEST_F(Console, AScriptThatExecsItselfIsAnErrorNotACrash) {
    const std::string path = writeScript("self.cfg", "echo in\nexec " + writeScript("self.cfg", "") + "\n");
    const ExecuteResult result = console.execute("exec " + path);
    EXPECT_EQ(result.errors, 1u);
    EXPECT_EQ(info.size(), std::size_t(CommandSystem::kMaxExecDepth));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0], path + ":2: error: exec of '" + path + "' nested deeper than 16 scripts (does a script exec itself?)");
}

TEST_F(Console, StrictModeStopsAtTheFirstErrorEvenInsideAScript) {
    console.setStrict(true);
    const std::string path = writeScript("bad.cfg", "set g_gravity 1\nbogus\nset g_gravity 2\n");
    ExecuteResult result = console.execute("exec " + path + "; set g_gravity 3");
    EXPECT_TRUE(result.stopped);
    EXPECT_EQ(result.errors, 1u);
    EXPECT_EQ(gravity(), 1);
    // A syntax error anywhere runs nothing.
    result = console.execute("set g_gravity 5\necho \"open");
    EXPECT_TRUE(result.stopped);
    EXPECT_EQ(result.commands, 0u);
    EXPECT_EQ(gravity(), 1);
}

TEST_F(Console, PlusCommandsRunWithTheirSourceNamed) {
    const PlusCommands plus = parsePlusCommands({"+set", "g_gravity", "12", "+spawn"});
    const ExecuteResult result = console.execute(plus.commands, "command line");
    EXPECT_EQ(result.commands, 2u);
    EXPECT_EQ(gravity(), 12);
    EXPECT_EQ(errors, Lines{"command line: error: 'spawn' takes 1 or more arguments, not 0 (usage: spawn DEF [KEY VALUE]...)"});
}

TEST_F(Console, CompletesNamesThenArguments) {
    EXPECT_EQ(console.complete("s"), (Lines{"set", "seta", "spawn"}));
    EXPECT_EQ(console.complete("echo x; G_"), Lines{"g_gravity"});
    EXPECT_EQ(console.complete("set "), (Lines{"af_skipSelfCollision", "g_gravity"}));
    EXPECT_EQ(console.complete("toggle af_skipSelfCollision "), (Lines{"0", "1"}));
    EXPECT_EQ(console.complete("af_skipSelfCollision "), (Lines{"0", "1"}));
    EXPECT_EQ(console.complete("help sp"), Lines{"spawn"});
    EXPECT_EQ(console.complete("spawn char_"), (Lines{"char_doomguy", "char_marine"}));
    EXPECT_EQ(console.complete("spawn \"MONSTER"), Lines{"monster_imp"});
    EXPECT_TRUE(console.complete("spawn char_doomguy ").empty());
    EXPECT_TRUE(console.complete("unknown ").empty());
}

TEST_F(Console, NamesAreSharedBetweenCommandsAndCvars) {
    EXPECT_THROW(console.addCommand({"G_GRAVITY", "", "", 0, 0, [](const CommandArgs&, const Output&) {
                                         return CommandStatus::success();
                                     },
                                     {}}),
                 std::invalid_argument);
    EXPECT_THROW(console.addCVar(boolCVar("Spawn", false, "")), std::invalid_argument);
    EXPECT_THROW(console.addCommand({"nohandler", "", "", 0, 0, {}, {}}), std::invalid_argument);
}

TEST_F(Console, AReplacedScriptReaderIsUsedByExec) {
    console.setScriptReader([](const std::string& path) -> std::optional<std::string> {
        if (path == "virtual.cfg") return "set g_gravity 42";
        return std::nullopt;
    });
    EXPECT_TRUE(console.execute("exec virtual").ok());
    EXPECT_EQ(gravity(), 42);
}

}  // namespace
}  // namespace af::console
