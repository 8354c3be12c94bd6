#pragma once
// Doom 3 `.map` files as plain data (docs/formats.md §5.6): a reader that keeps everything it
// reads and a canonical writer.
//
// Entities are key/value pairs plus primitives. brushDef3 brushes and patchDef2/patchDef3
// patches are read into numbers; any other primitive (old `brush`, brushDef2, Quake 3 style
// brushes) is kept as its text and written back unchanged.
//
// Numbers: every number is held as the float Doom stores, widened to double (Real), so that the
// writer's house format (formatDeclFloat, docs/formats.md §1.10) reads back to the same value.
// Coordinates: as written in the file, in Doom units. Doom subtracts an entity's `origin` from
// its patch control points and old-style brush points when it reads them and adds it back when
// it writes; we keep what the file says and do neither.
// Materials: as spelled. A file of version < 2 means `textures/<name>` (Doom prepends the
// prefix when it reads); materialPath() applies that rule.

#include "af/text/diagnostics.h"
#include "af/types.h"

#include <array>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace af {

struct MapKeyValue {
    std::string key;
    std::string value;
    SourceLocation where;  // of the key that set the value; {} for pairs set in code

    // Equal content; where it was read is not part of it.
    friend bool operator==(const MapKeyValue& a, const MapKeyValue& b) {
        return a.key == b.key && a.value == b.value;
    }
};

// Key/value pairs as idDict keeps them: in insertion order, looked up ignoring ASCII case.
class MapKeyValues {
public:
    // The pair for `key` (any case), or nullptr.
    const MapKeyValue* find(std::string_view key) const;
    bool contains(std::string_view key) const { return find(key) != nullptr; }
    // The value for `key`, or `fallback` when it is not set. The view lives as long as the pair.
    std::string_view value(std::string_view key, std::string_view fallback = {}) const;
    // A key already present (any case) keeps its place and first spelling and takes the new
    // value and position; a new key is appended.
    void set(std::string_view key, std::string_view value, SourceLocation where = {});

    const std::vector<MapKeyValue>& items() const { return items_; }
    std::size_t size() const { return items_.size(); }
    bool empty() const { return items_.empty(); }
    auto begin() const { return items_.begin(); }
    auto end() const { return items_.end(); }

    friend bool operator==(const MapKeyValues&, const MapKeyValues&) = default;

private:
    std::vector<MapKeyValue> items_;
};

// One side of a brushDef3: `( a b c d ) ( ( t00 t01 t02 ) ( t10 t11 t12 ) ) "material" f0 f1 f2`.
struct BrushSide {
    // The plane a·x + b·y + c·z + d = 0; (a, b, c) is the outward normal, not necessarily of
    // unit length, and −d/|(a,b,c)| the distance of the plane from the origin along it.
    std::array<Real, 4> plane{};
    // Texture coordinates relative to the default planar axes of the side (Doom's texMat).
    std::array<std::array<Real, 3>, 2> textureMatrix{};
    std::string material;
    // Quake 2's contents/flags/value, ignored by Doom; 0 0 0 when the file leaves them out.
    std::array<int, 3> flags{};

    friend bool operator==(const BrushSide&, const BrushSide&) = default;
};

struct BrushDef3 {
    MapKeyValues keys;  // editor-only pairs written inside the brush
    std::vector<BrushSide> sides;

    friend bool operator==(const BrushDef3&, const BrushDef3&) = default;
};

// A control point: x y z in Doom units, then the texture coordinates s t.
using PatchPoint = std::array<Real, 5>;

// patchDef2 `{ "material" ( w h 0 0 0 ) ( rows ) }`, or patchDef3 with explicit subdivisions
// `( w h subX subY 0 0 0 )`. The file holds w rows of h points each.
struct PatchDef {
    bool explicitSubdivisions = false;  // patchDef3
    std::string material;
    std::vector<Real> info;             // 5 numbers (patchDef2) or 7 (patchDef3), as read
    std::vector<std::vector<PatchPoint>> rows;
    MapKeyValues keys;                  // pairs after the control points (Doom reads them too)

    int width() const { return info.empty() ? 0 : int(info[0]); }
    int height() const { return info.size() < 2 ? 0 : int(info[1]); }

    friend bool operator==(const PatchDef&, const PatchDef&) = default;
};

// A primitive we do not interpret: the text between its braces, white space trimmed at both
// ends, comments included. It starts with a name (`brush`, `brushDef2`, ...) or, for a Quake 3
// style brush, with `(`.
struct RawPrimitive {
    std::string text;

    friend bool operator==(const RawPrimitive&, const RawPrimitive&) = default;
};

struct MapPrimitive {
    std::variant<BrushDef3, PatchDef, RawPrimitive> data;
    SourceLocation where;  // of the primitive's opening brace

    const BrushDef3* brush() const { return std::get_if<BrushDef3>(&data); }
    const PatchDef* patch() const { return std::get_if<PatchDef>(&data); }
    const RawPrimitive* raw() const { return std::get_if<RawPrimitive>(&data); }

    friend bool operator==(const MapPrimitive& a, const MapPrimitive& b) { return a.data == b.data; }
};

struct MapEntity {
    MapKeyValues keys;
    std::vector<MapPrimitive> primitives;
    SourceLocation where;  // of the entity's opening brace

    std::string_view value(std::string_view key, std::string_view fallback = {}) const {
        return keys.value(key, fallback);
    }
    void set(std::string_view key, std::string_view value) { keys.set(key, value); }

    friend bool operator==(const MapEntity& a, const MapEntity& b) {
        return a.keys == b.keys && a.primitives == b.primitives;
    }
};

struct MapFile {
    // The `Version` line's number; 1 when the file has none (Doom's rule), 2 is current.
    Real version = 2;
    std::vector<MapEntity> entities;  // the first is worldspawn

    // The first entity, or nullptr for a map without entities.
    const MapEntity* worldspawn() const { return entities.empty() ? nullptr : &entities.front(); }
    // The first entity whose `name` equals `name` ignoring case (how Doom finds entities).
    const MapEntity* findEntity(std::string_view name) const;
    MapEntity* findEntity(std::string_view name);

    friend bool operator==(const MapFile&, const MapFile&) = default;
};

// The material a side or patch means: the name as spelled, with Doom's implicit `textures/`
// prefix when the file's version is below 2.
std::string materialPath(const MapFile& map, std::string_view material);

struct MapParseResult {
    MapFile map;
    Diagnostics diagnostics;

    bool ok() const { return !diagnostics.hasErrors(); }
};

// Reads `text`; `fileName` is used in diagnostics. Errors are fatal, as in Doom: the first one
// (a missing brace, a value not on its key's line, a bad number, an unterminated string, the end
// of the file inside an entity, ...) is reported once with its position and reading stops, so a
// failed parse has exactly one error. `map` then holds what was read before it.
MapParseResult parseMapFile(std::string_view text, std::string fileName);

// Reads and parses a file; a file that cannot be read is an error diagnostic.
MapParseResult loadMapFile(const std::string& path);

// The canonical text (docs/formats.md §5.6): `Version <v>`, then each entity as `// entity i`,
// `{`, its pairs `"key" "value"` in order, each primitive as `// primitive j` (brushDef3 and
// patches in Doom's editor layout, raw primitives as kept), `}`. Numbers are written with
// formatDeclFloat. Every line ends with "\n". parse(write(m)) == m for every map that parse
// gives, and write(parse(write(m))) == write(m). Strings must not contain `"` or line breaks (the
// format has no escapes); parsed maps never do.
// Where we differ from Doom's writer, on purpose: the version written is the map's own (Doom
// writes 2 after prefixing old material names on read; we keep names as spelled), the side flags
// are written as kept, and patch key/value pairs are written after the control points.
std::string writeMapFile(const MapFile& map);

}  // namespace af
