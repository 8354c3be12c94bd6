// Fuzz target: any bytes given to the .map reader must give diagnostics, never a crash; a
// failed read has exactly one error; a map that loads must survive write -> parse -> write
// unchanged, and its brushes must build into solids or error values.

#include "af/geometry/brush.h"
#include "af/text/map_file.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

// The solid search is O(sides⁴); fuzzed brushes with hundreds of sides would only be slow.
constexpr std::size_t kMaxSidesToBuild = 64;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const af::MapParseResult first = af::parseMapFile(text, "fuzz.map");
    if (!first.ok()) {
        if (first.diagnostics.errorCount() != 1) std::abort();
        return 0;
    }
    const std::string written = af::writeMapFile(first.map);
    const af::MapParseResult second = af::parseMapFile(written, "fuzz.out");
    if (!second.ok() || !(second.map == first.map) || af::writeMapFile(second.map) != written) std::abort();
    for (const af::MapEntity& entity : first.map.entities) {
        for (const af::MapPrimitive& primitive : entity.primitives) {
            const af::BrushDef3* brush = primitive.brush();
            if (!brush || brush->sides.size() > kMaxSidesToBuild) continue;
            const af::BrushPolytope solid = af::polytopeFromBrush(*brush);
            if (solid.ok() != solid.polytope.has_value()) std::abort();
        }
    }
    return 0;
}
