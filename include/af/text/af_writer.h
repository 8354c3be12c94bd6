#pragma once
// The canonical `.af` writer: the Doom 3 AF editor's layout (docs/formats.md §1.10).
//
// parse(write(d)) == d for every decl d we parse, and write(parse(write(d))) == write(d) byte
// for byte. Where we differ from Doom's editor, on purpose:
//  * frictionDirection / contactMotorDirection are written when given, not when their resolved
//    value is non-zero, so joint-based directions survive a save without a skeleton;
//  * a number that ten decimals cannot hold exactly is written in exponent form (see
//    formatDeclFloat), so no value is lost;
//  * the later-game extensions we read (fastEval, extra contents names) are written back;
//  * a whole file ends with one newline after the last decl's closing brace.

#include "af/text/decl_af.h"

#include <string>

namespace af {

// One decl: the generated comment block, then `articulatedFigure NAME { ... }` with no newline
// after the final brace.
std::string writeDecl(const DeclAF& decl);

// Every decl of a file, one after the other, and a final newline.
std::string writeAFFile(const AFFile& file);

}  // namespace af
