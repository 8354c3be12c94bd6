#pragma once
// The .af parser's internals, shared by the files that parse settings, bodies and constraints.

#include "af/text/decl_af.h"
#include "token_reader.h"

#include <string_view>

namespace af {

class AFParser {
public:
    AFParser(std::string_view text, Diagnostics& diagnostics) : in_(text, diagnostics) {}

    void parseFile(AFFile& file);

private:
    void parseDecl(AFFile& file);
    void parseItems(DeclAF& decl);
    void parseSettings(AFSettings& settings);
    void parseBody(DeclAF& decl);
    void parseBodyKey(AFBody& body, const Token& key);
    AFShape parseShape();
    void parseConstraint(DeclAF& decl, ConstraintType type);
    // Returns the bit of a spring key just read, 0 for others.
    unsigned parseConstraintKey(AFConstraint& c, const Token& key);
    AFVector parseVector(std::string_view what);
    ContentsMask parseContents(std::string_view what);
    Real readNonNegative(std::string_view what);

    Diagnostics& diagnostics() { return in_.diagnostics(); }

    TokenReader in_;
    AFSettings current_;        // the settings as parsed so far: defaults for what follows
    std::string firstBodyName_; // default body1 of constraints
};

// Post-parse checks of a complete decl (names, references, required values) and the move of
// the origin body to index 0 (docs/formats.md §1.3, §1.8).
void validateDecl(DeclAF& decl, Diagnostics& diagnostics);

}  // namespace af
