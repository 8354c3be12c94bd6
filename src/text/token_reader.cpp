#include "token_reader.h"

#include <cmath>
#include <limits>

namespace af {

TokenReader::TokenReader(std::string_view text, Diagnostics& diagnostics)
    : lexer_(text, diagnostics), diagnostics_(diagnostics), lookahead_(lexer_.next()) {}

Token TokenReader::next() {
    Token t = lookahead_;
    if (t.type != TokenType::End) lookahead_ = lexer_.next();
    if (t.type == TokenType::Punctuation) {
        if (t.text == "{") ++depth_;
        else if (t.text == "}") --depth_;
    }
    return t;
}

void TokenReader::fail(const Token& found, std::string_view expected) {
    if (found.type != TokenType::Invalid)
        diagnostics_.error(found.where, "expected " + std::string(expected) + ", found " + describe(found));
    throw ParseAbort{};
}

void TokenReader::expectPunctuation(std::string_view punctuation, std::string_view context) {
    const Token t = next();
    if (t.isPunctuation(punctuation)) return;
    std::string expected = "'" + std::string(punctuation) + "'";
    if (!context.empty()) expected += " " + std::string(context);
    fail(t, expected);
}

bool TokenReader::acceptPunctuation(std::string_view punctuation) {
    if (!lookahead_.isPunctuation(punctuation)) return false;
    next();
    return true;
}

Token TokenReader::expectString(std::string_view what) {
    const Token t = next();
    if (t.type != TokenType::String) fail(t, std::string(what) + " in double quotes");
    return t;
}

Real TokenReader::readFloat(std::string_view what, SourceLocation* where) {
    Token t = next();
    if (where) *where = t.where;
    const bool negative = t.isPunctuation("-");
    if (negative) t = next();
    if (t.type != TokenType::Number) fail(t, "a number for " + std::string(what));
    if (t.numberKind == NumberKind::SpecialFloat) {
        diagnostics_.error(t.where, std::string(what) + " must be a finite number, found '" + printableExcerpt(t.text) + "'");
        return std::numeric_limits<Real>::quiet_NaN();
    }
    const float value = static_cast<float>(t.numberValue());
    if (!std::isfinite(value)) {
        diagnostics_.error(t.where, std::string(what) + " is out of range for a 32-bit float, found '" +
                                        printableExcerpt(t.text) + "'");
        return std::numeric_limits<Real>::quiet_NaN();
    }
    return negative ? -Real(value) : Real(value);
}

int TokenReader::readInt(std::string_view what, SourceLocation* where) {
    Token t = next();
    if (where) *where = t.where;
    const bool negative = t.isPunctuation("-");
    if (negative) t = next();
    if (t.type != TokenType::Number) fail(t, "an integer for " + std::string(what));
    const double value = t.numberValue();
    if (!t.isInteger())
        diagnostics_.error(t.where, "expected an integer for " + std::string(what) + ", found '" +
                                        printableExcerpt(t.text) + "'");
    if (!(value <= std::numeric_limits<int>::max())) {
        diagnostics_.error(t.where, std::string(what) + " is out of range, found '" + printableExcerpt(t.text) + "'");
        return 0;
    }
    const int truncated = static_cast<int>(value);
    return negative ? -truncated : truncated;
}

bool TokenReader::readBool(std::string_view what) {
    const Token t = next();
    if (t.type != TokenType::Number) fail(t, "0 or 1 for " + std::string(what));
    return t.numberValue() != 0;
}

void TokenReader::skipToDepth(int depth) {
    while (depth_ > depth && !atEnd()) next();
}

}  // namespace af
