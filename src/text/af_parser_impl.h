#pragma once
// The .af parser's internals, shared by the files that parse settings, bodies and constraints.

#include "af/text/decl_af.h"
#include "token_reader.h"

#include <string_view>

namespace af {

// Why a negative value is refused, or what a negative one does (docs/formats.md §1.3).
inline constexpr std::string_view kDoomIgnoresFriction =
    "Doom 3 refuses it too: it keeps its default friction and warns";
inline constexpr std::string_view kFrictionFeedsEnergy =
    "negative friction feeds energy into the figure, which cannot be simulated";
inline constexpr std::string_view kNeverBelow =
    "no motion is below a negative threshold, so this test never puts the figure to rest";
inline constexpr std::string_view kSeedsEditorOnly =
    "it only seeds constraints made in Doom's editor, never parsed ones, so it has no effect";
inline constexpr std::string_view kNoWindow = "the no-move window is then judged from the first step";
inline constexpr std::string_view kNeverStill =
    "no motion is below a negative tolerance, so the no-move test never puts the figure to rest";

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
    // A contents or clipMask list; names unknown to us go to `unknown`, as written.
    ContentsMask parseContents(std::string_view what, std::vector<std::string>& unknown);
    // A value that must not be negative; `why` says so in the error.
    Real readNonNegative(std::string_view what, std::string_view why);
    // A value Doom 3 loads even when negative (a rest threshold, the editor's constraint
    // friction; docs/formats.md §1.3): a negative one is a warning saying what it does.
    Real readWarnedIfNegative(std::string_view what, std::string_view effect);

    Diagnostics& diagnostics() { return in_.diagnostics(); }

    TokenReader in_;
    AFSettings current_;        // the settings as parsed so far: defaults for what follows
    std::string firstBodyName_; // default body1 of constraints
};

// Post-parse checks of a complete decl (names, references, required values) and the move of
// the origin body to index 0 (docs/formats.md §1.3, §1.8).
void validateDecl(DeclAF& decl, Diagnostics& diagnostics);

}  // namespace af
