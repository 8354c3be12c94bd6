// Golden files: every tests/golden/NAME.af is parsed; its diagnostics must equal NAME.diag and,
// when it loads, its canonical text must equal NAME.out (and read back to the same data).
// Run with AF_UPDATE_GOLDEN=1 to rewrite the expected files on purpose; see tests/golden/README.md.

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"
#include "golden_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

namespace af {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(AF_TEST_DIR) / "golden";

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
    const std::string text = test::readTextFile(input).value();
    const AFParseResult r = parseAF(text, input.filename().string());
    test::compareOrUpdateGolden(fs::path(input).replace_extension(".diag"), r.diagnostics.formatAll());
    const std::string canonical = r.ok() ? writeAFFile(r.file) : std::string();
    test::compareOrUpdateGolden(fs::path(input).replace_extension(".out"), canonical);
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
