// Golden files: every tests/golden/NAME.af is parsed; its diagnostics must equal NAME.diag and,
// when it loads, its canonical text must equal NAME.out (and read back to the same data).
// Run with AF_UPDATE_GOLDEN=1 to rewrite the expected files on purpose; see tests/golden/README.md.

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace af {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(AF_TEST_DIR) / "golden";

bool updating() {
    const char* v = std::getenv("AF_UPDATE_GOLDEN");
    return v && *v && std::string(v) != "0";
}

std::optional<std::string> readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return std::nullopt;
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string line; std::getline(s, line);) out.push_back(line);
    return out;
}

// A line diff (longest common subsequence), `-` for expected lines, `+` for actual ones.
std::string lineDiff(const std::string& expected, const std::string& actual) {
    const auto a = lines(expected), b = lines(actual);
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

void compareOrUpdate(const fs::path& expectedPath, const std::string& actual) {
    if (updating()) {
        if (actual.empty()) {
            fs::remove(expectedPath);
        } else {
            std::ofstream(expectedPath, std::ios::binary) << actual;
        }
        return;
    }
    const std::string expected = readFile(expectedPath).value_or("");
    EXPECT_EQ(expected, actual) << expectedPath.filename() << " differs (- expected, + actual):\n"
                                << lineDiff(expected, actual)
                                << "If the change is intended, regenerate with AF_UPDATE_GOLDEN=1.";
}

std::vector<fs::path> goldenInputs() {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(kGoldenDir))
        if (e.path().extension() == ".af") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

class Golden : public testing::TestWithParam<fs::path> {};

TEST_P(Golden, MatchesExpectedDiagnosticsAndCanonicalText) {
    const fs::path input = GetParam();
    const std::string text = readFile(input).value();
    const AFParseResult r = parseAF(text, input.filename().string());
    compareOrUpdate(fs::path(input).replace_extension(".diag"), r.diagnostics.formatAll());
    const std::string canonical = r.ok() ? writeAFFile(r.file) : std::string();
    compareOrUpdate(fs::path(input).replace_extension(".out"), canonical);
    if (!r.ok()) return;
    const AFParseResult again = parseAF(canonical, "canonical");
    ASSERT_TRUE(again.ok()) << again.diagnostics.formatAll();
    EXPECT_EQ(again.file, r.file);
    EXPECT_EQ(writeAFFile(again.file), canonical);
}

INSTANTIATE_TEST_SUITE_P(Files, Golden, testing::ValuesIn(goldenInputs()),
                         [](const testing::TestParamInfo<fs::path>& info) {
                             std::string name = info.param.stem().string();
                             std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                             return name;
                         });

TEST(Golden, DirectoryHasValidAndMalformedInputs) {
    int valid = 0, malformed = 0;
    for (const fs::path& p : goldenInputs()) (fs::exists(fs::path(p).replace_extension(".out")) ? valid : malformed)++;
    EXPECT_GE(valid, 3);
    EXPECT_GE(malformed, 3);
}

}  // namespace
}  // namespace af
