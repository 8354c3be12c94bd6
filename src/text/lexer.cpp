#include "af/text/lexer.h"

#include "af/text/strings.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace af {

namespace {

// Character classes, looked up once per byte on the hot path.
enum : std::uint8_t { kSpace = 1, kNameStart = 2, kNameChar = 4, kDigit = 8 };

constexpr std::array<std::uint8_t, 256> makeClasses() {
    std::array<std::uint8_t, 256> t{};
    for (int c = 0; c <= 0x20; ++c) t[c] = kSpace;
    for (int c = 'a'; c <= 'z'; ++c) t[c] = kNameStart | kNameChar;
    for (int c = 'A'; c <= 'Z'; ++c) t[c] = kNameStart | kNameChar;
    for (int c = '0'; c <= '9'; ++c) t[c] = kNameChar | kDigit;
    t['_'] = kNameStart | kNameChar;
    // Path names: `models/x.md5mesh` is one name.
    t['/'] = kNameStart | kNameChar;
    t['\\'] = kNameStart | kNameChar;
    t['.'] = kNameStart | kNameChar;
    t[':'] = kNameChar;
    return t;
}
constexpr std::array<std::uint8_t, 256> kClass = makeClasses();

bool has(char c, std::uint8_t cls) { return (kClass[static_cast<unsigned char>(c)] & cls) != 0; }

// The operators of C and C++. Single characters first: the brackets and commas that make up
// most of a decl never reach the longer lists.
constexpr std::string_view kPunctuation1 = "*/%+-=&|^~!><.,;:?(){}[]\\#$@";
constexpr std::string_view kMultiStart = "><.&|=!*/%+-^:#";  // first characters of longer operators
constexpr std::string_view kPunctuation3[] = {">>=", "<<=", "..."};
constexpr std::string_view kPunctuation2[] = {"&&", "||", ">=", "<=", "==", "!=", "*=", "/=", "%=", "+=",
                                             "-=", "++", "--", "&=", "|=", "^=", ">>", "<<", "->", "::",
                                             ".*", "##", "#@"};

std::uint64_t parseDigits(std::string_view digits, unsigned base) {
    std::uint64_t value = 0;
    for (char c : digits) {
        unsigned d = (c >= '0' && c <= '9') ? unsigned(c - '0') : unsigned((c | 0x20) - 'a' + 10);
        value = value * base + d;
    }
    return value;
}

}  // namespace

bool Token::isKeyword(std::string_view keyword) const {
    return type == TokenType::Name && equalsIgnoreCase(text, keyword);
}

double Token::numberValue() const {
    std::string_view digits = text;
    while (!digits.empty() && !has(digits.back(), kDigit) && numberKind != NumberKind::Hex &&
           numberKind != NumberKind::SpecialFloat && digits.back() != '.')
        digits.remove_suffix(1);  // the u/l/f suffixes
    switch (numberKind) {
    case NumberKind::Octal: return double(parseDigits(digits, 8));
    case NumberKind::Hex: {
        while (!digits.empty() && (digits.back() == 'u' || digits.back() == 'U' || digits.back() == 'l' ||
                                   digits.back() == 'L'))
            digits.remove_suffix(1);
        return double(parseDigits(digits.substr(2), 16));
    }
    case NumberKind::Binary: return double(parseDigits(digits.substr(2), 2));
    case NumberKind::SpecialFloat: {
        const std::size_t hash = text.find('#');
        const std::string_view word = text.substr(hash + 1);
        if (word.starts_with("INF")) return std::numeric_limits<double>::infinity();
        return std::numeric_limits<double>::quiet_NaN();
    }
    case NumberKind::Integer:
    case NumberKind::Float: break;
    }
    double value = 0.0;
    std::from_chars(digits.data(), digits.data() + digits.size(), value);
    return value;
}

std::string printableExcerpt(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size() && i < kMaxQuotedChars; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        out += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : '?';
    }
    if (text.size() > kMaxQuotedChars) out += "...";
    return out;
}

std::string describe(const Token& token) {
    switch (token.type) {
    case TokenType::End: return "end of file";
    case TokenType::String: return '"' + printableExcerpt(token.text) + '"';
    case TokenType::Literal:
    case TokenType::Invalid:
    case TokenType::Number:
    case TokenType::Name:
    case TokenType::Punctuation: break;
    }
    return '\'' + printableExcerpt(token.text) + '\'';
}

Lexer::Lexer(std::string_view source, Diagnostics& diagnostics)
    : p_(source.data()), end_(source.data() + source.size()), lineStart_(source.data()),
      diagnostics_(diagnostics) {}

SourceLocation Lexer::locate(const char* at) const {
    return {line_, static_cast<int>(at - lineStart_) + 1};
}

void Lexer::newLine(const char* lineEnd) {
    ++line_;
    lineStart_ = lineEnd + 1;
}

void Lexer::skipWhiteSpace() {
    while (p_ < end_) {
        const char c = *p_;
        if (has(c, kSpace)) {
            // "\r\n" counts once (at the "\n"); a lone "\r" ends a line by itself.
            if (c == '\n' || (c == '\r' && (p_ + 1 == end_ || p_[1] != '\n'))) newLine(p_);
            ++p_;
        } else if (c == '/' && p_ + 1 < end_ && p_[1] == '/') {
            p_ += 2;
            while (p_ < end_ && *p_ != '\n' && *p_ != '\r') ++p_;
        } else if (c == '/' && p_ + 1 < end_ && p_[1] == '*') {
            const SourceLocation opened = locate(p_);
            p_ += 2;
            bool closed = false;
            while (p_ < end_) {
                if (*p_ == '*' && p_ + 1 < end_ && p_[1] == '/') {
                    p_ += 2;
                    closed = true;
                    break;
                }
                if (*p_ == '/' && p_ + 1 < end_ && p_[1] == '*')
                    diagnostics_.warning(locate(p_), "'/*' inside a comment; comments do not nest");
                if (*p_ == '\n' || (*p_ == '\r' && (p_ + 1 == end_ || p_[1] != '\n'))) newLine(p_);
                ++p_;
            }
            if (!closed) diagnostics_.error(opened, "comment opened here is never closed with '*/'");
        } else {
            return;
        }
    }
}

Token Lexer::make(TokenType type, const char* start, const char* stop) const {
    Token t;
    t.type = type;
    t.text = std::string_view(start, static_cast<std::size_t>(stop - start));
    t.where = locate(start);
    return t;
}

Token Lexer::invalid(const char* start, const char* stop, std::string message) {
    Token t = make(TokenType::Invalid, start, stop);
    diagnostics_.error(t.where, std::move(message));
    return t;
}

Token Lexer::next() {
    skipWhiteSpace();
    if (p_ >= end_) {
        Token t;
        t.where = locate(end_);
        return t;
    }
    const char* start = p_;
    const char c = *p_;
    const char c2 = p_ + 1 < end_ ? p_[1] : '\0';
    if (c == '"' || c == '\'') return readString(start, c);
    if (has(c, kDigit) || (c == '.' && has(c2, kDigit))) return readNumber(start);
    if (has(c, kNameStart)) return readName(start);
    return readPunctuation(start);
}

// Reads one quoted run starting at p_ (on the opening quote). Returns false on an error, which
// has been reported. With `joined`, the run's contents are appended to it.
bool Lexer::quotedRun(char quote, std::string* joined) {
    const char* open = p_;
    const char* q = p_ + 1;
    while (q < end_ && *q != quote) {
        if (*q == '\n' || *q == '\r') {
            diagnostics_.error(locate(open), "newline inside a quoted string");
            p_ = q;
            return false;
        }
        ++q;
    }
    if (q >= end_) {
        diagnostics_.error(locate(open), "missing closing quote");
        p_ = end_;
        return false;
    }
    if (joined) joined->append(open + 1, q);
    p_ = q + 1;
    return true;
}

Token Lexer::readString(const char* start, char quote) {
    const TokenType type = quote == '"' ? TokenType::String : TokenType::Literal;
    if (!quotedRun(quote, nullptr)) return make(TokenType::Invalid, start, p_);
    Token t = make(type, start + 1, p_ - 1);
    t.where = locate(start);  // a string is where its opening quote is
    if (type != TokenType::String) return t;

    // `"a" \ "b"` is one string "ab". Anything else after the backslash leaves both alone.
    // The white space skipped while looking is white space the next token would skip anyway.
    std::string* joined = nullptr;
    for (;;) {
        skipWhiteSpace();
        if (p_ >= end_ || *p_ != '\\') break;
        const char* backslash = p_;
        const char* saveLineStart = lineStart_;
        const int saveLine = line_;
        ++p_;
        skipWhiteSpace();
        if (p_ >= end_ || *p_ != '"') {
            p_ = backslash;
            lineStart_ = saveLineStart;
            line_ = saveLine;
            break;
        }
        if (!joined) joined = &joinedStrings_.emplace_back(t.text);
        if (!quotedRun('"', joined)) return make(TokenType::Invalid, start, p_);
    }
    if (joined) t.text = *joined;
    return t;
}

Token Lexer::readName(const char* start) {
    const char* q = start + 1;
    while (q < end_ && has(*q, kNameChar)) ++q;
    p_ = q;
    return make(TokenType::Name, start, q);
}

Token Lexer::readNumber(const char* start) {
    const char* q = start;
    NumberKind kind = NumberKind::Integer;
    auto digitsWhile = [&](auto accept) {
        const char* from = q;
        while (q < end_ && accept(*q)) ++q;
        return q > from;
    };
    if (*q == '0' && q + 1 < end_ && q[1] != '.') {
        const char x = q[1];
        if (x == 'x' || x == 'X' || x == 'b' || x == 'B') {
            const bool hex = (x == 'x' || x == 'X');
            kind = hex ? NumberKind::Hex : NumberKind::Binary;
            q += 2;
            const bool any = hex ? digitsWhile([](char d) { return has(d, kDigit) || ((d | 0x20) >= 'a' && (d | 0x20) <= 'f'); })
                                 : digitsWhile([](char d) { return d == '0' || d == '1'; });
            if (!any) {
                p_ = q;
                return invalid(start, q, hex ? "hex number without digits" : "binary number without digits");
            }
        } else {
            kind = NumberKind::Octal;
            ++q;
            digitsWhile([](char d) { return d >= '0' && d <= '7'; });
        }
    } else {
        int dots = 0;
        while (q < end_ && (has(*q, kDigit) || *q == '.')) {
            dots += (*q == '.');
            ++q;
        }
        if (dots > 1) {
            p_ = q;
            return invalid(start, q, "more than one dot in number '" + printableExcerpt({start, q}) + "'");
        }
        const bool exponent = q < end_ && (*q == 'e' || *q == 'E');
        if (dots == 1 || exponent) kind = NumberKind::Float;
        if (exponent) {
            ++q;
            if (q < end_ && (*q == '+' || *q == '-')) ++q;
            if (!digitsWhile([](char d) { return has(d, kDigit); })) {
                p_ = q;
                return invalid(start, q, "exponent without digits in number '" + printableExcerpt({start, q}) + "'");
            }
        } else if (dots == 1 && q < end_ && *q == '#') {
            // 1.#INF, 1.#IND, 1.#NAN, 1.#QNAN, 1.#SNAN: what MSVC printed for non-finite floats.
            const char* word = q + 1;
            const char* w = word;
            while (w < end_ && *w >= 'A' && *w <= 'Z') ++w;
            const std::string_view spelled(word, static_cast<std::size_t>(w - word));
            if (spelled == "INF" || spelled == "IND" || spelled == "NAN" || spelled == "QNAN" || spelled == "SNAN") {
                q = w;
                kind = NumberKind::SpecialFloat;
            }
        }
    }
    // Suffixes idLexer eats: f/F/l/L after floats, u/U/l/L after integers.
    if (kind == NumberKind::Float) {
        if (q < end_ && (*q == 'f' || *q == 'F' || *q == 'l' || *q == 'L')) ++q;
    } else if (kind != NumberKind::SpecialFloat) {
        while (q < end_ && (*q == 'u' || *q == 'U' || *q == 'l' || *q == 'L')) ++q;
    }
    p_ = q;
    Token t = make(TokenType::Number, start, q);
    t.numberKind = kind;
    return t;
}

Token Lexer::readPunctuation(const char* start) {
    const std::size_t left = static_cast<std::size_t>(end_ - start);
    if (left > 1 && kMultiStart.find(*start) != std::string_view::npos) {
        const std::string_view rest(start, left < 3 ? left : 3);
        for (std::string_view p : kPunctuation3)
            if (rest.starts_with(p)) return p_ = start + 3, make(TokenType::Punctuation, start, p_);
        for (std::string_view p : kPunctuation2)
            if (rest.starts_with(p)) return p_ = start + 2, make(TokenType::Punctuation, start, p_);
    }
    p_ = start + 1;
    if (kPunctuation1.find(*start) != std::string_view::npos) return make(TokenType::Punctuation, start, p_);
    char shown[8];
    std::snprintf(shown, sizeof shown, "0x%02X", static_cast<unsigned char>(*start));
    return invalid(start, p_, std::string("unexpected character (byte ") + shown + ")");
}

}  // namespace af
