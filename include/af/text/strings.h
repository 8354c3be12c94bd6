#pragma once
// Small string helpers for the case-insensitive names of id Tech 4 files.

#include <string>
#include <string_view>

namespace af {

// ASCII case-insensitive equality, as idStr::Icmp compares.
bool equalsIgnoreCase(std::string_view a, std::string_view b);

std::string toLower(std::string_view s);

// A decl name as Doom canonicalises it: `\` becomes `/`, lower case, and the text from the
// last `.` on removed (docs/formats.md §1.1).
std::string canonicalDeclName(std::string_view name);

}  // namespace af
