// Golden .map files: every tests/golden/NAME.map is parsed; its diagnostics must equal NAME.diag
// and, when it loads, its canonical text must equal NAME.out, read back to the same data and
// write again to the same bytes. AF_UPDATE_GOLDEN=1 rewrites the expected files:
//   AF_UPDATE_GOLDEN=1 build/tests/text/test_text --gtest_filter='*MapGolden*'
// Inputs: map_brushes_patches (brushes, patches, key rules, number spellings), map_kept_as_text
// (brushDef2 and a Quake 3 brush kept verbatim, CRLF), map_no_version (version 1); malformed:
// map_bad_value_line, map_bad_eof_in_entity, map_bad_number.

#include "af/text/map_file.h"
#include "golden_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace af {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> goldenMaps() {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(fs::path(AF_TEST_DIR) / "golden"))
        if (e.path().extension() == ".map") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

class MapGolden : public testing::TestWithParam<fs::path> {};

TEST_P(MapGolden, MatchesExpectedDiagnosticsAndCanonicalText) {
    const fs::path input = GetParam();
    const std::string text = test::readTextFile(input).value();
    const MapParseResult r = parseMapFile(text, input.filename().string());
    test::compareOrUpdateGolden(fs::path(input).replace_extension(".diag"), r.diagnostics.formatAll());
    const std::string canonical = r.ok() ? writeMapFile(r.map) : std::string();
    test::compareOrUpdateGolden(fs::path(input).replace_extension(".out"), canonical);
    if (!r.ok()) {
        EXPECT_EQ(r.diagnostics.errorCount(), 1u);
        return;
    }
    const MapParseResult again = parseMapFile(canonical, "canonical");
    ASSERT_TRUE(again.ok()) << again.diagnostics.formatAll();
    EXPECT_EQ(again.map, r.map);
    EXPECT_EQ(writeMapFile(again.map), canonical);
}

INSTANTIATE_TEST_SUITE_P(Files, MapGolden, testing::ValuesIn(goldenMaps()),
                         [](const testing::TestParamInfo<fs::path>& info) {
                             std::string name = info.param.stem().string();
                             std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                             return name;
                         });

TEST(MapGolden, DirectoryHasValidAndMalformedMaps) {
    int valid = 0, malformed = 0;
    for (const fs::path& p : goldenMaps()) (fs::exists(fs::path(p).replace_extension(".out")) ? valid : malformed)++;
    EXPECT_GE(valid, 3);
    EXPECT_GE(malformed, 3);
}

}  // namespace
}  // namespace af
