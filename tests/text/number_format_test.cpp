#include "af/text/lexer.h"
#include "af/text/number_format.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>

namespace af {
namespace {

TEST(NumberFormat, MatchesDoomEditorSpelling) {
    EXPECT_EQ(formatDeclFloat(0.2), "0.200000003");
    EXPECT_EQ(formatDeclFloat(0.01), "0.0099999998");
    EXPECT_EQ(formatDeclFloat(0.8), "0.8000000119");
    EXPECT_EQ(formatDeclFloat(0.5), "0.5");
    EXPECT_EQ(formatDeclFloat(10), "10");
    EXPECT_EQ(formatDeclFloat(-10), "-10");
    EXPECT_EQ(formatDeclFloat(-0.0), "-0");
    EXPECT_EQ(formatDeclFloat(1.57), "1.5700000525");
}

TEST(NumberFormat, TinyValuesFallBackToExponentForm) {
    EXPECT_EQ(formatDeclFloat(1e-12), "1e-12");
}

// Whatever the writer prints, the lexer must read back as the very same float.
TEST(NumberFormat, EveryFloatReadsBackExactly) {
    std::mt19937 rng(12345);
    std::uniform_int_distribution<std::uint32_t> bits;
    int checked = 0;
    while (checked < 20000) {
        const std::uint32_t b = bits(rng);
        float f;
        std::memcpy(&f, &b, sizeof f);
        if (!std::isfinite(f)) continue;
        ++checked;
        std::string text = formatDeclFloat(f);
        const bool negative = text[0] == '-';
        Diagnostics d;
        Lexer lexer(negative ? std::string_view(text).substr(1) : std::string_view(text), d);
        const Token t = lexer.next();
        ASSERT_EQ(t.type, TokenType::Number) << text;
        ASSERT_EQ(lexer.next().type, TokenType::End) << text;
        const float back = static_cast<float>(negative ? -t.numberValue() : t.numberValue());
        ASSERT_EQ(std::memcmp(&back, &f, sizeof f), 0) << text << " for " << f;
    }
}

}  // namespace
}  // namespace af
