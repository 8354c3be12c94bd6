#include "af/text/lexer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace af {
namespace {

std::vector<Token> lexAll(std::string_view text, Diagnostics& d) {
    Lexer lexer(text, d);
    std::vector<Token> out;
    for (Token t = lexer.next(); t.type != TokenType::End; t = lexer.next()) out.push_back(t);
    return out;
}

std::vector<Token> lexClean(std::string_view text) {
    Diagnostics d("t");
    std::vector<Token> out = lexAll(text, d);
    EXPECT_EQ(d.formatAll(), "") << "for input: " << text;
    return out;
}

TEST(Lexer, SlashAfterANameIsPartOfIt) {
    // With path names allowed, idLexer reads `b/` as one name; only `//` and `/*` open comments.
    const auto t = lexClean("b/**/c");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].text, "b/");
    EXPECT_EQ(t[3].text, "/c");
}

TEST(Lexer, PathNamesAreOneName) {
    const auto t = lexClean("models/humanoid/x.md5mesh \\win\\path .hidden");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].type, TokenType::Name);
    EXPECT_EQ(t[0].text, "models/humanoid/x.md5mesh");
    EXPECT_EQ(t[1].text, "\\win\\path");
    EXPECT_EQ(t[2].text, ".hidden");
}

TEST(Lexer, StringsHaveNoEscapesAndLiteralsAreNotStrings) {
    const auto t = lexClean(R"("a\n" 'lit' "")");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].type, TokenType::String);
    EXPECT_EQ(t[0].text, "a\\n");
    EXPECT_EQ(t[1].type, TokenType::Literal);
    EXPECT_EQ(t[1].text, "lit");
    EXPECT_EQ(t[2].type, TokenType::String);
    EXPECT_EQ(t[2].text, "");
}

TEST(Lexer, BackslashJoinsTwoStrings) {
    Diagnostics d;
    Lexer lexer("\"ab\" \\\n \"cd\" next \"x\" \\ y", d);  // a joined string lives in its lexer
    const Token joined = lexer.next();
    EXPECT_EQ(joined.type, TokenType::String);
    EXPECT_EQ(joined.text, "abcd");
    const Token next = lexer.next();
    EXPECT_EQ(next.text, "next");
    EXPECT_EQ(next.where.line, 2);
    EXPECT_EQ(lexer.next().text, "x");
    EXPECT_EQ(lexer.next().text, "\\");  // a backslash not followed by a string stays
    EXPECT_EQ(lexer.next().text, "y");
    EXPECT_FALSE(d.hasErrors());
}

TEST(Lexer, NumbersCarryNoSign) {
    const auto t = lexClean("-5");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_TRUE(t[0].isPunctuation("-"));
    EXPECT_EQ(t[1].type, TokenType::Number);
    EXPECT_EQ(t[1].numberValue(), 5.0);
}

TEST(Lexer, NumberKindsAndValuesFollowIdLexer) {
    const auto t = lexClean("42 1. .5 0.25 1e5 2.5e-3 3 010 0x1F 0b101 7u 0");
    ASSERT_EQ(t.size(), 12u);
    const NumberKind kinds[] = {NumberKind::Integer, NumberKind::Float, NumberKind::Float, NumberKind::Float,
                                NumberKind::Float,   NumberKind::Float, NumberKind::Integer, NumberKind::Octal,
                                NumberKind::Hex,     NumberKind::Binary, NumberKind::Integer, NumberKind::Integer};
    const double values[] = {42, 1, 0.5, 0.25, 1e5, 2.5e-3, 3, 8, 31, 5, 7, 0};
    for (std::size_t i = 0; i < t.size(); ++i) {
        EXPECT_EQ(t[i].type, TokenType::Number) << i;
        EXPECT_EQ(t[i].numberKind, kinds[i]) << t[i].text;
        EXPECT_EQ(t[i].numberValue(), values[i]) << t[i].text;
    }
}

TEST(Lexer, FloatSuffixIsEatenButNotAfterIntegers) {
    const auto t = lexClean("1.5f 2.f 3f");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[2].numberKind, NumberKind::Integer);
    EXPECT_EQ(t[3].text, "f");
    EXPECT_EQ(t[0].numberValue(), 1.5);
    EXPECT_EQ(t[0].numberKind, NumberKind::Float);
    EXPECT_EQ(t[1].numberValue(), 2.0);
}

TEST(Lexer, ZeroPaddedEightIsTwoTokens) {
    const auto t = lexClean("08");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].text, "0");
    EXPECT_EQ(t[0].numberValue(), 0.0);
    EXPECT_EQ(t[1].text, "8");
}

TEST(Lexer, SpecialFloatsAreRecognised) {
    const auto t = lexClean("1.#INF 1.#QNAN");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].numberKind, NumberKind::SpecialFloat);
    EXPECT_TRUE(std::isinf(t[0].numberValue()));
    EXPECT_TRUE(std::isnan(t[1].numberValue()));
}

TEST(Lexer, PunctuationIsLongestMatch) {
    const auto t = lexClean("->>>=-(,){}");
    std::vector<std::string_view> texts;
    for (const Token& k : t) texts.push_back(k.text);
    EXPECT_EQ(texts, (std::vector<std::string_view>{"->", ">>=", "-", "(", ",", ")", "{", "}"}));
}

TEST(Lexer, CommentsAreSkipped) {
    const auto t = lexClean("a // line comment\n/* block\n comment */ b /**/ c");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[1].text, "b");
    EXPECT_EQ(t[1].where.line, 3);
    EXPECT_EQ(t[2].text, "c");
}

TEST(Lexer, PositionsCountCrLfLoneCrAndTabsAsOneColumn) {
    const auto t = lexClean("a\r\n\tb\rc\n  d");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].where, (SourceLocation{1, 1}));
    EXPECT_EQ(t[1].where, (SourceLocation{2, 2}));
    EXPECT_EQ(t[2].where, (SourceLocation{3, 1}));
    EXPECT_EQ(t[3].where, (SourceLocation{4, 3}));
}

TEST(Lexer, ControlBytesAndTrailingNulAreWhiteSpace) {
    const std::string text("a\x01\x1f" "b\0", 5);
    const auto t = lexClean(text);
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[1].text, "b");
}

TEST(Lexer, UnterminatedStringIsAnError) {
    Diagnostics d("f.af");
    const auto t = lexAll("x \"abc", d);
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[1].type, TokenType::Invalid);
    EXPECT_EQ(d.formatAll(), "f.af:1:3: error: missing closing quote\n");
}

TEST(Lexer, NewlineInsideStringIsAnError) {
    Diagnostics d("f.af");
    lexAll("\"ab\ncd\"", d);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(d.all()[0].format(), "f.af:1:1: error: newline inside a quoted string");
}

TEST(Lexer, TwoDotsInANumberIsAnError) {
    Diagnostics d("f.af");
    const auto t = lexAll("  1.2.3", d);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_EQ(t[0].type, TokenType::Invalid);
    EXPECT_EQ(d.formatAll(), "f.af:1:3: error: more than one dot in number '1.2.3'\n");
}

TEST(Lexer, UnclosedBlockCommentIsAnError) {
    Diagnostics d("f.af");
    lexAll("a\n /* never closed", d);
    EXPECT_EQ(d.formatAll(), "f.af:2:2: error: comment opened here is never closed with '*/'\n");
}

TEST(Lexer, NestedCommentOpenerWarns) {
    Diagnostics d("f.af");
    lexAll("/* a /* b */ c", d);
    EXPECT_FALSE(d.hasErrors());
    ASSERT_EQ(d.warningCount(), 1u);
    EXPECT_EQ(d.all()[0].where, (SourceLocation{1, 6}));
}

TEST(Lexer, StrayByteIsAnErrorAndLexingGoesOn) {
    Diagnostics d("f.af");
    const auto t = lexAll("a \x80 b", d);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[1].type, TokenType::Invalid);
    EXPECT_EQ(t[2].text, "b");
    EXPECT_EQ(d.formatAll(), "f.af:1:3: error: unexpected character (byte 0x80)\n");
}

TEST(Lexer, EndRepeatsAtEndOfInput) {
    Diagnostics d;
    Lexer lexer("x", d);
    EXPECT_EQ(lexer.next().type, TokenType::Name);
    EXPECT_EQ(lexer.next().type, TokenType::End);
    EXPECT_EQ(lexer.next().type, TokenType::End);
}

}  // namespace
}  // namespace af
