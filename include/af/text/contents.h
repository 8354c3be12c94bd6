#pragma once
// Names of contents bits as .af files write them (docs/formats.md §1.9).

#include "af/text/decl_af.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// A list as the writer prints it: the mask's names as above, then the `unknown` names as they
// were written; only those when the mask is empty (a `none` first would read back the same, but
// is not what the file said).
std::string contentsToString(ContentsMask mask, const std::vector<std::string>& unknown);

// The accepted names, for messages.
std::string contentsNameList();

bool isDoom3AfContentsName(std::string_view name);

}  // namespace af
