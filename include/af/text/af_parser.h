#pragma once
// Reading `.af` files into DeclAF data (docs/formats.md §1).
//
// Every problem is a Diagnostic with its position; a file with any error does not load. After
// a structural error (a missing brace, an unknown keyword) the parser skips to the end of that
// decl and goes on with the next, so one mistake gives one message, not a cascade.

#include "af/text/decl_af.h"
#include "af/text/diagnostics.h"

#include <string>
#include <string_view>

namespace af {

struct AFParseResult {
    AFFile file;
    Diagnostics diagnostics;

    bool ok() const { return !diagnostics.hasErrors(); }
};

// Parses `text`; `fileName` is used in diagnostics only.
AFParseResult parseAF(std::string_view text, std::string fileName);

// Reads and parses a file; a file that cannot be read is reported as an error diagnostic.
AFParseResult loadAFFile(const std::string& path);

}  // namespace af
