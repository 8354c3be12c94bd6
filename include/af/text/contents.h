#pragma once
// Names of contents bits as .af files write them (docs/formats.md §1.9).

#include "af/text/decl_af.h"

#include <optional>
#include <string>
#include <string_view>

namespace af {

struct ContentsName {
    std::string_view name;
    ContentsMask bit;
    bool doom3Af;  // one of the five names Doom 3's AF parser knows
};

// The bit of a name (case-insensitive), 0 for `none`, nothing for an unknown name.
std::optional<ContentsMask> contentsBitFromName(std::string_view name);

// The names of a mask, `, `-separated: Doom 3's five first in its order (solid, body, corpse,
// playerclip, monsterclip), then any other named bits in bit order; `none` for an empty mask.
std::string contentsToString(ContentsMask mask);

// The accepted names, for messages.
std::string contentsNameList();

bool isDoom3AfContentsName(std::string_view name);

}  // namespace af
