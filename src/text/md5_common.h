#pragma once
// Pieces shared by the .md5mesh and .md5anim readers: the header, Doom's Parse1DMatrix
// `( a b c )` form and value checks that stop the parse.

#include "af/text/md5.h"
#include "text_file.h"
#include "token_reader.h"

#include <optional>
#include <string>
#include <string_view>

namespace af::md5detail {

// Reports `message` at `where` and abandons the file. An md5 file is one unit, so the first
// error ends it; continuing would only pile up consequences of the same mistake.
[[noreturn]] void failAt(TokenReader& in, SourceLocation where, const std::string& message);

// A case-sensitive keyword, as Doom's ExpectTokenString wants it.
void expectKeyword(TokenReader& in, std::string_view keyword, std::string_view context = {});

// `MD5Version 10` and `commandline "..."`; returns the command line.
std::string readHeader(TokenReader& in);

// `keyword N` with N >= minimum.
int readCount(TokenReader& in, std::string_view keyword, int minimum);

// Doom's Parse1DMatrix: `(` then `count` numbers without commas, then `)`.
void readTuple(TokenReader& in, Real* values, int count, std::string_view what);
Real3 readTuple3(TokenReader& in, std::string_view what);
Md5Quat readQuat(TokenReader& in, std::string_view what);

// A name-like token: a string or a bare name.
Token readWord(TokenReader& in, std::string_view what);

// After the last item: anything more is a count that does not match the data.
void expectEnd(TokenReader& in, std::string_view after);


}  // namespace af::md5detail
