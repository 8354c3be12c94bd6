// Fuzz target: any bytes given to the .def reader must give diagnostics, never a crash, and
// resolving inheritance over what was read must terminate.

#include "af/text/decl_def.h"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const af::DefParseResult parsed = af::parseDef(text, "fuzz.def");
    af::DefCollection collection;
    std::vector<af::Diagnostic> diagnostics;
    collection.add(parsed.file, diagnostics);
    (void)af::resolveDefInheritance(collection);
    return 0;
}
