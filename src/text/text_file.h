#pragma once
// Reading a whole text file, for the parsers' load functions.

#include <optional>
#include <string>

namespace af {

// The file's bytes, or nothing when it cannot be opened.
std::optional<std::string> readWholeFile(const std::string& path);

}  // namespace af
