#pragma once
// Doom 3's registered decl types (DeclManager.cpp and the game's): any of them may appear in any
// decl file (docs/formats.md §1.1), so both the .def and the .af reader must know them.

#include "af/text/strings.h"

#include <array>
#include <string_view>

namespace af {

inline constexpr std::array<std::string_view, 15> kDoomDeclTypes = {
    "table", "material", "skin", "sound", "entityDef", "mapDef", "fx", "particle", "articulatedFigure",
    "pda", "video", "audio", "email", "model", "export"};

// `word` names a decl type, ignoring case.
inline bool isDoomDeclType(std::string_view word) {
    for (std::string_view type : kDoomDeclTypes)
        if (equalsIgnoreCase(word, type)) return true;
    return false;
}

}  // namespace af
