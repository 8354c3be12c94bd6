// The canonical writer: layout, and the round trips parse -> write -> parse and write twice.

#include "af/text/af_writer.h"
#include "af_test_util.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace af {
namespace {

using test::parseOne;
using test::withRoot;

const std::string kEveryKey = R"af(articulatedFigure Every {
settings { model "m" skin "s" friction 0.1, 0.2, 0.3, 0.4 suspendSpeed 1, 2, 3, 4 noMoveTime 0.5
  noMoveTranslation 3 noMoveRotation 4 minMoveTime 1 maxMoveTime 9 totalMass 120
  contents body, corpse clipMask solid, moveableclip selfCollision 0 fastEval }
body "root" { joint "origin" mod position model dodecahedron( ( -1, -2, -3 ), ( 1, 2, 3 ) )
  origin bonecenter( "a", "b" ) angles ( 1, 2, 3 ) density 0.3 inertiaScale (1 0.5 0 0 1 0 0 0 2)
  friction 0.1, 0.2, 0.3 contents corpse, water clipMask none selfCollision 1 containedJoints "*origin"
  frictionDirection joint( "a" ) contactMotorDirection -( 0, 1, 0 ) }
body "b" { joint "b" model bone( joint( "a" ), joint( "b" ), 3.5 ) origin -bonedir( "a", "b" ) }
body "c" { joint "c" model cone( ( -1, -1, 0 ), ( 1, 1, 2 ), 17 ) }
fixed "f" { body1 "c" body2 "root" }
ballAndSocketJoint "bs" { body1 "b" body2 "root" anchor joint( "b" ) friction 0.25
  pyramidLimit ( 1, 0, 0 ), 30, 40, 1e-12, ( 0, 1, 0 ) }
universalJoint "u" { body1 "c" body2 "b" anchor ( 0, 0, 1 ) shafts ( 0, 0, 1 ), ( 0, 0, -1 ) coneLimit ( 0, 0, 1 ), 90 }
hinge "h" { body1 "c" body2 "world" axis ( 0, 1, 0 ) limit 10, 20, 30 }
slider "s" { body1 "b" axis -( 0, 0, 1 ) friction 0 }
spring "sp" { body1 "b" anchor1 ( 1, 1, 1 ) anchor2 ( 2, 2, 2 ) stretch 1 compress 2 damping 3 restLength 4
  minLength 1 maxLength 8 }
}
)af";

TEST(AFWriter, ParseWriteParseKeepsEveryValue) {
    const AFParseResult first = parseAF(kEveryKey, "every.af");
    ASSERT_TRUE(first.ok()) << first.diagnostics.formatAll();
    const std::string text = writeAFFile(first.file);
    const AFParseResult second = parseAF(text, "every.out");
    ASSERT_TRUE(second.ok()) << second.diagnostics.formatAll() << text;
    EXPECT_EQ(first.file, second.file) << text;
    EXPECT_EQ(writeAFFile(second.file), text);
}

TEST(AFWriter, LayoutFollowsTheEditor) {
    const DeclAF d = parseOne(withRoot(R"af(hinge "h" { body1 "root" axis ( 0, 0, 1 ) limit 0, 90, 0 })af"));
    const std::string text = writeDecl(d);
    EXPECT_TRUE(text.starts_with("\n\n/*\n")) << text;
    EXPECT_NE(text.find("*/\n\narticulatedFigure t {\n\nsettings {\n\tmodel \"\"\n\tskin \"\"\n"
                        "\tfriction 0.0099999998, 0.0099999998, 0.8000000119, 0.5\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("\nbody \"root\" {\n\tjoint \"origin\"\n\tmod orientation\n"
                        "\tmodel box( ( -10, -10, -10 ), ( 10, 10, 10 ) )\n\torigin ( 0, 0, 0 )\n"
                        "\tdensity 0.200000003\n\tfriction 0.0099999998, 0.0099999998, 0.8000000119\n"
                        "\tcontents corpse\n\tclipMask solid, corpse\n\tselfCollision 1\n"
                        "\tcontainedJoints \"*origin\"\n}\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("\nhinge \"h\" {\n\tbody1 \"root\"\n\tbody2 \"world\"\n\tanchor ( 0, 0, 0 )\n"
                        "\taxis ( 0, 0, 1 )\n\tfriction 0.5\n\tlimit 0, 90, 0\n}\n\n}"),
              std::string::npos)
        << text;
    EXPECT_TRUE(text.ends_with("}\n\n}")) << text;
}

TEST(AFWriter, OptionalBodyLinesOnlyWhenGiven) {
    const DeclAF plain = parseOne(withRoot(""));
    const std::string text = writeDecl(plain);
    EXPECT_EQ(text.find("angles"), std::string::npos);
    EXPECT_EQ(text.find("inertiaScale"), std::string::npos);
    EXPECT_EQ(text.find("frictionDirection"), std::string::npos);
    const DeclAF rich = parseOne(withRoot(R"af(body "b" { joint "j" inertiaScale (2 0 0 0 1 0 0 0 1)
        frictionDirection joint( "j" ) })af"));
    const std::string richText = writeDecl(rich);
    EXPECT_NE(richText.find("\tinertiaScale (2 0 0 0 1 0 0 0 1)\n"), std::string::npos) << richText;
    // Doom's editor would drop an unresolved joint direction; we keep it.
    EXPECT_NE(richText.find("\tfrictionDirection joint( \"j\" )\n"), std::string::npos) << richText;
}

TEST(AFWriter, BodyClipMaskOmitsTheForcedMoveableClipBit) {
    const DeclAF d = parseOne(withRoot(""));
    EXPECT_NE(writeDecl(d).find("\tclipMask solid, corpse\n\tselfCollision"), std::string::npos);
}

TEST(AFWriter, EmptyMaskIsWrittenAsNone) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" contents none })af"));
    EXPECT_NE(writeDecl(d).find("\tcontents none\n"), std::string::npos);
}

// Every sample figure we ship is stored exactly as the writer prints it.
TEST(AFWriter, SampleFiguresAreCanonical) {
    const std::filesystem::path dir = std::filesystem::path(AF_SOURCE_DIR) / "af";
    int checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".af") continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        const AFParseResult r = parseAF(text.str(), entry.path().filename().string());
        ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
        EXPECT_EQ(r.diagnostics.warningCount(), 0u) << r.diagnostics.formatAll();
        EXPECT_EQ(writeAFFile(r.file), text.str()) << entry.path() << " is not in canonical form";
        ++checked;
    }
    EXPECT_GE(checked, 3);
}

}  // namespace
}  // namespace af
