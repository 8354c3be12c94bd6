#include "af/text/strings.h"

namespace af {

namespace {
char lowerAscii(char c) { return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c; }
}  // namespace

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (lowerAscii(a[i]) != lowerAscii(b[i])) return false;
    return true;
}

std::string toLower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = lowerAscii(c);
    return out;
}

std::string canonicalDeclName(std::string_view name) {
    std::string out = toLower(name);
    for (char& c : out)
        if (c == '\\') c = '/';
    if (std::size_t dot = out.rfind('.'); dot != std::string::npos) out.erase(dot);
    return out;
}

}  // namespace af
