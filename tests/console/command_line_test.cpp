#include "console/command_line.h"

#include <gtest/gtest.h>

namespace af::console {
namespace {

using Words = std::vector<std::string>;

std::vector<Words> wordsOf(const SplitResult& split) {
    std::vector<Words> out;
    for (const CommandText& command : split.commands) out.push_back(command.words);
    return out;
}

TEST(CommandLine, SemicolonsAndLineBreaksSeparateCommands) {
    const SplitResult split = splitCommands("set a 1; set b 2\r\necho x\rreset a\n\n;;");
    EXPECT_TRUE(split.ok());
    EXPECT_EQ(wordsOf(split), (std::vector<Words>{{"set", "a", "1"}, {"set", "b", "2"}, {"echo", "x"}, {"reset", "a"}}));
    EXPECT_EQ(split.commands[1].where, (SourceLocation{1, 10}));
    EXPECT_EQ(split.commands[3].where, (SourceLocation{3, 1}));
}

TEST(CommandLine, QuotesKeepSpacesSemicolonsAndSlashes) {
    const SplitResult split = splitCommands("echo \"a b; c // d\" \"\" x\"y z\"w");
    ASSERT_TRUE(split.ok());
    EXPECT_EQ(wordsOf(split), (std::vector<Words>{{"echo", "a b; c // d", "", "xy zw"}}));
}

TEST(CommandLine, CommentsRunToTheEndOfTheLineAndHideSemicolons) {
    const SplitResult split = splitCommands("// a whole line\necho a // b; echo c\necho d//e");
    ASSERT_TRUE(split.ok());
    EXPECT_EQ(wordsOf(split), (std::vector<Words>{{"echo", "a"}, {"echo", "d"}}));
}

TEST(CommandLine, AnUnterminatedQuoteIsAnErrorAtItsColumnAndDropsOnlyItsLine) {
    const SplitResult split = splitCommands("echo ok\nset a 1; echo \"b c\n\"x\"; echo \"y");
    ASSERT_EQ(split.errors.size(), 2u);
    EXPECT_EQ(split.errors[0].where, (SourceLocation{2, 15}));
    EXPECT_EQ(split.errors[0].message, "unterminated quote");
    EXPECT_EQ(split.errors[1].where, (SourceLocation{3, 11}));
    EXPECT_EQ(wordsOf(split), (std::vector<Words>{{"echo", "ok"}}));
}

TEST(CommandLine, ControlCharactersSeparateWords) {
    const SplitResult split = splitCommands(std::string("echo\ta\0b", 8));
    EXPECT_EQ(wordsOf(split), (std::vector<Words>{{"echo", "a", "b"}}));
}

TEST(CommandLine, CompletionSeesTheLastCommandAndTheWordAtTheCursor) {
    PartialCommand p = splitForCompletion("echo x; set g_gr");
    EXPECT_EQ(p.words, (Words{"set"}));
    EXPECT_EQ(p.partial, "g_gr");
    p = splitForCompletion("set g_gravity ");
    EXPECT_EQ(p.words, (Words{"set", "g_gravity"}));
    EXPECT_EQ(p.partial, "");
    p = splitForCompletion("exec \"my fi");
    EXPECT_EQ(p.words, (Words{"exec"}));
    EXPECT_EQ(p.partial, "my fi");
    p = splitForCompletion("first line\nse");
    EXPECT_TRUE(p.words.empty());
    EXPECT_EQ(p.partial, "se");
}

TEST(CommandLine, PlusArgumentsStartCommandsAsInDoom) {
    const PlusCommands parsed =
        parsePlusCommands({"--map", "x.map", "+set", "g_gravity", "0", "+exec", "a.cfg", "+", "+toggle", "+b"});
    EXPECT_EQ(parsed.leading, (Words{"--map", "x.map"}));
    ASSERT_EQ(parsed.commands.size(), 5u);
    EXPECT_EQ(parsed.commands[0].words, (Words{"set", "g_gravity", "0"}));
    EXPECT_EQ(parsed.commands[1].words, (Words{"exec", "a.cfg"}));
    EXPECT_EQ(parsed.commands[2].words, (Words{""}));  // reported as an unknown command when run
    EXPECT_EQ(parsed.commands[3].words, (Words{"toggle"}));
    EXPECT_EQ(parsed.commands[4].words, (Words{"b"}));
    EXPECT_EQ(parsed.commands[0].where, SourceLocation{});
}

}  // namespace
}  // namespace af::console
