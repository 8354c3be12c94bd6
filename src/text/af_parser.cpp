#include "af/text/af_parser.h"

#include "af/text/strings.h"
#include "af_parser_impl.h"
#include "decl_types.h"
#include "text_file.h"
#include "af/text/contents.h"
#include "af/text/number_format.h"


namespace af {

AFParseResult parseAF(std::string_view text, std::string fileName) {
    AFParseResult result{{fileName, {}}, Diagnostics(fileName)};
    AFParser parser(text, result.diagnostics);
    parser.parseFile(result.file);
    return result;
}

AFParseResult loadAFFile(const std::string& path) {
    const std::optional<std::string> text = readWholeFile(path);
    if (!text) {
        AFParseResult result{{path, {}}, Diagnostics(path)};
        result.diagnostics.error({}, "cannot open the file for reading");
        return result;
    }
    return parseAF(*text, path);
}

void AFParser::parseFile(AFFile& file) {
    bool recovering = false;
    while (!in_.atEnd()) {
        // After a broken decl (an unclosed string, say) its last braces may still be ahead; they
        // are debris of the error already reported, not a new error.
        if (recovering && in_.peek().isPunctuation("}")) {
            in_.next();
            continue;
        }
        const int depth = in_.braceDepth();
        try {
            parseDecl(file);
            recovering = false;
        } catch (const ParseAbort&) {
            in_.skipToDepth(depth);
            recovering = true;
        }
    }
    diagnostics().sortByPosition();
}

void AFParser::parseDecl(AFFile& file) {
    Token name = in_.next();
    if (name.isKeyword("articulatedFigure")) {
        name = in_.next();
    } else if (name.type == TokenType::Name && isDoomDeclType(name.text) && !in_.peek().isPunctuation("{")) {
        // Doom reads any decl type in any decl file; another type's decl is not a figure, so it
        // is skipped whole (and not written back), with a word.
        in_.next();  // its name
        const int depth = in_.braceDepth();
        in_.expectPunctuation("{", "after the decl name");
        diagnostics().warning(name.where, "a decl of type " + printableExcerpt(name.text) +
                                              " in an .af file is skipped (Doom 3 reads it as one) and not "
                                              "written back");
        in_.skipToDepth(depth);
        return;
    }
    if (name.type != TokenType::Name && name.type != TokenType::String) {
        if (name.isPunctuation("{")) {
            // A braced section without a name: Doom 3 warns and skips it whole, and so do we.
            diagnostics().warning(name.where, "a braced section without a decl name is skipped, as in Doom 3");
            in_.skipToDepth(in_.braceDepth() - 1);
            return;
        }
        in_.fail(name, "articulatedFigure or a decl name");
    }
    in_.expectPunctuation("{", "after the decl name");

    DeclAF decl;
    decl.name = canonicalDeclName(name.text);
    decl.where = name.where;
    current_ = AFSettings{};
    firstBodyName_.clear();
    parseItems(decl);  // throws past the validation when the decl is malformed
    validateDecl(decl, diagnostics());

    if (const DeclAF* earlier = file.findDecl(decl.name)) {
        diagnostics().warning(decl.where, "decl '" + decl.name + "' is defined again; the definition at line " +
                                              std::to_string(earlier->where.line) + " is used");
    }
    file.decls.push_back(std::move(decl));
}

void AFParser::parseItems(DeclAF& decl) {
    for (;;) {
        const Token key = in_.next();
        if (key.isPunctuation("}")) return;
        if (key.isKeyword("settings")) parseSettings(current_), decl.settings = current_;
        else if (key.isKeyword("body")) parseBody(decl);
        else if (key.isKeyword("fixed")) parseConstraint(decl, ConstraintType::Fixed);
        else if (key.isKeyword("ballAndSocketJoint")) parseConstraint(decl, ConstraintType::BallAndSocket);
        else if (key.isKeyword("universalJoint")) parseConstraint(decl, ConstraintType::Universal);
        else if (key.isKeyword("hinge")) parseConstraint(decl, ConstraintType::Hinge);
        else if (key.isKeyword("slider")) parseConstraint(decl, ConstraintType::Slider);
        else if (key.isKeyword("spring")) parseConstraint(decl, ConstraintType::Spring);
        else
            in_.fail(key, "settings, body, a constraint (fixed, ballAndSocketJoint, universalJoint, hinge, "
                          "slider, spring) or '}'");
    }
}

void AFParser::parseSettings(AFSettings& s) {
    in_.expectPunctuation("{", "after settings");
    for (;;) {
        const Token key = in_.next();
        if (key.isPunctuation("}")) return;
        if (key.isKeyword("model")) s.model = in_.expectString("a model name").text;
        else if (key.isKeyword("skin")) s.skin = in_.expectString("a skin name").text;
        else if (key.isKeyword("mesh") || key.isKeyword("anim")) {
            in_.expectString("a file name");
            diagnostics().warning(key.where, "'" + std::string(key.text) +
                                                 "' in settings is ignored (as in Doom 3) and not written back");
        } else if (key.isKeyword("friction")) {
            s.linearFriction = readNonNegative("linear friction", kDoomIgnoresFriction);
            in_.expectPunctuation(",", "after the linear friction");
            s.angularFriction = readNonNegative("angular friction", kDoomIgnoresFriction);
            in_.expectPunctuation(",", "after the angular friction");
            s.contactFriction = readNonNegative("contact friction", kDoomIgnoresFriction);
            if (in_.acceptPunctuation(",")) s.constraintFriction = readWarnedIfNegative("constraint friction", kSeedsEditorOnly);
        } else if (key.isKeyword("suspendSpeed")) {
            s.suspendLinearVelocity = readWarnedIfNegative("the linear suspend velocity", kNeverBelow);
            in_.expectPunctuation(",", "after the linear suspend velocity");
            s.suspendAngularVelocity = readWarnedIfNegative("the angular suspend velocity", kNeverBelow);
            in_.expectPunctuation(",", "after the angular suspend velocity");
            s.suspendLinearAcceleration = readWarnedIfNegative("the linear suspend acceleration", kNeverBelow);
            in_.expectPunctuation(",", "after the linear suspend acceleration");
            s.suspendAngularAcceleration = readWarnedIfNegative("the angular suspend acceleration", kNeverBelow);
        } else if (key.isKeyword("noMoveTime")) s.noMoveTime = readWarnedIfNegative("noMoveTime", kNoWindow);
        else if (key.isKeyword("noMoveTranslation")) s.noMoveTranslation = readWarnedIfNegative("noMoveTranslation", kNeverStill);
        else if (key.isKeyword("noMoveRotation")) s.noMoveRotation = readWarnedIfNegative("noMoveRotation", kNeverStill);
        else if (key.isKeyword("minMoveTime")) s.minMoveTime = in_.readFloat("minMoveTime");
        else if (key.isKeyword("maxMoveTime")) s.maxMoveTime = in_.readFloat("maxMoveTime");
        else if (key.isKeyword("totalMass")) s.totalMass = in_.readFloat("totalMass");
        else if (key.isKeyword("contents")) s.contents = parseContents("contents", s.unknownContents);
        else if (key.isKeyword("clipMask")) s.clipMask = parseContents("clipMask", s.unknownClipMask);
        else if (key.isKeyword("selfCollision")) s.selfCollision = in_.readBool("selfCollision");
        else if (key.isKeyword("fastEval")) {
            s.extensions.fastEval = true;
            diagnostics().warning(key.where, "fastEval (a Quake 4 setting) is kept for writing but has no effect here");
        } else {
            in_.fail(key, "a settings key (model, skin, friction, suspendSpeed, noMoveTime, noMoveTranslation, "
                          "noMoveRotation, minMoveTime, maxMoveTime, totalMass, contents, clipMask, "
                          "selfCollision) or '}'");
        }
    }
}

Real AFParser::readNonNegative(std::string_view what, std::string_view why) {
    SourceLocation where;
    const Real value = in_.readFloat(what, &where);
    if (value < 0)
        diagnostics().error(where, std::string(what) + " must not be negative, found " + formatDeclFloat(value) +
                                       " (" + std::string(why) + ")");
    return value;
}

Real AFParser::readWarnedIfNegative(std::string_view what, std::string_view effect) {
    SourceLocation where;
    const Real value = in_.readFloat(what, &where);
    if (value < 0)
        diagnostics().warning(where, std::string(what) + " is negative, found " + formatDeclFloat(value) +
                                         "; Doom 3 loads it, and so do we: " + std::string(effect));
    return value;
}

AFVector AFParser::parseVector(std::string_view what) {
    AFVector v;
    const Token first = in_.peek();
    v.where = first.where;
    v.negated = in_.acceptPunctuation("-");
    const Token t = in_.next();
    if (t.isPunctuation("(")) {
        for (int i = 0; i < 3; ++i) {
            if (i > 0) in_.expectPunctuation(",", "between vector components");
            v.coordinates[i] = in_.readFloat(what);
        }
        in_.expectPunctuation(")", "after the third vector component");
        return v;
    }
    // The joint words are case-sensitive in Doom's parser.
    if (t.type == TokenType::Name && (t.text == "joint" || t.text == "bonecenter" || t.text == "bonedir")) {
        v.kind = t.text == "joint" ? AFVector::Kind::Joint
                 : t.text == "bonecenter" ? AFVector::Kind::BoneCenter : AFVector::Kind::BoneDir;
        in_.expectPunctuation("(", "after " + std::string(t.text));
        auto jointName = [&] {
            const Token j = in_.next();
            if (j.type != TokenType::String && j.type != TokenType::Name) in_.fail(j, "a joint name");
            return std::string(j.text);
        };
        v.joint1 = jointName();
        if (v.kind != AFVector::Kind::Joint) {
            in_.expectPunctuation(",", "between the two joint names");
            v.joint2 = jointName();
        }
        in_.expectPunctuation(")", "after the joint name");
        return v;
    }
    in_.fail(t, std::string(what) + " as ( x, y, z ), joint( \"J\" ), bonecenter( \"A\", \"B\" ) or bonedir( \"A\", \"B\" )");
}

// A list replaces the one before it, so the unknown names of an earlier list go too.
ContentsMask AFParser::parseContents(std::string_view what, std::vector<std::string>& unknown) {
    ContentsMask mask = 0;
    unknown.clear();
    do {
        const Token t = in_.next();
        if (t.type != TokenType::Name) in_.fail(t, "a " + std::string(what) + " name (" + contentsNameList() + ")");
        const std::optional<ContentsMask> bit = contentsBitFromName(t.text);
        if (!bit) {
            // Doom 3 ends the list at a name it does not know and loads the figure; later games
            // name bits of their own here. Kept for the writer, with no effect (§1.9).
            diagnostics().warning(t.where, "unknown " + std::string(what) + " name '" + printableExcerpt(t.text) +
                                               "' (a later game's?); kept and written back, no effect here");
            unknown.emplace_back(t.text);
            continue;
        }
        if (!isDoom3AfContentsName(t.text))
            diagnostics().warning(t.where, "'" + std::string(t.text) + "' is not a " + std::string(what) +
                                               " name Doom 3's AF parser knows; kept");
        if (*bit == 0) unknown.clear();
        mask = *bit == 0 ? 0 : (mask | *bit);
    } while (in_.acceptPunctuation(","));
    return mask;
}

}  // namespace af
