#pragma once
// Small text helpers the console's messages and tables share.

#include "af/types.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace af::console {

// A name as messages quote it: 'name'.
inline std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// `text` padded with spaces to `width` columns (never cut), for aligned tables.
inline std::string padded(const std::string& text, std::size_t width) {
    return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

// `v` with `decimals` decimals, and never "-0.00".
inline std::string fixed(Real v, int decimals = 2) {
    if (std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0;
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    return buffer;
}

// `v` to three significant digits.
inline std::string general(Real v) {
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
    return buffer;
}

}  // namespace af::console
