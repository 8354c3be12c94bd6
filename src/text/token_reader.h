#pragma once
// The parsers' view of a token stream: one token of look-ahead, `expect` helpers that report
// "expected X, found Y", and Doom's number rules (a sign is a separate `-` token).
//
// A structural error is reported once and then thrown as ParseAbort; the parser catches it at
// the level that can resynchronise (the end of the current decl) and goes on from there.

#include "af/text/diagnostics.h"
#include "af/text/lexer.h"
#include "af/types.h"

#include <string>
#include <string_view>

namespace af {

struct ParseAbort {};

class TokenReader {
public:
    TokenReader(std::string_view text, Diagnostics& diagnostics);

    const Token& peek() const { return lookahead_; }
    Token next();
    bool atEnd() const { return lookahead_.type == TokenType::End; }
    // How many `{` are open at the current position.
    int braceDepth() const { return depth_; }

    Diagnostics& diagnostics() { return diagnostics_; }

    // Reports "expected <expected>, found <token>" at the token and throws ParseAbort. An Invalid
    // token was reported by the lexer already, so nothing more is said about it.
    [[noreturn]] void fail(const Token& found, std::string_view expected);

    void expectPunctuation(std::string_view punctuation, std::string_view context = {});
    bool acceptPunctuation(std::string_view punctuation);
    Token expectString(std::string_view what);

    // [-] NUMBER, narrowed to float precision as Doom stores it. A value that is not finite as a
    // float is an error (reported, parsing goes on) and reads as NaN, which range checks let
    // pass so that it is not reported twice. `where` receives the position of the value.
    Real readFloat(std::string_view what, SourceLocation* where = nullptr);
    // [-] integer NUMBER; a float spelling is an error (reported, the value is truncated).
    int readInt(std::string_view what, SourceLocation* where = nullptr);
    // A number; non-zero is true.
    bool readBool(std::string_view what);

    // Skips tokens until the brace depth drops to `depth` (or the text ends).
    void skipToDepth(int depth);

private:
    Lexer lexer_;
    Diagnostics& diagnostics_;
    Token lookahead_;
    int depth_ = 0;
};

}  // namespace af
