// Inheritance of entityDefs and model decls over a collection of parsed .def files, with
// errors for unknown parents and cycles.

#include "af/text/decl_def.h"

#include <gtest/gtest.h>

#include <string>

namespace af {
namespace {

DefCollection collect(const std::string& text, const std::string& file = "test.def") {
    const DefParseResult r = parseDef(text, file);
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    DefCollection decls;
    std::vector<Diagnostic> diagnostics;
    decls.add(r.file, diagnostics);
    EXPECT_TRUE(diagnostics.empty());
    return decls;
}

std::vector<std::string> keysOf(const EntityDef& def) {
    std::vector<std::string> keys;
    for (const DefKeyValue& kv : def.keyValues) keys.push_back(kv.key + "=" + kv.value);
    return keys;
}

TEST(DefResolve, InheritCopiesOnlyMissingKeysThroughSeveralLevels) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "entityDef child {\n"
        "\t\"inherit\" \"parent\"\n"
        "\t\"model\" \"child_model\"\n"
        "}\n"
        "entityDef parent {\n"
        "\t\"inherit\" \"grandparent\"\n"
        "\t\"model\" \"parent_model\"\n"
        "\t\"nodrop\" \"1\"\n"
        "}\n"
        "entityDef grandparent {\n"
        "\t\"spawnclass\" \"idAFEntity_Generic\"\n"
        "\t\"NODROP\" \"0\"\n"
        "}\n"));
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    const EntityDef* child = r.decls.findEntityDef("child");
    ASSERT_NE(child, nullptr);
    // The inherit key is gone, classname is added, then the parent's keys the child lacks, in the
    // parent's order (the parent already holds what it got from the grandparent).
    EXPECT_EQ(keysOf(*child), (std::vector<std::string>{"model=child_model", "classname=child", "nodrop=1",
                                                        "spawnclass=idAFEntity_Generic"}));
    EXPECT_EQ(child->find("nodrop")->inheritedFrom, "parent");
    EXPECT_EQ(child->find("spawnclass")->inheritedFrom, "grandparent");
    EXPECT_EQ(child->find("model")->inheritedFrom, "");
}

TEST(DefResolve, SeveralInheritKeysApplyInKeyOrder) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "entityDef a { \"inherit\" \"first\" \"inherit2\" \"second\" }\n"
        "entityDef first { \"x\" \"from_first\" }\n"
        "entityDef second { \"x\" \"from_second\" \"y\" \"from_second\" }\n"));
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    const EntityDef* a = r.decls.findEntityDef("a");
    EXPECT_EQ(a->valueOr("x"), "from_first");
    EXPECT_EQ(a->valueOr("y"), "from_second");
    EXPECT_EQ(a->find("inherit2"), nullptr);
}

TEST(DefResolve, ClassnameIsTheCanonicalDeclName) {
    const ResolvedDefs r = resolveDefInheritance(collect("entityDef Prop_Barrel.old { \"classname\" \"other\" }\n"));
    EXPECT_EQ(r.decls.findEntityDef("PROP_BARREL")->valueOr("classname"), "prop_barrel");
}

TEST(DefResolve, UnknownParentIsAnErrorAtTheInheritKey) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "entityDef a {\n"
        "\t\"model\" \"m\"\n"
        "\t\"inherit\" \"missing\"\n"
        "}\n",
        "defs/a.def"));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.formatDiagnostics(), "defs/a.def:3:2: error: entityDef 'a' inherits 'missing', which is not defined\n");
    // The decl keeps what it has.
    EXPECT_EQ(r.decls.findEntityDef("a")->valueOr("model"), "m");
}

TEST(DefResolve, InheritanceCycleIsAnError) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "entityDef a {\n"
        "\t\"inherit\" \"b\"\n"
        "}\n"
        "entityDef b {\n"
        "\t\"inherit\" \"c\"\n"
        "}\n"
        "entityDef c {\n"
        "\t\"inherit\" \"a\"\n"
        "\t\"k\" \"v\"\n"
        "}\n"
        "entityDef self { \"inherit\" \"self\" }\n"));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.formatDiagnostics(),
              "test.def:8:2: error: entityDef 'c' inherits 'a', which is an inheritance cycle (a -> b -> c -> a); "
              "that inherit is ignored\n"
              "test.def:11:18: error: entityDef 'self' inherits 'self', which is an inheritance cycle (self -> self); "
              "that inherit is ignored\n");
    EXPECT_EQ(r.decls.findEntityDef("a")->valueOr("k"), "v");
}

TEST(DefResolve, ModelInheritReplacesMergesAndRemoves) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "model base {\n"
        "\tmesh models/base.md5mesh\n"
        "\tskin skins/base\n"
        "\toffset ( 0 0 1 )\n"
        "\tchannel torso ( *Waist )\n"
        "\tchannel legs ( *Hips )\n"
        "\tanim af_pose base_pose.md5anim\n"
        "\tanim walk1 walk1.md5anim\n"
        "\tanim walk2 walk2.md5anim\n"
        "\tanim idle idle.md5anim\n"
        "}\n"
        "model derived {\n"
        "\tinherit base\n"
        "\tskin skins/derived\n"
        "\tchannel TORSO ( *Chest )\n"
        "\tremove walk\n"
        "\tanim af_pose derived_pose.md5anim\n"
        "\tanim run run.md5anim\n"
        "}\n"));
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    const ModelDecl* m = r.decls.findModel("derived");
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->mesh, "models/base.md5mesh");
    EXPECT_EQ(m->skin, "skins/derived");
    ASSERT_TRUE(m->offset.has_value());
    EXPECT_EQ(*m->offset, (Real3{0, 0, 1}));
    ASSERT_EQ(m->channels.size(), 2u);
    EXPECT_EQ(m->channels[0].joints, "*Chest");
    EXPECT_EQ(m->channels[1].joints, "*Hips");
    ASSERT_EQ(m->anims.size(), 3u);  // walk1 and walk2 removed by "walk"
    EXPECT_EQ(m->anims[0].alias, "af_pose");
    EXPECT_EQ(m->anims[0].files[0], "derived_pose.md5anim");
    EXPECT_EQ(m->anims[1].alias, "idle");
    EXPECT_EQ(m->anims[2].alias, "run");
    EXPECT_TRUE(m->inherit.empty());
    EXPECT_TRUE(m->removes.empty());
}

TEST(DefResolve, ModelRemoveOfAnAnimThatWasNotInheritedWarns) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "model base { mesh b.md5mesh anim idle idle.md5anim }\n"
        "model derived {\n"
        "\tinherit base\n"
        "\tremove jump\n"
        "}\n"));
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.formatDiagnostics(),
              "test.def:4:9: warning: remove 'jump' matches no anim inherited from 'base' (Doom 3 rejects the model "
              "decl)\n");
}

TEST(DefResolve, ModelWithUnknownParentSaysWhenAnEntityDefHasThatName) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "entityDef zombie { }\n"
        "model m {\n"
        "\tinherit zombie\n"
        "}\n"));
    EXPECT_EQ(r.formatDiagnostics(),
              "test.def:3:10: error: model 'm' inherits 'zombie', which is not defined as a model decl (there is an "
              "entityDef of that name)\n");
}

TEST(DefResolve, ModelInheritanceCycleIsAnError) {
    const ResolvedDefs r = resolveDefInheritance(collect(
        "model a {\n\tinherit b\n}\n"
        "model b {\n\tinherit a\n\tmesh b.md5mesh\n}\n"));
    EXPECT_EQ(r.formatDiagnostics(),
              "test.def:5:10: error: model 'b' inherits 'a', which is an inheritance cycle (a -> b -> a); that "
              "inherit is ignored\n");
    EXPECT_EQ(r.decls.findModel("a")->mesh, "b.md5mesh");
}

TEST(DefResolve, CollectionKeepsTheFirstOfARepeatedNameAcrossFiles) {
    DefCollection decls;
    std::vector<Diagnostic> diagnostics;
    decls.add(parseDef("entityDef a { \"v\" \"1\" }\nmodel a { mesh a.md5mesh }\n", "one.def").file, diagnostics);
    decls.add(parseDef("\n\nentityDef A { \"v\" \"2\" }\n", "two.def").file, diagnostics);
    ASSERT_EQ(diagnostics.size(), 1u);
    EXPECT_EQ(diagnostics[0].format(),
              "two.def:3:11: warning: entityDef 'a' is defined again; the definition in one.def at line 1 is used");
    EXPECT_EQ(decls.findEntityDef("a")->valueOr("v"), "1");
    // Models and entityDefs are separate namespaces.
    EXPECT_NE(decls.findModel("A.def"), nullptr);
    EXPECT_EQ(decls.findEntityDef("b"), nullptr);
}

}  // namespace
}  // namespace af
