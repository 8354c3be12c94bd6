// Fuzz target: any bytes given to the .af parser must give diagnostics, never a crash; a file
// that loads must survive write -> parse -> write unchanged.

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const af::AFParseResult first = af::parseAF(text, "fuzz.af");
    if (!first.ok()) return 0;
    const std::string written = af::writeAFFile(first.file);
    const af::AFParseResult second = af::parseAF(written, "fuzz.out");
    if (!second.ok() || !(second.file == first.file) || af::writeAFFile(second.file) != written) std::abort();
    return 0;
}
