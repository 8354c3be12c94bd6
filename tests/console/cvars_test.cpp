#include "console/cvars.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace af::console {
namespace {

// A console with the cvars of docs/doom-physics.md §4.13 that the tests need.
struct Cvars : ::testing::Test {
    Cvars() {
        auto gravity = realCVar("g_gravity", 1066, {0, 10000}, "gravity, units/s²", CVarFlags::Simulation);
        gravity.onChange = [this](const CVar& cvar) { applied.push_back(cvar.asReal()); };
        cvars.add(std::move(gravity));
        cvars.add(boolCVar("af_skipSelfCollision", false, "no self collision"));
        cvars.add(intCVar("af_steps", 4, {1, {}}, "substeps"));
        cvars.add(stringCVar("af_solver", "tree", "the primary solver", {"tree", "exact"}));
        cvars.add(stringCVar("af_label", "", "any text"));
        cvars.add(intCVar("af_version", 1, {}, "read-only", CVarFlags::ReadOnly));
    }
    CVarSystem cvars;
    std::vector<double> applied;
};

TEST_F(Cvars, AreFoundIgnoringCaseAndKeepTheirSpelling) {
    const CVar* cvar = cvars.find("G_GRAVITY");
    ASSERT_NE(cvar, nullptr);
    EXPECT_EQ(cvar->name(), "g_gravity");
    EXPECT_EQ(cvar->type(), CVarType::Real);
    EXPECT_EQ(cvars.find("g_gravit"), nullptr);
}

TEST_F(Cvars, SetParsesTheTypeAndCallsTheOwnerOnce) {
    EXPECT_TRUE(cvars.set("g_gravity", "500.5").ok());
    EXPECT_TRUE(cvars.set("g_gravity", "+500.5").ok());  // the same value: no change, no call
    EXPECT_EQ(applied, std::vector<double>{500.5});
    EXPECT_TRUE(cvars.set("af_steps", "12").ok());
    EXPECT_EQ(cvars.find("af_steps")->asInt(), 12);
    EXPECT_TRUE(cvars.set("af_skipSelfCollision", "TRUE").ok());
    EXPECT_TRUE(cvars.find("af_skipSelfCollision")->asBool());
    EXPECT_TRUE(cvars.set("af_solver", "EXACT").ok());
    EXPECT_EQ(cvars.find("af_solver")->asString(), "exact");  // spelt as the allowed value
}

TEST_F(Cvars, NonFiniteNumbersAreRefusedAndTheValueKept) {
    for (const char* text : {"nan", "NaN", "inf", "-inf", "infinity", "1e999"}) {
        const Status status = cvars.set("g_gravity", text);
        EXPECT_FALSE(status.ok()) << text;
        EXPECT_NE(status.message().find("finite"), std::string::npos) << status.message();
    }
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 1066);
    EXPECT_TRUE(applied.empty());
}

TEST_F(Cvars, ValuesOutsideTheRangeAreRefusedWithTheBound) {
    Status status = cvars.set("g_gravity", "-1");
    EXPECT_EQ(status.message(), "'g_gravity' must be at least 0, not -1");
    status = cvars.set("g_gravity", "10000.5");
    EXPECT_EQ(status.message(), "'g_gravity' must be at most 10000, not 10000.5");
    EXPECT_FALSE(cvars.set("af_steps", "0").ok());
    EXPECT_TRUE(cvars.set("g_gravity", "10000").ok());  // bounds are inclusive
    EXPECT_EQ(cvars.find("af_steps")->asInt(), 4);
}

TEST_F(Cvars, TextThatIsNotAValueOfTheTypeIsRefused) {
    EXPECT_EQ(cvars.set("af_steps", "1.5").message(), "'af_steps' needs an integer, not '1.5'");
    EXPECT_EQ(cvars.set("af_steps", "99999999999999999999").message(), "'af_steps' cannot hold '99999999999999999999'");
    EXPECT_EQ(cvars.set("g_gravity", "12abc").message(), "'g_gravity' needs a number, not '12abc'");
    EXPECT_EQ(cvars.set("g_gravity", "").message(), "'g_gravity' needs a number, not ''");
    EXPECT_EQ(cvars.set("af_skipSelfCollision", "yes").message(),
              "'af_skipSelfCollision' needs 0, 1, true or false, not 'yes'");
    EXPECT_EQ(cvars.set("af_solver", "pgs").message(), "'af_solver' must be one of tree, exact, not 'pgs'");
    EXPECT_FALSE(cvars.set("af_label", "a\"b").ok());
    EXPECT_EQ(cvars.set("nope", "1").message(), "unknown cvar 'nope'");
    EXPECT_EQ(cvars.find("af_solver")->text(), "tree");
}

TEST_F(Cvars, ReadOnlyCvarsChangeOnlyThroughTheirOwner) {
    EXPECT_EQ(cvars.set("af_version", "2").message(), "'af_version' is read-only");
    EXPECT_FALSE(cvars.reset("af_version").ok());
    EXPECT_TRUE(cvars.set("af_version", "2", CVarSystem::Access::Owner).ok());
    EXPECT_EQ(cvars.find("af_version")->asInt(), 2);
}

TEST_F(Cvars, ToggleFlipsBoolsAndTurnsNumbersBetweenZeroAndOne) {
    EXPECT_TRUE(cvars.toggle("af_skipSelfCollision", {}).ok());
    EXPECT_TRUE(cvars.find("af_skipSelfCollision")->asBool());
    EXPECT_TRUE(cvars.toggle("af_skipSelfCollision", {}).ok());
    EXPECT_FALSE(cvars.find("af_skipSelfCollision")->asBool());
    // Doom's `toggle NAME VALUE`: between 0 and VALUE.
    EXPECT_TRUE(cvars.toggle("g_gravity", {"500"}).ok());
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 0);
    EXPECT_TRUE(cvars.toggle("g_gravity", {"500"}).ok());
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 500);
    EXPECT_FALSE(cvars.toggle("af_solver", {}).ok());  // a string needs values to cycle through
}

TEST_F(Cvars, ToggleWithValuesCyclesAndStartsOverFromAnUnlistedValue) {
    EXPECT_TRUE(cvars.toggle("af_label", {"a", "b", "c"}).ok());  // "" is not listed: the first
    EXPECT_EQ(cvars.find("af_label")->text(), "a");
    EXPECT_TRUE(cvars.toggle("af_label", {"a", "b", "c"}).ok());
    EXPECT_EQ(cvars.find("af_label")->text(), "b");
    EXPECT_TRUE(cvars.toggle("af_label", {"a", "b", "c"}).ok());
    EXPECT_TRUE(cvars.toggle("af_label", {"a", "b", "c"}).ok());
    EXPECT_EQ(cvars.find("af_label")->text(), "a");
    // Numbers match by value, so 1066 is found as "1066.0".
    EXPECT_TRUE(cvars.toggle("g_gravity", {"0", "1066.0", "300"}).ok());
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 300);
    // A value that does not fit is refused when its turn comes, and nothing changes.
    EXPECT_FALSE(cvars.toggle("g_gravity", {"300", "-5"}).ok());
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 300);
}

TEST_F(Cvars, ResetReturnsToTheDefaultAndCallsTheOwner) {
    ASSERT_TRUE(cvars.set("g_gravity", "0").ok());
    ASSERT_TRUE(cvars.reset("g_gravity").ok());
    EXPECT_EQ(cvars.find("g_gravity")->asReal(), 1066);
    EXPECT_EQ(applied, (std::vector<double>{0, 1066}));
}

TEST_F(Cvars, ListIsSortedByNameAndFilteredByPrefixIgnoringCase) {
    std::vector<std::string> names;
    for (const CVar* cvar : cvars.list("AF_S")) names.push_back(cvar->name());
    EXPECT_EQ(names, (std::vector<std::string>{"af_skipSelfCollision", "af_solver", "af_steps"}));
    EXPECT_EQ(cvars.list().size(), 6u);
    EXPECT_TRUE(cvars.list("x").empty());
}

TEST_F(Cvars, RealsPrintAsTheShortestTextThatReadsBack) {
    ASSERT_TRUE(cvars.set("g_gravity", "0.1").ok());
    EXPECT_EQ(cvars.find("g_gravity")->text(), "0.1");
    ASSERT_TRUE(cvars.set("g_gravity", "1e-12").ok());
    EXPECT_EQ(cvars.find("g_gravity")->text(), "1e-12");
    EXPECT_EQ(cvars.find("g_gravity")->defaultText(), "1066");
    EXPECT_EQ(cvars.find("g_gravity")->describeType(), "real in [0, 10000]");
    EXPECT_EQ(cvars.find("af_steps")->describeType(), "integer, at least 1");
}

TEST_F(Cvars, ArchiveWritesAScriptOfTheArchivedCvars) {
    cvars.markArchived(*cvars.find("af_solver"));
    cvars.markArchived(*cvars.find("af_label"));
    ASSERT_TRUE(cvars.set("af_label", "two words").ok());
    EXPECT_EQ(cvars.archive(), "seta af_label \"two words\"\nseta af_solver \"tree\"\n");
}

TEST(CvarDefinitions, BadDefinitionsAreProgrammingErrors) {
    CVarSystem cvars;
    cvars.add(boolCVar("a", true, ""));
    EXPECT_THROW(cvars.add(boolCVar("A", true, "")), std::invalid_argument);  // names ignore case
    EXPECT_THROW(cvars.add(boolCVar("two words", true, "")), std::invalid_argument);
    EXPECT_THROW(cvars.add(boolCVar("9lives", true, "")), std::invalid_argument);
    EXPECT_THROW(cvars.add(realCVar("r", 5, {0, 1}, "")), std::invalid_argument);
    EXPECT_THROW(cvars.add(realCVar("r", 0.5, {1, 0}, "")), std::invalid_argument);
    EXPECT_THROW(cvars.add(realCVar("r", std::nan(""), {}, "")), std::invalid_argument);
    EXPECT_THROW(cvars.add(stringCVar("s", "c", "", {"a", "b"})), std::invalid_argument);
    EXPECT_EQ(cvars.list().size(), 1u);
}

TEST(CvarValues, AStringCvarHasNoNumber) {
    const CVar label(stringCVar("label", "x", ""));
    EXPECT_THROW((void)label.asReal(), std::logic_error);
    const CVar steps(intCVar("steps", 3, {}, ""));
    EXPECT_THROW((void)steps.asString(), std::logic_error);
    EXPECT_EQ(steps.asReal(), 3);
}

}  // namespace
}  // namespace af::console
