// Tab completion at af-console's prompt (console_completion.h): body and constraint names where
// an argument names them, the console's own candidates everywhere else.

#include "console_completion.h"

#include <gtest/gtest.h>

namespace af::console {
namespace {

using Names = std::vector<std::string>;

struct CompletionConsole {
    CommandSystem commands;
    Session session{{AF_SOURCE_DIR}, commands};
    CompletionConsole() { EXPECT_TRUE(commands.execute("spawn ragdoll_humanoid\nspawn af_lamp origin \"200 0 60\" name lamp", "test.cfg").ok()); }
    Names complete(std::string_view line) const { return completeConsoleLine(commands, session, line); }
};

TEST(ConsoleCompletion, DragCompletesTheNamedEntitysBodies) {
    CompletionConsole c;
    EXPECT_EQ(c.complete("drag ragdoll_humanoid_1 rh"), (Names{"rhand"}));
    EXPECT_EQ(c.complete("drag RAGDOLL_HUMANOID_1 l").size(), 6u) << "luparm, lloarm, lhand, lthigh, lshin, lfoot";
    EXPECT_EQ(c.complete("drag lamp ").size(), c.session.bodyNames("lamp").size());
    EXPECT_TRUE(c.complete("drag nobody ").empty());
    EXPECT_TRUE(c.complete("drag ragdoll_humanoid_1 rhand ").empty()) << "coordinates follow the body";
    EXPECT_EQ(c.complete("drag rag"), (Names{"ragdoll_humanoid_1"})) << "the entity, as before";
}

TEST(ConsoleCompletion, HighlightCvarsCompleteEveryRagdollsBodiesAndConstraints) {
    CompletionConsole c;
    EXPECT_EQ(c.complete("af_highlightBody rh"), (Names{"rhand"}));
    EXPECT_EQ(c.complete("set af_highlightBody rha"), (Names{"rhand"}));
    EXPECT_EQ(c.complete("af_highlightConstraint rk"), (Names{"rknee"}));
    const Names all = c.complete("seta af_highlightBody ");
    EXPECT_EQ(all.size(), c.session.bodyNames("ragdoll_humanoid_1").size() + c.session.bodyNames("lamp").size());
    EXPECT_TRUE(std::is_sorted(all.begin(), all.end()));
}

TEST(ConsoleCompletion, OtherWordsCompleteAsTheConsoleCompletesThem) {
    CompletionConsole c;
    for (const char* line : {"", "af_show", "set af_showM", "af_showMass ", "spawn rag", "help dr", "list "})
        EXPECT_EQ(c.complete(line), c.commands.complete(line)) << line;
}

}  // namespace
}  // namespace af::console
