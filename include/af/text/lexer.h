#pragma once
// An idLexer-compatible tokenizer for Doom 3 decl text (.af, .def, .md5mesh, .md5anim, .map).
//
// The rules, as idLexer applies them with the decl flags (docs/formats.md §1.2):
//  * every byte <= 0x20 is white space (so "\r\n", a lone "\r" and a trailing NUL are too);
//    comments are `// ...` and `/* ... */` (they do not nest);
//  * strings are "..." with no escapes; '...' is a literal; `"a" \ "b"` joins two strings;
//  * names start with a letter, `_`, `/`, `\` or a `.` not followed by a digit, and go on with
//    letters, digits, `_`, `/`, `\`, `:` and `.`, so `models/x.md5mesh` is one name;
//  * numbers never carry a sign (`-` is punctuation): decimal integers, floats (`1.`, `.5`,
//    `1e5`, suffixes f/F/l/L), octal after a leading 0 (`010` is 8, `08` is `0` then `8`), hex
//    `0x..`, binary `0b..`, and the special floats `1.#INF`, `1.#IND`, `1.#NAN`, `1.#QNAN`;
//  * punctuation is the longest match over the C/C++ operators.
// Every token knows its line and column. Lexical errors are reported to the Diagnostics and
// come out as an Invalid token, so a parser stops there without reporting the same thing twice.

#include "af/text/diagnostics.h"

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>

namespace af {

enum class TokenType : std::uint8_t { End, String, Literal, Number, Name, Punctuation, Invalid };

enum class NumberKind : std::uint8_t { Integer, Float, Octal, Hex, Binary, SpecialFloat };

struct Token {
    TokenType type = TokenType::End;
    NumberKind numberKind = NumberKind::Integer;
    // The spelling: strings and literals without their quotes, numbers with their suffix.
    std::string_view text;
    SourceLocation where;

    bool isPunctuation(std::string_view p) const { return type == TokenType::Punctuation && text == p; }
    // A name token equal to `keyword`, ignoring ASCII case.
    bool isKeyword(std::string_view keyword) const;
    // An integer spelled without a fraction or exponent (decimal, octal, hex or binary).
    bool isInteger() const { return type == TokenType::Number && numberKind != NumberKind::Float &&
                                    numberKind != NumberKind::SpecialFloat; }
    // The value of a Number token, in double precision (inf or NaN for the special floats).
    double numberValue() const;
};

// At most this many characters of a file's own text are quoted in a message. A file that is
// not of the expected format (a binary, a system file named by a hostile decl) must not be
// echoed into logs: a diagnostic shows a short, printable token of it, never its content
// (docs/formats.md §1.3).
inline constexpr std::size_t kMaxQuotedChars = 32;

// `text` as a message may show it: every byte outside printable ASCII as `?`, and anything
// beyond kMaxQuotedChars cut off and marked with `...`.
std::string printableExcerpt(std::string_view text);

// How a token reads in a message: 'name', "string", end of file; its text as printableExcerpt.
std::string describe(const Token& token);

class Lexer {
public:
    // `source` must outlive the lexer and its tokens; a string joined with `\\` lives in the
    // lexer itself, so tokens must not outlive the lexer either.
    Lexer(std::string_view source, Diagnostics& diagnostics);

    // The next token; TokenType::End at the end of the text (and from then on).
    Token next();

private:
    void skipWhiteSpace();
    void newLine(const char* lineEnd);
    Token readString(const char* start, char quote);
    bool quotedRun(char quote, std::string* joined);
    Token readName(const char* start);
    Token readNumber(const char* start);
    Token readPunctuation(const char* start);
    Token make(TokenType type, const char* start, const char* stop) const;
    Token invalid(const char* start, const char* stop, std::string message);
    SourceLocation locate(const char* at) const;

    const char* p_;
    const char* end_;
    const char* lineStart_;
    int line_ = 1;
    Diagnostics& diagnostics_;
    std::deque<std::string> joinedStrings_;  // storage for strings joined with `\`
};

}  // namespace af
