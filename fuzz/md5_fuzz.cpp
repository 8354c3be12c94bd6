// Fuzz target: any bytes given to the md5mesh and md5anim readers must give diagnostics, never a
// crash; an anim that reads must evaluate every frame.

#include "af/text/md5.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const af::Md5MeshParseResult mesh = af::parseMd5Mesh(text, "fuzz.md5mesh");
    (void)mesh;
    const af::Md5AnimParseResult anim = af::parseMd5Anim(text, "fuzz.md5anim");
    if (anim.ok())
        for (int f = 0; f < anim.anim.frameCount && f < 64; ++f) (void)af::evaluateMd5AnimFrame(anim.anim, f);
    return 0;
}
