#pragma once
// Comparing text against expected files under tests/golden, and regenerating them on purpose
// with AF_UPDATE_GOLDEN=1 (see tests/golden/README.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace af::test {

inline bool updatingGolden() {
    const char* v = std::getenv("AF_UPDATE_GOLDEN");
    return v && *v && std::string(v) != "0";
}

inline std::optional<std::string> readTextFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return std::nullopt;
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A line diff by longest common subsequence: `-` expected lines, `+` actual ones.
inline std::string lineDiff(const std::string& expected, const std::string& actual) {
    auto split = [](const std::string& text) {
        std::vector<std::string> out;
        std::stringstream s(text);
        for (std::string line; std::getline(s, line);) out.push_back(line);
        return out;
    };
    const auto a = split(expected), b = split(actual);
    std::vector<std::vector<int>> lcs(a.size() + 1, std::vector<int>(b.size() + 1, 0));
    for (std::size_t i = a.size(); i-- > 0;)
        for (std::size_t j = b.size(); j-- > 0;)
            lcs[i][j] = a[i] == b[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);
    std::string out;
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (i < a.size() && j < b.size() && a[i] == b[j]) {
            out += "  " + a[i++] + "\n";
            ++j;
        } else if (j < b.size() && (i == a.size() || lcs[i][j + 1] >= lcs[i + 1][j])) {
            out += "+ " + b[j++] + "\n";
        } else {
            out += "- " + a[i++] + "\n";
        }
    }
    return out;
}

// `actual` must equal the file's text (an absent file reads as empty). When updating, the file
// is rewritten instead, or removed when `actual` is empty.
inline void compareOrUpdateGolden(const std::filesystem::path& expectedPath, const std::string& actual) {
    if (updatingGolden()) {
        if (actual.empty()) std::filesystem::remove(expectedPath);
        else std::ofstream(expectedPath, std::ios::binary) << actual;
        return;
    }
    const std::string expected = readTextFile(expectedPath).value_or("");
    EXPECT_EQ(expected, actual) << expectedPath.filename() << " differs (- expected, + actual):\n"
                                << lineDiff(expected, actual)
                                << "If the change is intended, regenerate with AF_UPDATE_GOLDEN=1.";
}

}  // namespace af::test
