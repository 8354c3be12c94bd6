// Reading Doom 3 `.map` files (docs/formats.md §5.6). Errors are fatal here, as in Doom's map
// reader: the first one is reported and reading stops.

#include "af/text/map_file.h"
#include "text_file.h"
#include "token_reader.h"

#include <cmath>
#include <utility>

namespace af {

namespace {

// Larger patches do not exist in practice; the bound keeps a corrupt size from reading as an
// absurd loop count or overflowing an int.
constexpr Real kMaxPatchSize = 1024;

std::string_view trimmedRight(std::string_view s) {
    while (!s.empty() && static_cast<unsigned char>(s.back()) <= 0x20) s.remove_suffix(1);
    return s;
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && static_cast<unsigned char>(s.front()) <= 0x20) s.remove_prefix(1);
    return trimmedRight(s);
}

std::string lineOf(const Token& t) { return std::to_string(t.where.line); }

class MapParser {
public:
    MapParser(std::string_view text, Diagnostics& diagnostics) : text_(text), in_(text, diagnostics) {}

    void parse(MapFile& map) {
        map.version = 1;
        if (in_.peek().isKeyword("Version")) {
            const Token version = in_.next();
            requireSameLine(version, "the map version on the same line as 'Version'");
            map.version = number("the map version");
        }
        while (!in_.atEnd()) {
            const Token open = in_.next();
            const std::string name = "entity " + std::to_string(map.entities.size());
            if (!open.isPunctuation("{")) fail(open, "'{' to open " + name);
            map.entities.emplace_back().where = open.where;
            parseEntity(map.entities.back(), name, open);
        }
    }

private:
    [[noreturn]] void fail(const Token& found, std::string_view expected) { in_.fail(found, expected); }

    void expect(std::string_view punctuation, std::string_view context) {
        in_.expectPunctuation(punctuation, context);
    }

    // The next token must start on `anchor`'s line (Doom reads it with ReadTokenOnLine).
    void requireSameLine(const Token& anchor, std::string_view expected) {
        const Token& t = in_.peek();
        if (t.type == TokenType::End || t.where.line != anchor.where.line) fail(t, expected);
    }

    // A number; a value the lexer or reader flags (out of float range, 1.#INF) ends the parse
    // like any other error.
    Real number(std::string_view what, SourceLocation* where = nullptr) {
        const std::size_t before = in_.diagnostics().errorCount();
        const Real v = in_.readFloat(what, where);
        if (in_.diagnostics().errorCount() != before) throw ParseAbort{};
        return v;
    }

    int integer(std::string_view what) {
        const std::size_t before = in_.diagnostics().errorCount();
        const int v = in_.readInt(what);
        if (in_.diagnostics().errorCount() != before) throw ParseAbort{};
        return v;
    }

    // `"key" "value"` with the value on the key's line.
    Token valueOnLine(const Token& key) {
        const std::string expected = "the value of \"" + printableExcerpt(key.text) + "\" in double quotes on the same line";
        requireSameLine(key, expected);
        const Token value = in_.next();
        if (value.type != TokenType::String) fail(value, expected);
        return value;
    }

    Token materialName() {
        const Token t = in_.next();
        if (t.type != TokenType::String && t.type != TokenType::Name) fail(t, "a material name");
        return t;
    }

    void parseEntity(MapEntity& entity, const std::string& name, const Token& open) {
        for (;;) {
            const Token t = in_.next();
            if (t.isPunctuation("}")) return;
            if (t.isPunctuation("{")) {
                parsePrimitive(entity, t);
                continue;
            }
            if (t.type != TokenType::String)
                fail(t, "a key in double quotes, '{' to open a primitive or '}' to close " + name +
                            " (opened at line " + lineOf(open) + ")");
            const Token value = valueOnLine(t);
            // Doom strips trailing white space that editors sometimes leave in entity pairs.
            entity.keys.set(trimmedRight(t.text), trimmedRight(value.text), t.where);
        }
    }

    void parsePrimitive(MapEntity& entity, const Token& open) {
        const std::string name = "primitive " + std::to_string(entity.primitives.size());
        const Token keyword = in_.peek();
        MapPrimitive primitive;
        primitive.where = open.where;
        if (keyword.isKeyword("brushDef3")) {
            in_.next();
            primitive.data = parseBrush(name);
        } else if (keyword.isKeyword("patchDef2") || keyword.isKeyword("patchDef3")) {
            in_.next();
            primitive.data = parsePatch(name, keyword.isKeyword("patchDef3"));
        } else if (keyword.type != TokenType::Name && !keyword.isPunctuation("(")) {
            // Anything else is no primitive of any format, most likely a brace gone missing.
            fail(keyword, "a primitive (brushDef3, patchDef2, patchDef3, another primitive name or the '(' of a "
                          "Quake 3 brush side) in " + name);
        } else {
            primitive.data = readRaw(name, open);
            entity.primitives.push_back(std::move(primitive));
            return;
        }
        expect("}", "to close " + name + " (opened at line " + lineOf(open) + ")");
        entity.primitives.push_back(std::move(primitive));
    }

    // Everything up to the brace that closes `open`, as it is written.
    RawPrimitive readRaw(const std::string& name, const Token& open) {
        const int depth = in_.braceDepth();
        for (;;) {
            const Token t = in_.next();
            if (t.type == TokenType::End || t.type == TokenType::Invalid)
                fail(t, "'}' to close " + name + " (opened at line " + lineOf(open) + ")");
            if (t.isPunctuation("}") && in_.braceDepth() < depth) {
                // Punctuation tokens are views into the source text, so the span is exact.
                const std::size_t from = static_cast<std::size_t>(open.text.data() + 1 - text_.data());
                const std::size_t to = static_cast<std::size_t>(t.text.data() - text_.data());
                return {std::string(trimmed(text_.substr(from, to - from)))};
            }
        }
    }

    BrushDef3 parseBrush(const std::string& name) {
        expect("{", "after brushDef3");
        BrushDef3 brush;
        for (;;) {
            const Token t = in_.next();
            if (t.isPunctuation("}")) return brush;
            if (t.type == TokenType::String) {
                const Token value = valueOnLine(t);
                brush.keys.set(t.text, value.text, t.where);
                continue;
            }
            if (!t.isPunctuation("("))
                fail(t, "'(' to start a side of " + name + ", a key in double quotes or '}' to close the brush");
            brush.sides.push_back(parseSide());
        }
    }

    // After the side's `(`: `a b c d ) ( ( t t t ) ( t t t ) ) material [f f f]`.
    BrushSide parseSide() {
        BrushSide side;
        for (Real& v : side.plane) v = number("the side's plane ( a b c d )");
        expect(")", "after the four numbers of the side's plane");
        expect("(", "to open the side's texture matrix ( ( a b c ) ( d e f ) )");
        for (auto& row : side.textureMatrix) {
            expect("(", "to open a row of the texture matrix");
            for (Real& v : row) v = number("the texture matrix");
            expect(")", "after the three numbers of a texture matrix row");
        }
        expect(")", "to close the texture matrix");
        const Token material = materialName();
        side.material = material.text;
        // Quake 2's three flags: optional, on the material's line.
        const Token& next = in_.peek();
        if (next.where.line == material.where.line &&
            (next.type == TokenType::Number || next.isPunctuation("-")))
            for (int& f : side.flags) f = integer("the side's flags (three integers)");
        return side;
    }

    // A patch size: a whole number from 1 to kMaxPatchSize.
    void checkSize(Real v, SourceLocation where, std::string_view what) {
        if (v >= 1 && v <= kMaxPatchSize && v == std::floor(v)) return;
        in_.diagnostics().error(where, "the patch " + std::string(what) + " must be a whole number from 1 to " +
                                           std::to_string(int(kMaxPatchSize)));
        throw ParseAbort{};
    }

    PatchDef parsePatch(const std::string& name, bool patchDef3) {
        const std::string_view keyword = patchDef3 ? "patchDef3" : "patchDef2";
        expect("{", "after " + std::string(keyword));
        PatchDef patch;
        patch.explicitSubdivisions = patchDef3;
        patch.material = materialName().text;
        expect("(", patchDef3 ? "to open the patch info ( width height subX subY 0 0 0 )"
                              : "to open the patch info ( width height 0 0 0 )");
        SourceLocation widthAt, heightAt;
        patch.info.resize(patchDef3 ? 7 : 5);
        for (std::size_t i = 0; i < patch.info.size(); ++i)
            patch.info[i] = number("the patch info", i == 0 ? &widthAt : i == 1 ? &heightAt : nullptr);
        expect(")", patchDef3 ? "after the seven numbers of the patch info" : "after the five numbers of the patch info");
        checkSize(patch.info[0], widthAt, "width");
        checkSize(patch.info[1], heightAt, "height");
        const int width = patch.width(), height = patch.height();

        expect("(", "to open the control points of " + name);
        patch.rows.resize(static_cast<std::size_t>(width));
        for (int r = 0; r < width; ++r) {
            const std::string row = "row " + std::to_string(r + 1) + " of " + std::to_string(width);
            expect("(", "to open control point " + row);
            patch.rows[r].resize(static_cast<std::size_t>(height));
            for (int c = 0; c < height; ++c) {
                expect("(", "to open point " + std::to_string(c + 1) + " of " + std::to_string(height) + " in " + row);
                for (Real& v : patch.rows[r][c]) v = number("a control point ( x y z s t )");
                expect(")", "after the five numbers of a control point");
            }
            expect(")", "to close control point " + row);
        }
        expect(")", "to close the control points of " + name);
        for (;;) {
            const Token t = in_.next();
            if (t.isPunctuation("}")) return patch;
            if (t.type != TokenType::String) fail(t, "a key in double quotes or '}' to close the patch");
            const Token value = in_.next();
            if (value.type != TokenType::String) fail(value, "the value of \"" + printableExcerpt(t.text) + "\" in double quotes");
            patch.keys.set(t.text, value.text, t.where);
        }
    }

    std::string_view text_;
    TokenReader in_;
};

}  // namespace

MapParseResult parseMapFile(std::string_view text, std::string fileName) {
    MapParseResult result{{}, Diagnostics(fileName)};
    // The reader looks one token ahead, so a lexical error just past the point where parsing
    // fails can be reported too; only the first error in reading order is kept.
    Diagnostics found(fileName);
    try {
        MapParser(text, found).parse(result.map);
    } catch (const ParseAbort&) {
    }
    const Diagnostic* first = nullptr;
    for (const Diagnostic& d : found.all()) {
        if (d.severity != Severity::Error) continue;
        if (!first || std::pair(d.where.line, d.where.column) < std::pair(first->where.line, first->where.column))
            first = &d;
    }
    for (const Diagnostic& d : found.all()) {
        if (d.severity == Severity::Warning) result.diagnostics.warning(d.where, d.message);
        else if (&d == first) result.diagnostics.error(d.where, d.message);
    }
    return result;
}

MapParseResult loadMapFile(const std::string& path) {
    const std::optional<std::string> text = readWholeFile(path);
    if (!text) {
        MapParseResult result{{}, Diagnostics(path)};
        result.diagnostics.error({}, "cannot open the file for reading");
        return result;
    }
    return parseMapFile(*text, path);
}

}  // namespace af
