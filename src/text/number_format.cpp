#include "af/text/number_format.h"

#include <charconv>
#include <cstdio>

namespace af {

std::string formatDeclFloat(Real v) {
    const float f = static_cast<float>(v);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.10f", static_cast<double>(f));
    std::string text(buffer);
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();

    float back = 0;
    std::from_chars(text.data(), text.data() + text.size(), back);
    if (back == f) return text;

    // std::to_chars gives the shortest spelling that reads back as the same float.
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, f);
    (void)ec;
    return std::string(buffer, end);
}

}  // namespace af
