// `.def` decl files: entityDef and model decls kept, every other kind skipped by brace matching
// (docs/formats.md §1.1, §2.4, §2.5).

#include "af/text/decl_def.h"
#include "af/text/strings.h"
#include "decl_types.h"
#include "text_file.h"
#include "token_reader.h"

#include <array>

namespace af {

namespace {

// The decl types matter here only to tell `TYPE {` (a missing name) from `NAME {` (an
// entityDef, the def/ folder's default type).
bool isDeclType(const Token& t) { return t.type == TokenType::Name && isDoomDeclType(t.text); }

DefKeyValue* findKey(EntityDef& def, std::string_view key) {
    for (DefKeyValue& kv : def.keyValues)
        if (equalsIgnoreCase(kv.key, key)) return &kv;
    return nullptr;
}

bool isWord(const Token& t) {
    return t.type == TokenType::Name || t.type == TokenType::String || t.type == TokenType::Number;
}

class DefParser {
public:
    DefParser(std::string_view text, Diagnostics& diagnostics) : in_(text, diagnostics) {}

    void parseFile(DefFile& file) {
        while (!in_.atEnd()) {
            const int depth = in_.braceDepth();
            try {
                parseDecl(file, depth);
            } catch (const ParseAbort&) {
                resynchronise(depth);
            }
        }
    }

private:
    Diagnostics& diagnostics() { return in_.diagnostics(); }

    // Skips to the `}` that brings the depth back to `depth`; the end of the file first is an
    // error, unless a lexical error inside the block (an unclosed string or comment, which eats
    // the rest of the file) already explains it.
    void skipBlock(int depth, const Token& opened, std::string_view what) {
        const std::size_t errorsBefore = diagnostics().errorCount();
        in_.skipToDepth(depth);
        if (in_.braceDepth() <= depth) return;
        if (diagnostics().errorCount() != errorsBefore) throw ParseAbort{};
        in_.fail(in_.peek(),
                 "'}' to close " + std::string(what) + " opened at line " + std::to_string(opened.where.line));
    }

    // After an error, skips the rest of the broken decl so that it gives one message, not a
    // cascade: inside a block, to its end; outside, past the next block or a `}` without a `{`.
    void resynchronise(int depth) {
        if (in_.braceDepth() > depth) {
            in_.skipToDepth(depth);
            return;
        }
        while (!in_.atEnd() && in_.braceDepth() == depth) {
            if (in_.next().isPunctuation("{")) {
                in_.skipToDepth(depth);
                return;
            }
        }
    }

    Token readWord(std::string_view what) {
        const Token t = in_.next();
        if (!isWord(t)) in_.fail(t, what);
        return t;
    }

    void parseDecl(DefFile& file, int depth) {
        const Token first = in_.next();
        if (first.isPunctuation("{")) {
            // Doom warns "missing decl name" and skips the section; so do we.
            diagnostics().warning(first.where, "a braced section without a decl type and name is skipped");
            skipBlock(depth, first, "the braced section");
            return;
        }
        if (first.type != TokenType::Name && first.type != TokenType::String)
            in_.fail(first, "a decl (TYPE NAME { ... }) or a decl name");

        std::string type = "entityDef";
        Token name = first;
        if (isDeclType(first) || !in_.peek().isPunctuation("{")) {
            type = first.text;
            name = in_.next();
        }
        if (name.isPunctuation("{")) {
            diagnostics().warning(name.where, "'" + printableExcerpt(type) + "' without a decl name; the braced section is skipped");
            skipBlock(depth, name, "the braced section");
            return;
        }
        if (!isWord(name)) in_.fail(name, "a decl name after '" + printableExcerpt(type) + "'");
        const Token open = in_.next();
        if (!open.isPunctuation("{")) in_.fail(open, "'{' after the decl name");

        if (equalsIgnoreCase(type, "entityDef")) {
            parseEntityDef(file, name);
        } else if (equalsIgnoreCase(type, "model")) {
            parseModel(file, name, depth);
        } else {
            skipBlock(depth, open, printableExcerpt(type) + " '" + printableExcerpt(name.text) + "'");
            file.skipped.push_back({type, std::string(name.text), first.where});
        }
    }

    template <class Decl>
    bool isRepeat(const std::vector<Decl>& decls, const Decl& decl, std::string_view kind) {
        for (const Decl& earlier : decls) {
            if (earlier.name != decl.name) continue;
            diagnostics().warning(decl.where, std::string(kind) + " '" + decl.name +
                                                  "' is defined again; the definition at line " +
                                                  std::to_string(earlier.where.line) + " is used");
            return true;
        }
        return false;
    }

    void parseEntityDef(DefFile& file, const Token& name) {
        EntityDef def;
        def.name = canonicalDeclName(name.text);
        def.writtenName = name.text;
        def.file = file.path;
        def.where = name.where;
        for (;;) {
            const Token key = in_.next();
            if (key.isPunctuation("}")) break;
            if (key.type != TokenType::String) in_.fail(key, "a key in double quotes or '}'");
            const Token value = in_.next();
            if (value.type == TokenType::End || value.type == TokenType::Invalid || value.isPunctuation("{") ||
                value.isPunctuation("}"))
                in_.fail(value, "a value for \"" + printableExcerpt(key.text) + "\"");
            if (DefKeyValue* earlier = findKey(def, key.text)) {
                diagnostics().warning(key.where, "key \"" + std::string(key.text) +
                                                     "\" is set again (first at line " +
                                                     std::to_string(earlier->where.line) + "); the later value is used");
                earlier->value = value.text;
                earlier->where = key.where;
            } else {
                def.keyValues.push_back({std::string(key.text), std::string(value.text), key.where, {}});
            }
        }
        if (!isRepeat(file.entityDefs, def, "entityDef")) file.entityDefs.push_back(std::move(def));
    }

    void parseModel(DefFile& file, const Token& name, int depth) {
        ModelDecl model;
        model.name = canonicalDeclName(name.text);
        model.writtenName = name.text;
        model.file = file.path;
        model.where = name.where;
        for (;;) {
            const Token key = in_.next();
            if (key.isPunctuation("}")) break;
            // Doom compares model keys with ==, so they are case-sensitive.
            if (key.type != TokenType::Name) in_.fail(key, kModelKeys);
            if (key.text == "inherit") {
                const Token parent = readWord("a model decl name after inherit");
                if (!model.inherit.empty())
                    diagnostics().warning(parent.where, "a second inherit replaces '" + model.inherit + "'");
                model.inherit = parent.text;
                model.inheritWhere = parent.where;
            } else if (key.text == "mesh") {
                const Token mesh = readWord("an .md5mesh file name after mesh");
                model.mesh = mesh.text;
                model.meshWhere = mesh.where;
                if (!model.mesh.ends_with(".md5mesh"))
                    diagnostics().warning(mesh.where, "mesh '" + model.mesh +
                                                          "' is not an .md5mesh; Doom 3 rejects this model decl");
            } else if (key.text == "skin") {
                model.skin = readWord("a skin name after skin").text;
            } else if (key.text == "offset") {
                Real3 offset{};
                in_.expectPunctuation("(", "before the offset ( x y z )");
                for (Real& v : offset) v = in_.readFloat("the offset");
                in_.expectPunctuation(")", "after the three offset values (they take no commas)");
                model.offset = offset;
            } else if (key.text == "channel") {
                model.channels.push_back(parseChannel());
            } else if (key.text == "anim") {
                parseAnim(model, depth + 1);
            } else if (key.text == "remove") {
                const Token alias = readWord("an anim name after remove");
                model.removes.push_back({std::string(alias.text), alias.where});
            } else {
                in_.fail(key, kModelKeys);
            }
        }
        if (!isRepeat(file.models, model, "model")) file.models.push_back(std::move(model));
    }

    ModelChannel parseChannel() {
        ModelChannel channel;
        const Token name = readWord("a channel name after channel");
        channel.name = name.text;
        channel.where = name.where;
        in_.expectPunctuation("(", "before the channel's joint list");
        // Joined as Doom joins it: `*` and `-` stick to the next name, names are space-separated.
        for (;;) {
            const Token t = in_.next();
            if (t.isPunctuation(")")) break;
            if (t.isPunctuation("*") || t.isPunctuation("-")) channel.joints += t.text;
            else if (isWord(t)) (channel.joints += t.text) += ' ';
            else in_.fail(t, "a joint name, '*', '-' or ')' in the channel's joint list");
        }
        if (!channel.joints.empty() && channel.joints.back() == ' ') channel.joints.pop_back();
        return channel;
    }

    void parseAnim(ModelDecl& model, int depth) {
        ModelAnim anim;
        const Token alias = readWord("an anim name after anim");
        anim.alias = alias.text;
        anim.where = alias.where;
        do {
            anim.files.emplace_back(readWord("an .md5anim file name").text);
        } while (in_.acceptPunctuation(","));
        if (in_.peek().isPunctuation("{")) {
            const Token open = in_.next();
            skipBlock(depth, open, "the frame commands of anim '" + anim.alias + "'");
            anim.hasFrameCommands = true;
        }
        for (ModelAnim& earlier : model.anims) {
            if (earlier.alias != anim.alias) continue;
            diagnostics().warning(alias.where, "anim '" + anim.alias + "' is defined again (first at line " +
                                                   std::to_string(earlier.where.line) +
                                                   "); the later one is used (Doom 3 rejects the model decl)");
            earlier = std::move(anim);
            return;
        }
        model.anims.push_back(std::move(anim));
    }

    static constexpr std::string_view kModelKeys =
        "a model key (inherit, mesh, skin, offset, channel, anim, remove) or '}'";

    TokenReader in_;
};

}  // namespace

const DefKeyValue* EntityDef::find(std::string_view key) const {
    for (const DefKeyValue& kv : keyValues)
        if (equalsIgnoreCase(kv.key, key)) return &kv;
    return nullptr;
}

std::string EntityDef::valueOr(std::string_view key, std::string_view fallback) const {
    const DefKeyValue* kv = find(key);
    return kv ? kv->value : std::string(fallback);
}

const ModelAnim* ModelDecl::findAnim(std::string_view alias) const {
    for (const ModelAnim& anim : anims)
        if (anim.alias == alias) return &anim;
    return nullptr;
}

DefParseResult parseDef(std::string_view text, std::string fileName) {
    DefParseResult result{{fileName, {}, {}, {}}, Diagnostics(fileName)};
    DefParser parser(text, result.diagnostics);
    parser.parseFile(result.file);
    return result;
}

DefParseResult loadDefFile(const std::string& path) {
    const std::optional<std::string> text = readWholeFile(path);
    if (!text) {
        DefParseResult result{{path, {}, {}, {}}, Diagnostics(path)};
        result.diagnostics.error({}, "cannot open the file for reading");
        return result;
    }
    return parseDef(*text, path);
}

}  // namespace af
