// The canonical `.map` writer: Doom 3's editor layout (docs/formats.md §5.6), numbers in the
// house format of docs/formats.md §1.10.

#include "af/text/map_file.h"
#include "text_writer.h"

namespace af {

namespace {

class MapWriter : public text_detail::TextWriter<MapWriter> {
public:
    // `( v v v )` from any range of numbers.
    template <class Numbers>
    MapWriter& numbers(const Numbers& values) {
        raw("(");
        for (Real v : values) raw(" ").num(v);
        return raw(" )");
    }

    void pairs(const MapKeyValues& keys, std::string_view indent) {
        for (const MapKeyValue& kv : keys) raw(indent).quoted(kv.key).raw(" ").quoted(kv.value).raw("\n");
    }

    void brush(const BrushDef3& b) {
        raw(" brushDef3\n {\n");
        pairs(b.keys, "  ");
        for (const BrushSide& s : b.sides) {
            raw("  ").numbers(s.plane).raw(" ( ").numbers(s.textureMatrix[0]).raw(" ").numbers(s.textureMatrix[1]);
            raw(" ) ").quoted(s.material);
            for (int f : s.flags) raw(" ").raw(std::to_string(f));
            raw("\n");
        }
        raw(" }\n");
    }

    void patch(const PatchDef& p) {
        raw(p.explicitSubdivisions ? " patchDef3\n {\n" : " patchDef2\n {\n");
        raw("  ").quoted(p.material).raw("\n");
        raw("  ").numbers(p.info).raw("\n");
        raw("  (\n");
        for (const std::vector<PatchPoint>& row : p.rows) {
            raw("   (");
            for (const PatchPoint& point : row) raw(" ").numbers(point);
            raw(" )\n");
        }
        raw("  )\n");
        pairs(p.keys, "  ");
        raw(" }\n");
    }

    void primitive(const MapPrimitive& p, std::size_t index) {
        raw("// primitive ").raw(std::to_string(index)).raw("\n{\n");
        if (const BrushDef3* b = p.brush()) brush(*b);
        else if (const PatchDef* patchDef = p.patch()) patch(*patchDef);
        else if (const RawPrimitive* r = p.raw()) raw(r->text).raw("\n");
        raw("}\n");
    }

    void entity(const MapEntity& e, std::size_t index) {
        raw("// entity ").raw(std::to_string(index)).raw("\n{\n");
        pairs(e.keys, "");
        for (std::size_t j = 0; j < e.primitives.size(); ++j) primitive(e.primitives[j], j);
        raw("}\n");
    }
};

}  // namespace

std::string writeMapFile(const MapFile& map) {
    MapWriter w;
    w.raw("Version ").num(map.version).raw("\n");
    for (std::size_t i = 0; i < map.entities.size(); ++i) w.entity(map.entities[i], i);
    return w.take();
}

}  // namespace af
