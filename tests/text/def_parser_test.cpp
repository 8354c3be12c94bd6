// .def files: entityDef and model decls kept, every other decl kind skipped by brace matching,
// and only true syntax errors reported, each at its place.

#include "af/text/decl_def.h"

#include <gtest/gtest.h>

#include <string>

namespace af {
namespace {

DefFile parseDefGood(const std::string& text) {
    const DefParseResult r = parseDef(text, "test.def");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.diagnostics.warningCount(), 0u) << r.diagnostics.formatAll();
    return r.file;
}

std::string diagnosticsOf(const std::string& text) { return parseDef(text, "bad.def").diagnostics.formatAll(); }

TEST(DefParser, KeepsEntityDefKeyValuesInOrder) {
    const DefFile f = parseDefGood(
        "entityDef Ragdoll_Humanoid.v2 {\n"
        "\t\"spawnclass\"\t\"idAFEntity_Generic\"\n"
        "\t\"model\"\t\t\"humanoid\"\n"
        "\t\"mass\"\t\t150.5\n"
        "\t\"skin\"\t\tskins/plain\n"
        "}\n");
    ASSERT_EQ(f.entityDefs.size(), 1u);
    const EntityDef& def = f.entityDefs[0];
    EXPECT_EQ(def.name, "ragdoll_humanoid");
    EXPECT_EQ(def.writtenName, "Ragdoll_Humanoid.v2");
    EXPECT_EQ(def.file, "test.def");
    EXPECT_EQ(def.where, (SourceLocation{1, 11}));
    ASSERT_EQ(def.keyValues.size(), 4u);
    EXPECT_EQ(def.keyValues[0].key, "spawnclass");
    EXPECT_EQ(def.keyValues[0].value, "idAFEntity_Generic");
    EXPECT_EQ(def.keyValues[2].value, "150.5");  // any token is a value, kept as spelled
    EXPECT_EQ(def.keyValues[3].value, "skins/plain");
    EXPECT_EQ(def.valueOr("MODEL"), "humanoid");
    EXPECT_EQ(def.valueOr("nodrop", "0"), "0");
}

TEST(DefParser, RepeatedKeyWarnsAndTheLaterValueWins) {
    const DefParseResult r = parseDef(
        "entityDef a {\n"
        "\t\"model\" \"one\"\n"
        "\t\"MODEL\" \"two\"\n"
        "}\n",
        "test.def");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(),
              "test.def:3:2: warning: key \"MODEL\" is set again (first at line 2); the later value is used\n");
    ASSERT_EQ(r.file.entityDefs[0].keyValues.size(), 1u);
    EXPECT_EQ(r.file.entityDefs[0].keyValues[0].key, "model");
    EXPECT_EQ(r.file.entityDefs[0].keyValues[0].value, "two");
}

TEST(DefParser, NameBeforeBraceIsAnEntityDefAndTypeKeywordsIgnoreCase) {
    const DefFile f = parseDefGood(
        "plain_name { \"a\" \"1\" }\n"
        "ENTITYDEF shouted { \"b\" \"2\" }\n"
        "Model mixed { mesh m.md5mesh }\n");
    ASSERT_EQ(f.entityDefs.size(), 2u);
    EXPECT_EQ(f.entityDefs[0].name, "plain_name");
    EXPECT_EQ(f.entityDefs[1].name, "shouted");
    ASSERT_EQ(f.models.size(), 1u);
    EXPECT_EQ(f.models[0].name, "mixed");
}

TEST(DefParser, KeepsModelDeclItems) {
    const DefFile f = parseDefGood(
        "model monster_zombie {\n"                                                   // 1
        "\tinherit zombie_base\n"                                                    // 2
        "\tmesh models/md5/zombie.md5mesh\n"                                         // 3
        "\tskin skins/zombie/bloody\n"                                               // 4
        "\toffset ( 0 0 -2.5 )\n"                                                    // 5
        "\tchannel torso ( *Waist )\n"                                               // 6
        "\tchannel legs ( origin Body *Hips -*Waist SPINNER )\n"                     // 7
        "\tanim af_pose models/md5/af_pose.md5anim\n"                                // 8
        "\tanim idle2 models/md5/idle.md5anim, \"models/md5/idle-b.md5anim\" {\n"   // 9
        "\t\tframe 16.5 sound_voice snd_sight\n"                                     // 10
        "\t\tframe 20 { nested }\n"                                                  // 11
        "\t}\n"                                                                      // 12
        "\tremove walk\n"                                                            // 13
        "}\n");
    ASSERT_EQ(f.models.size(), 1u);
    const ModelDecl& m = f.models[0];
    EXPECT_EQ(m.name, "monster_zombie");
    EXPECT_EQ(m.inherit, "zombie_base");
    EXPECT_EQ(m.inheritWhere, (SourceLocation{2, 10}));
    EXPECT_EQ(m.mesh, "models/md5/zombie.md5mesh");
    EXPECT_EQ(m.meshWhere, (SourceLocation{3, 7}));
    EXPECT_EQ(m.skin, "skins/zombie/bloody");
    ASSERT_TRUE(m.offset.has_value());
    EXPECT_EQ(*m.offset, (Real3{0, 0, -2.5}));
    ASSERT_EQ(m.channels.size(), 2u);
    EXPECT_EQ(m.channels[0].name, "torso");
    EXPECT_EQ(m.channels[0].joints, "*Waist");
    EXPECT_EQ(m.channels[1].joints, "origin Body *Hips -*Waist SPINNER");
    ASSERT_EQ(m.anims.size(), 2u);
    EXPECT_EQ(m.anims[0].alias, "af_pose");
    EXPECT_EQ(m.anims[0].files, (std::vector<std::string>{"models/md5/af_pose.md5anim"}));
    EXPECT_FALSE(m.anims[0].hasFrameCommands);
    EXPECT_EQ(m.anims[1].alias, "idle2");
    EXPECT_EQ(m.anims[1].files, (std::vector<std::string>{"models/md5/idle.md5anim", "models/md5/idle-b.md5anim"}));
    EXPECT_TRUE(m.anims[1].hasFrameCommands);
    ASSERT_EQ(m.removes.size(), 1u);
    EXPECT_EQ(m.removes[0].alias, "walk");
    EXPECT_NE(m.findAnim("af_pose"), nullptr);
    EXPECT_EQ(m.findAnim("AF_POSE"), nullptr);  // aliases are case-sensitive, as in Doom
}

TEST(DefParser, SkipsOtherDeclKindsWithoutErrors) {
    const DefFile f = parseDefGood(
        "export fred {\n"
        "\toptions -prefix FRED_ -keep Body -parent Body2 Body\n"
        "\tmesh models/fred.mb -dest models/md5/fred.md5mesh\n"
        "}\n"
        "material textures/base/floor {\n"
        "\tqer_editorimage textures/floor.tga\n"
        "\t{ blend diffusemap map textures/floor_d.tga rgb 0.5 * parm0 }\n"
        "\t{ if ( time > 2 ) { nested } }\n"
        "}\n"
        "table sinTable { { 0, 1, 0, -1 } }\n"
        "skin skins/zombie/bloody { \"models/skin\" \"models/skin_bloody\" }\n"
        "sound zombie_sight { minDistance 10 \"sound/zombie.wav\" }\n"
        "particle blood { { count 10 material \"textures/blood\" } }\n"
        "guiTemplate somethingNew { \"{ in a string }\" { } }\n"
        "entityDef kept { \"a\" \"b\" }\n");
    EXPECT_EQ(f.entityDefs.size(), 1u);
    ASSERT_EQ(f.skipped.size(), 7u);
    EXPECT_EQ(f.skipped[0].type, "export");
    EXPECT_EQ(f.skipped[0].name, "fred");
    EXPECT_EQ(f.skipped[1].type, "material");
    EXPECT_EQ(f.skipped[1].name, "textures/base/floor");
    EXPECT_EQ(f.skipped[6].type, "guiTemplate");
    EXPECT_EQ(f.skipped[6].where, (SourceLocation{14, 1}));
}

TEST(DefParser, UnquotedKeyIsAnErrorAndTheNextDeclStillLoads) {
    const DefParseResult r = parseDef(
        "entityDef broken {\n"
        "\tspawnclass \"idAFEntity_Generic\"\n"
        "}\n"
        "entityDef fine { \"a\" \"b\" }\n",
        "bad.def");
    EXPECT_EQ(r.diagnostics.formatAll(),
              "bad.def:2:2: error: expected a key in double quotes or '}', found 'spawnclass'\n");
    ASSERT_EQ(r.file.entityDefs.size(), 1u);
    EXPECT_EQ(r.file.entityDefs[0].name, "fine");
}

TEST(DefParser, KeyWithoutValueIsAnError) {
    EXPECT_EQ(diagnosticsOf("entityDef a {\n\t\"model\"\n}\n"),
              "bad.def:3:1: error: expected a value for \"model\", found '}'\n");
}

TEST(DefParser, EndOfFileInsideABlockIsAnError) {
    EXPECT_EQ(diagnosticsOf("entityDef a {\n\t\"model\" \"x\"\n"),
              "bad.def:3:1: error: expected a key in double quotes or '}', found end of file\n");
    EXPECT_EQ(diagnosticsOf("material m {\n\t{ map x\n}\n"),
              "bad.def:4:1: error: expected '}' to close material 'm' opened at line 1, found end of file\n");
    EXPECT_EQ(diagnosticsOf("model m {\n\tanim idle idle.md5anim {\n\t\tframe 1 sound x\n"),
              "bad.def:4:1: error: expected '}' to close the frame commands of anim 'idle' opened at line 2, "
              "found end of file\n");
    EXPECT_EQ(diagnosticsOf("model m {\n\tchannel torso ( *Waist\n"),
              "bad.def:3:1: error: expected a joint name, '*', '-' or ')' in the channel's joint list, found end of "
              "file\n");
}

TEST(DefParser, StrayClosingBraceIsAnError) {
    EXPECT_EQ(diagnosticsOf("entityDef a { \"k\" \"v\" }\n}\nentityDef b { }\n"),
              "bad.def:2:1: error: expected a decl (TYPE NAME { ... }) or a decl name, found '}'\n");
}

TEST(DefParser, MissingBraceAfterNameIsAnError) {
    EXPECT_EQ(diagnosticsOf("entityDef a \"k\" \"v\" }\n"),
              "bad.def:1:13: error: expected '{' after the decl name, found \"k\"\n");
}

TEST(DefParser, UnknownModelKeyIsAnErrorBecauseModelKeysAreCaseSensitive) {
    EXPECT_EQ(diagnosticsOf("model m {\n\tMesh m.md5mesh\n}\n"),
              "bad.def:2:2: error: expected a model key (inherit, mesh, skin, offset, channel, anim, remove) or '}', "
              "found 'Mesh'\n");
}

TEST(DefParser, OffsetTakesNoCommas) {
    EXPECT_EQ(diagnosticsOf("model m {\n\toffset ( 0, 0, 1 )\n}\n"),
              "bad.def:2:12: error: expected a number for the offset, found ','\n");
}

TEST(DefParser, BraceWithoutNameWarnsAndIsSkipped) {
    const DefParseResult r = parseDef("{ \"a\" \"b\" }\nmodel { mesh x.md5mesh }\nentityDef e { }\n", "w.def");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(),
              "w.def:1:1: warning: a braced section without a decl type and name is skipped\n"
              "w.def:2:7: warning: 'model' without a decl name; the braced section is skipped\n");
    EXPECT_EQ(r.file.entityDefs.size(), 1u);
    EXPECT_TRUE(r.file.models.empty());
}

TEST(DefParser, DeclDefinedTwiceInAFileKeepsTheFirst) {
    const DefParseResult r = parseDef("entityDef a { \"v\" \"1\" }\nentityDef A.old { \"v\" \"2\" }\n", "w.def");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(),
              "w.def:2:11: warning: entityDef 'a' is defined again; the definition at line 1 is used\n");
    ASSERT_EQ(r.file.entityDefs.size(), 1u);
    EXPECT_EQ(r.file.entityDefs[0].valueOr("v"), "1");
}

TEST(DefParser, MeshThatIsNotMd5meshWarns) {
    const DefParseResult r = parseDef("model m { mesh models/m.lwo }\n", "w.def");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(),
              "w.def:1:16: warning: mesh 'models/m.lwo' is not an .md5mesh; Doom 3 rejects this model decl\n");
}

TEST(DefParser, RepeatedAnimAliasWarnsAndTheLaterOneIsUsed) {
    const DefParseResult r = parseDef("model m {\n\tmesh m.md5mesh\n\tanim idle a.md5anim\n\tanim idle b.md5anim\n}\n",
                                      "w.def");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(),
              "w.def:4:7: warning: anim 'idle' is defined again (first at line 3); the later one is used (Doom 3 "
              "rejects the model decl)\n");
    ASSERT_EQ(r.file.models[0].anims.size(), 1u);
    EXPECT_EQ(r.file.models[0].anims[0].files[0], "b.md5anim");
}

TEST(DefParser, EveryTruncationIsHandledWithoutACrash) {
    const std::string text =
        "model m { mesh m.md5mesh channel torso ( *Waist ) anim af_pose a.md5anim { frame 1 x } offset ( 0 0 1 ) }\n"
        "export e { options -keep \"x\" }\n"
        "entityDef d { \"model\" \"m\" \"inherit\" \"base\" }\n";
    for (std::size_t n = 0; n < text.size(); ++n) {
        const DefParseResult r = parseDef(text.substr(0, n), "cut.def");
        // A cut between decls leaves complete decls; any other cut is exactly one error.
        const bool betweenDecls = n == 0 || text[n - 1] == '\n' || text.compare(n - 1, 2, "}\n") == 0;
        EXPECT_EQ(r.diagnostics.errorCount(), betweenDecls ? 0u : 1u) << "cut at " << n << "\n"
                                                                      << r.diagnostics.formatAll();
    }
}

TEST(DefParser, MissingFileIsAnError) {
    const DefParseResult r = loadDefFile("/nonexistent/x.def");
    EXPECT_EQ(r.diagnostics.formatAll(), "/nonexistent/x.def: error: cannot open the file for reading\n");
}

}  // namespace
}  // namespace af
