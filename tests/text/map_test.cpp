// .map files: entities, keys, brushDef3 sides and patches read with their values, everything
// else kept; the canonical writer and its round trips; one located error per malformed input.

#include "af/text/map_file.h"
#include "golden_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace af {
namespace {

MapFile parseMapGood(const std::string& text) {
    const MapParseResult r = parseMapFile(text, "test.map");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.diagnostics.warningCount(), 0u) << r.diagnostics.formatAll();
    return r.map;
}

// The one error of a malformed input, formatted.
std::string errorOf(const std::string& text) {
    const MapParseResult r = parseMapFile(text, "bad.map");
    EXPECT_EQ(r.diagnostics.errorCount(), 1u) << r.diagnostics.formatAll();
    return r.diagnostics.formatAll();
}

constexpr const char* kTexture = "( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) )";

std::string side(const std::string& plane, const std::string& material = "\"textures/af/floor\" 0 0 0") {
    return "  ( " + plane + " ) " + kTexture + " " + material + "\n";
}

TEST(MapParser, ReadsEntitiesKeysAndBrushSides) {
    const MapFile m = parseMapGood("Version 2\n"
                                "{\n"
                                "\"classname\" \"worldspawn\"\n"
                                "{\n"
                                " brushDef3\n"
                                " {\n"
                                "  \"editorKey\" \"v\"\n"
                                "  ( 0 0 -1 -16 ) ( ( 0.5 0 -3 ) ( 0 .25 1e1 ) ) \"textures/af/floor\" 1 -2 3\n"
                                "  ( -0.6 0.8 0 12.5 ) " + std::string(kTexture) + " af/unquoted\n"
                                " }\n"
                                "}\n"
                                "}\n"
                                "{\n"
                                "\"classname\" \"info_player_start\"\n"
                                "\"origin\" \"-128 0 0\"\n"
                                "}\n");
    EXPECT_EQ(m.version, 2);
    ASSERT_EQ(m.entities.size(), 2u);
    const MapEntity& world = m.entities[0];
    EXPECT_EQ(m.worldspawn(), &world);
    EXPECT_EQ(world.where, (SourceLocation{2, 1}));
    EXPECT_EQ(world.value("classname"), "worldspawn");
    ASSERT_EQ(world.primitives.size(), 1u);
    EXPECT_EQ(world.primitives[0].where, (SourceLocation{4, 1}));
    const BrushDef3* brush = world.primitives[0].brush();
    ASSERT_NE(brush, nullptr);
    EXPECT_EQ(brush->keys.value("editorKey"), "v");
    ASSERT_EQ(brush->sides.size(), 2u);
    const BrushSide& s0 = brush->sides[0];
    EXPECT_EQ(s0.plane, (std::array<Real, 4>{0, 0, -1, -16}));
    EXPECT_EQ(s0.textureMatrix[0], (std::array<Real, 3>{0.5, 0, -3}));
    EXPECT_EQ(s0.textureMatrix[1], (std::array<Real, 3>{0, 0.25, 10}));
    EXPECT_EQ(s0.material, "textures/af/floor");
    EXPECT_EQ(s0.flags, (std::array<int, 3>{1, -2, 3}));
    const BrushSide& s1 = brush->sides[1];
    // Numbers are the floats Doom stores, widened.
    EXPECT_EQ(s1.plane, (std::array<Real, 4>{Real(-0.6f), Real(0.8f), 0, 12.5}));
    EXPECT_EQ(s1.material, "af/unquoted");
    EXPECT_EQ(s1.flags, (std::array<int, 3>{0, 0, 0}));  // left out: Doom ignores them
    EXPECT_EQ(m.entities[1].value("origin"), "-128 0 0");
    EXPECT_TRUE(m.entities[1].primitives.empty());
}

TEST(MapParser, ReadsPatchDef2AndPatchDef3ControlPointRows) {
    const MapFile m = parseMapGood("Version 2\n{\n\"classname\" \"worldspawn\"\n"
                                "{\n patchDef2\n {\n  \"textures/af/curve\"\n  ( 2 3 0 0 0 )\n  (\n"
                                "   ( ( 0 0 0 0 0 ) ( 0 10 0 0 0.5 ) ( 0 20 0 0 1 ) )\n"
                                "   ( ( 10 0 5 1 0 ) ( 10 10 5 1 0.5 ) ( 10 20 -5 1 1 ) )\n"
                                "  )\n }\n}\n"
                                "{\n patchDef3\n {\n  curve\n  ( 1 2 4 6 0 0 0 )\n  (\n"
                                "   ( ( 1 2 3 4 5 ) ( 6 7 8 9 10 ) )\n"
                                "  )\n  \"k\" \"v\"\n }\n}\n}\n");
    const MapEntity& world = m.entities.at(0);
    ASSERT_EQ(world.primitives.size(), 2u);
    const PatchDef* p2 = world.primitives[0].patch();
    ASSERT_NE(p2, nullptr);
    EXPECT_FALSE(p2->explicitSubdivisions);
    EXPECT_EQ(p2->material, "textures/af/curve");
    EXPECT_EQ(p2->info, (std::vector<Real>{2, 3, 0, 0, 0}));
    EXPECT_EQ(p2->width(), 2);
    EXPECT_EQ(p2->height(), 3);
    ASSERT_EQ(p2->rows.size(), 2u);  // width rows of height points
    ASSERT_EQ(p2->rows[1].size(), 3u);
    EXPECT_EQ(p2->rows[1][2], (PatchPoint{10, 20, -5, 1, 1}));
    EXPECT_EQ(p2->rows[0][1], (PatchPoint{0, 10, 0, 0, 0.5}));
    const PatchDef* p3 = world.primitives[1].patch();
    ASSERT_NE(p3, nullptr);
    EXPECT_TRUE(p3->explicitSubdivisions);
    EXPECT_EQ(p3->info, (std::vector<Real>{1, 2, 4, 6, 0, 0, 0}));
    EXPECT_EQ(p3->rows, (std::vector<std::vector<PatchPoint>>{{{1, 2, 3, 4, 5}, {6, 7, 8, 9, 10}}}));
    EXPECT_EQ(p3->keys.value("k"), "v");
}

TEST(MapParser, KeysAreCaseInsensitiveAndARepeatedKeyOverwritesInPlace) {
    const MapFile m = parseMapGood("{\n\"classname\" \"worldspawn\"\n\"Gravity\" \"800\"\n\"name\" \"w\"\n"
                                "\"gravity\" \"1066\"\n\"message  \" \"trailing blanks go  \t\"\n}\n");
    const MapEntity& e = m.entities.at(0);
    ASSERT_EQ(e.keys.size(), 4u);
    EXPECT_EQ(e.keys.items()[1].key, "Gravity");  // the first spelling and place are kept
    EXPECT_EQ(e.keys.items()[1].value, "1066");
    EXPECT_EQ(e.keys.items()[1].where, (SourceLocation{5, 1}));  // where the value came from
    EXPECT_EQ(e.value("GRAVITY"), "1066");
    EXPECT_EQ(e.keys.items()[3].key, "message");
    EXPECT_EQ(e.value("message"), "trailing blanks go");
    EXPECT_EQ(e.value("missing", "fallback"), "fallback");
    EXPECT_FALSE(e.keys.contains("missing"));
    EXPECT_EQ(m.findEntity("W"), &e);
    EXPECT_EQ(m.findEntity("x"), nullptr);
}

TEST(MapEntity, SetOverwritesInPlaceAndAppendsNewKeys) {
    MapEntity e;
    e.set("classname", "worldspawn");
    e.set("origin", "0 0 0");
    e.set("ORIGIN", "1 2 3");
    e.set("name", "n");
    ASSERT_EQ(e.keys.size(), 3u);
    EXPECT_EQ(e.keys.items()[1].key, "origin");
    EXPECT_EQ(e.keys.items()[1].value, "1 2 3");
    EXPECT_EQ(e.keys.items()[2].key, "name");
}

TEST(MapParser, NoVersionLineMeansVersionOneWithImplicitTexturesPrefix) {
    const MapFile m = parseMapGood("{\n\"classname\" \"worldspawn\"\n{\nbrushDef3\n{\n" + side("0 0 1 0", "floor") + "}\n}\n}\n");
    EXPECT_EQ(m.version, 1);
    const BrushSide& s = m.entities.at(0).primitives.at(0).brush()->sides.at(0);
    EXPECT_EQ(s.material, "floor");  // kept as spelled
    EXPECT_EQ(materialPath(m, s.material), "textures/floor");
    EXPECT_TRUE(writeMapFile(m).starts_with("Version 1\n"));
    MapFile v2 = m;
    v2.version = 2;
    EXPECT_EQ(materialPath(v2, s.material), "floor");
}

TEST(MapParser, OtherPrimitivesAreKeptAsTheirText) {
    const std::string oldBrush = "brush\n {\n  ( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) /* comment */ af/x 0 0 0 0.5 0.5\n }";
    const std::string q3Brush = "( 0 0 64 ) ( 64 0 64 ) ( 0 64 64 ) af/q3 0 0 0 0.5 0.5 0 0 0";
    const std::string patch1 = "patchDef1 { \"not one we read\" }";
    const MapFile m = parseMapGood("Version 2\n{\n\"classname\" \"worldspawn\"\n{\n" + oldBrush + "\n}\n{  " + q3Brush +
                                "\n\n}\n{" + patch1 + "}\n}\n");
    const MapEntity& e = m.entities.at(0);
    ASSERT_EQ(e.primitives.size(), 3u);
    ASSERT_NE(e.primitives[0].raw(), nullptr);
    EXPECT_EQ(e.primitives[0].raw()->text, oldBrush);
    EXPECT_EQ(e.primitives[1].raw()->text, q3Brush);  // white space around it trimmed
    EXPECT_EQ(e.primitives[2].raw()->text, patch1);
    const std::string written = writeMapFile(m);
    EXPECT_NE(written.find("// primitive 0\n{\n" + oldBrush + "\n}\n"), std::string::npos) << written;
    EXPECT_NE(written.find("// primitive 1\n{\n" + q3Brush + "\n}\n"), std::string::npos) << written;
    EXPECT_EQ(parseMapGood(written), m);
}

TEST(MapWriter, WritesDoomsEditorLayout) {
    MapFile m;
    MapEntity& world = m.entities.emplace_back();
    world.set("classname", "worldspawn");
    BrushDef3 brush;
    brush.keys.set("k", "v");
    brush.sides.push_back({{0, 0, 1, -0.2}, {{{0.0078125, 0, 0}, {0, 0.0078125, 0}}}, "textures/af/floor", {}});
    world.primitives.push_back({brush, {}});
    PatchDef patch;
    patch.material = "textures/af/curve";
    patch.info = {1, 2, 0, 0, 0};
    patch.rows = {{{0, 0, 0, 0, 0}, {1, 2, 3, 0.5, 1}}};
    world.primitives.push_back({patch, {}});
    // Assigned in place: GCC 12 warns falsely (-Wmaybe-uninitialized) about the patch alternative
    // when a primitive holding raw text is moved into the vector.
    world.primitives.emplace_back().data = RawPrimitive{"( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) x 0 0 0 1 1"};
    m.entities.emplace_back().set("classname", "light");
    EXPECT_EQ(writeMapFile(m),
              "Version 2\n"
              "// entity 0\n{\n\"classname\" \"worldspawn\"\n"
              "// primitive 0\n{\n brushDef3\n {\n  \"k\" \"v\"\n"
              "  ( 0 0 1 -0.200000003 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) \"textures/af/floor\" 0 0 0\n"
              " }\n}\n"
              "// primitive 1\n{\n patchDef2\n {\n  \"textures/af/curve\"\n  ( 1 2 0 0 0 )\n  (\n"
              "   ( ( 0 0 0 0 0 ) ( 1 2 3 0.5 1 ) )\n  )\n }\n}\n"
              "// primitive 2\n{\n( 0 0 0 ) ( 1 0 0 ) ( 0 1 0 ) x 0 0 0 1 1\n}\n"
              "}\n"
              "// entity 1\n{\n\"classname\" \"light\"\n}\n");
}

TEST(MapWriter, ReadWriteReadGivesTheSameMapAndWritingIsStable) {
    const std::string text = "Version 2\n{\n\"classname\" \"worldspawn\"\n{\nbrushDef3\n{\n" +
                             side("0.1 -0.7 0.3 1e-12") + side("0 0 -1 123456.789", "m 5 6 7") +
                             "}\n}\n}\n{\n\"classname\" \"x\"\n}\n";
    const MapFile first = parseMapGood(text);
    const std::string written = writeMapFile(first);
    const MapFile second = parseMapGood(written);
    EXPECT_EQ(second, first);
    EXPECT_EQ(writeMapFile(second), written);
    EXPECT_NE(written.find("( 0.1000000015 -0.6999999881 0.3000000119 1e-12 )"), std::string::npos) << written;
    EXPECT_NE(written.find("( 0 0 -1 123456.7890625 )"), std::string::npos) << written;
}

TEST(MapWriter, EqualityIgnoresWhereThingsWereRead) {
    const MapFile a = parseMapGood("{\n\"classname\" \"worldspawn\"\n}\n");
    const MapFile b = parseMapGood("\n\n   {  \"classname\"    \"worldspawn\" }");
    EXPECT_NE(a.entities[0].where, b.entities[0].where);
    EXPECT_EQ(a, b);
}

// Each kind of malformed input gives exactly one error, at the place reading stopped.

TEST(MapParserErrors, MissingBraceOfAnEntity) {
    EXPECT_EQ(errorOf("Version 2\n\"classname\" \"worldspawn\"\n}\n"),
              "bad.map:2:1: error: expected '{' to open entity 0, found \"classname\"\n");
}

TEST(MapParserErrors, MissingBraceAroundAPrimitive) {
    // The brush's `}` is missing: the primitive's `}` closes the brush, the entity's `}` closes
    // the primitive, and the next entity's `{` reads as a primitive that starts with a string.
    EXPECT_EQ(errorOf("Version 2\n{\n\"classname\" \"worldspawn\"\n{\n brushDef3\n {\n" + side("0 0 1 0") +
                      "}\n}\n{\n\"classname\" \"light\"\n}\n"),
              "bad.map:11:1: error: expected a primitive (brushDef3, patchDef2, patchDef3, another primitive name "
              "or the '(' of a Quake 3 brush side) in primitive 1, found \"classname\"\n");
    EXPECT_EQ(errorOf("{\n\"classname\" \"worldspawn\"\n{\nbrushDef3\n{\n" + side("0 0 1 0") + "}\n\"k\" \"v\"\n}\n"),
              "bad.map:8:1: error: expected '}' to close primitive 0 (opened at line 3), found \"k\"\n");
}

TEST(MapParserErrors, ValueNotOnTheKeysLine) {
    EXPECT_EQ(errorOf("{\n\"classname\" \"worldspawn\"\n\"message\"\n  \"next line\"\n}\n"),
              "bad.map:4:3: error: expected the value of \"message\" in double quotes on the same line, found "
              "\"next line\"\n");
    EXPECT_EQ(errorOf("{\n\"classname\" }\n"),
              "bad.map:2:13: error: expected the value of \"classname\" in double quotes on the same line, found '}'\n");
}

TEST(MapParserErrors, BadNumbers) {
    EXPECT_EQ(errorOf("{\n{\nbrushDef3\n{\n  ( 0 0 1 x ) " + std::string(kTexture) + " m\n}\n}\n}\n"),
              "bad.map:5:11: error: expected a number for the side's plane ( a b c d ), found 'x'\n");
    EXPECT_EQ(errorOf("{\n{\nbrushDef3\n{\n  ( 0 0 1 1.2.3 ) " + std::string(kTexture) + " m\n}\n}\n}\n"),
              "bad.map:5:11: error: more than one dot in number '1.2.3'\n");
    EXPECT_EQ(errorOf("{\n{\nbrushDef3\n{\n  ( 0 0 1 1e39 ) " + std::string(kTexture) + " m\n}\n}\n}\n"),
              "bad.map:5:11: error: the side's plane ( a b c d ) is out of range for a 32-bit float, found '1e39'\n");
    EXPECT_EQ(errorOf("{\n{\nbrushDef3\n{\n  ( 0 0 1 0 ) " + std::string(kTexture) + " m 1 2.5 3\n}\n}\n}\n"),
              "bad.map:5:59: error: expected an integer for the side's flags (three integers), found '2.5'\n");
    EXPECT_EQ(errorOf("Version\n2\n"), "bad.map:2:1: error: expected the map version on the same line as "
                                       "'Version', found '2'\n");
}

TEST(MapParserErrors, UnterminatedString) {
    EXPECT_EQ(errorOf("{\n\"classname\" \"worldspawn\n}\n"), "bad.map:2:13: error: newline inside a quoted string\n");
    EXPECT_EQ(errorOf("{\n\"classname\" \"worldspawn"), "bad.map:2:13: error: missing closing quote\n");
}

TEST(MapParserErrors, EndOfFileInsideAnEntity) {
    EXPECT_EQ(errorOf("Version 2\n{\n\"classname\" \"worldspawn\"\n"),
              "bad.map:4:1: error: expected a key in double quotes, '{' to open a primitive or '}' to close "
              "entity 0 (opened at line 2), found end of file\n");
    EXPECT_EQ(errorOf("{\n}\n{\n{\n( 0 0 0 ) ( 1 0 0 )"),
              "bad.map:5:20: error: expected '}' to close primitive 0 (opened at line 4), found end of file\n");
    EXPECT_EQ(errorOf("{\n/* never closed\n}\n"), "bad.map:2:1: error: comment opened here is never closed with '*/'\n");
}

TEST(MapParserErrors, EmptyPrimitiveAndBadPatchSize) {
    EXPECT_EQ(errorOf("{\n{ }\n}\n"), "bad.map:2:3: error: expected a primitive (brushDef3, patchDef2, patchDef3, another "
                                      "primitive name or the '(' of a Quake 3 brush side) in primitive 0, found '}'\n");
    EXPECT_EQ(errorOf("{\n{\npatchDef2\n{\nm\n( 2.5 3 0 0 0 )\n(\n)\n}\n}\n}\n"),
              "bad.map:6:3: error: the patch width must be a whole number from 1 to 1024\n");
    EXPECT_EQ(errorOf("{\n{\npatchDef2\n{\nm\n( 1 2 0 0 0 )\n(\n( ( 0 0 0 0 0 ) )\n)\n}\n}\n}\n"),
              "bad.map:8:17: error: expected '(' to open point 2 of 2 in row 1 of 1, found ')'\n");
}

TEST(MapParserErrors, PartialMapIsKeptUpToTheError) {
    const MapParseResult r = parseMapFile("{\n\"classname\" \"worldspawn\"\n}\n{\n\"a\" \"b\"\n\"c\"\n", "bad.map");
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.map.entities.size(), 2u);
    EXPECT_EQ(r.map.entities[1].value("a"), "b");
}

// The maps we ship are stored exactly as the writer prints them.
TEST(MapWriter, ShippedMapsAreCanonical) {
    const std::filesystem::path dir = std::filesystem::path(AF_SOURCE_DIR) / "maps";
    int checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".map") continue;
        const std::string text = test::readTextFile(entry.path()).value();
        const MapParseResult r = parseMapFile(text, entry.path().filename().string());
        ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
        EXPECT_EQ(r.diagnostics.warningCount(), 0u) << r.diagnostics.formatAll();
        EXPECT_EQ(writeMapFile(r.map), text) << entry.path() << " is not in canonical form";
        ++checked;
    }
    EXPECT_GE(checked, 1);
}

TEST(MapFile, DefaultMapHasWorldspawnFirstAndAPlayerStart) {
    const MapParseResult r = loadMapFile(std::string(AF_SOURCE_DIR) + "/maps/default.map");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    ASSERT_GE(r.map.entities.size(), 2u);
    EXPECT_EQ(r.map.worldspawn()->value("classname"), "worldspawn");
    EXPECT_EQ(r.map.findEntity("info_player_start_1")->value("classname"), "info_player_start");
    EXPECT_EQ(r.map.worldspawn()->primitives.size(), 4u);
}

}  // namespace
}  // namespace af
