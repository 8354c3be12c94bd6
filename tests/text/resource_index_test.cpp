// The resource index: decl files of several root folders found and parsed, names looked up as
// Doom does, and an AF entity or a figure resolved to its decls, mesh and af_pose anim, with
// errors that say what was looked for and where.

#include "af/text/lexer.h"
#include "af/text/resource_index.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace af {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = AF_SOURCE_DIR;

// A folder laid out like Doom's base/, removed at the end of the test. The name holds the test's
// name and the process id, since test processes run in parallel.
class TempRoot {
public:
    explicit TempRoot(std::string_view tag) {
        const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::path(testing::TempDir()) / ("af_resource_index_" + std::string(test->name()) + "_" +
                                                std::string(tag) + "_" + std::to_string(::getpid()));
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempRoot() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempRoot(const TempRoot&) = delete;
    TempRoot& operator=(const TempRoot&) = delete;

    const fs::path& path() const { return path_; }
    std::string str(std::string_view relative = {}) const {
        return relative.empty() ? path_.string() : (path_ / relative).string();
    }

    void write(std::string_view relative, std::string_view text) const {
        const fs::path file = path_ / relative;
        fs::create_directories(file.parent_path());
        std::ofstream out(file, std::ios::binary);
        out << text;
    }

private:
    fs::path path_;
};

// A two-joint skeleton and its af_pose, small enough to write inline.
constexpr std::string_view kStickMesh =
    "MD5Version 10\ncommandline \"\"\nnumJoints 2\nnumMeshes 0\n"
    "joints {\n\t\"origin\" -1 ( 0 0 0 ) ( 0 0 0 )\n\t\"tip\" 0 ( 0 0 10 ) ( 0 0 0 )\n}\n";
constexpr std::string_view kStickAnim =
    "MD5Version 10\ncommandline \"\"\nnumFrames 1\nnumJoints 2\nframeRate 24\nnumAnimatedComponents 0\n"
    "hierarchy {\n\t\"origin\" -1 0 0\n\t\"tip\" 0 0 0\n}\n"
    "bounds {\n\t( -1 -1 -1 ) ( 1 1 11 )\n}\n"
    "baseframe {\n\t( 0 0 0 ) ( 0 0 0 )\n\t( 0 0 10 ) ( 0 0 0 )\n}\n"
    "frame 0 {\n}\n";

std::string stickFigure(std::string_view name, std::string_view model = "stick") {
    return "articulatedFigure " + std::string(name) + " {\nsettings {\n\tmodel \"" + std::string(model) +
           "\"\n}\nbody \"root\" {\n\tjoint \"origin\"\n}\n}\n";
}

std::string stickModel(std::string_view name, std::string_view mesh = "models/stick/stick.md5mesh",
                       std::string_view anim = "models/stick/af_pose.md5anim") {
    return "model " + std::string(name) + " {\n\tmesh " + std::string(mesh) + "\n\tanim af_pose " +
           std::string(anim) + "\n}\n";
}

std::string afEntity(std::string_view name, std::string_view model, std::string_view figure) {
    return "entityDef " + std::string(name) + " {\n\t\"model\" \"" + std::string(model) +
           "\"\n\t\"articulatedFigure\" \"" + std::string(figure) + "\"\n}\n";
}

// The stick's md5 files, figure, model decl and entityDef `af_stick`.
void writeStick(const TempRoot& root) {
    root.write("models/stick/stick.md5mesh", kStickMesh);
    root.write("models/stick/af_pose.md5anim", kStickAnim);
    root.write("af/stick.af", stickFigure("stick"));
    root.write("def/stick.def", stickModel("stick") + afEntity("af_stick", "stick", "stick"));
}

std::vector<std::string> errorsOf(const std::vector<Diagnostic>& diagnostics) {
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::Error) out.push_back(d.format());
    return out;
}

// ---- the shipped samples ------------------------------------------------------------------

TEST(ResourceIndexSamples, RepositoryRootIndexesTheSampleFiguresAndDefsWithoutErrors) {
    const ResourceIndex index({kSourceDir});
    EXPECT_FALSE(index.hasErrors()) << index.formatDiagnostics();
    for (const char* figure : {"humanoid", "chain", "lamp"}) EXPECT_NE(index.findFigure(figure), nullptr) << figure;
    for (const char* entity : {"ragdoll_humanoid", "af_chain", "af_lamp"})
        EXPECT_NE(index.findEntityDef(entity), nullptr) << entity;
    const FigureEntry* humanoid = index.findFigure("humanoid");
    ASSERT_NE(humanoid, nullptr);
    EXPECT_EQ(fs::path(humanoid->file), kSourceDir / "af" / "humanoid.af");
    EXPECT_EQ(humanoid->decl.bodies.size(), 16u);
}

TEST(ResourceIndexSamples, RagdollHumanoidResolvesToTheHumanoidDeclMeshAndOneFramePose) {
    const ResourceIndex index({kSourceDir});
    const AFResources r = index.resolveAFEntity("ragdoll_humanoid");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    ASSERT_TRUE(r.entity.has_value());
    EXPECT_EQ(r.entity->name, "ragdoll_humanoid");
    EXPECT_EQ(r.entity->valueOr("spawnclass"), "idAFEntity_Generic");
    EXPECT_EQ(r.figure->decl.name, "humanoid");
    EXPECT_EQ(r.model->name, "humanoid");
    EXPECT_FALSE(r.implicitModel);
    EXPECT_EQ(fs::path(r.mesh.path), kSourceDir / "models" / "humanoid" / "humanoid.md5mesh");
    EXPECT_EQ(fs::path(r.afPose.path), kSourceDir / "models" / "humanoid" / "af_pose.md5anim");
    EXPECT_EQ(r.mesh.mesh->joints.size(), 25u);
    EXPECT_EQ(r.afPose.anim->joints.size(), 25u);
    EXPECT_EQ(r.afPose.anim->frameCount, 1);
    EXPECT_TRUE(r.diagnostics.empty()) << r.formatDiagnostics();
}

TEST(ResourceIndexSamples, ChainAndLampEntitiesResolve) {
    const ResourceIndex index({kSourceDir});
    for (const char* entity : {"af_chain", "af_lamp"}) {
        const AFResources r = index.resolveAFEntity(entity);
        EXPECT_TRUE(r.ok()) << entity << "\n" << r.formatDiagnostics();
    }
}

TEST(ResourceIndexSamples, FigureAloneFindsItsModelThroughItsSettings) {
    const ResourceIndex index({kSourceDir});
    const AFResources r = index.resolveFigure("Humanoid.af");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_FALSE(r.entity.has_value());
    EXPECT_EQ(r.model->name, "humanoid");
    EXPECT_EQ(r.mesh.mesh->joints.size(), 25u);
}

TEST(ResourceIndexSamples, NamesIgnoreCaseExtensionAndBackslashes) {
    const ResourceIndex index({kSourceDir});
    EXPECT_EQ(index.findFigure("HUMANOID.af"), index.findFigure("humanoid"));
    EXPECT_NE(index.findEntityDef("Ragdoll_Humanoid"), nullptr);
    EXPECT_NE(index.findModel("HUMANOID"), nullptr);
    const std::optional<fs::path> mesh = index.resolvePath("models\\humanoid\\humanoid.md5mesh");
    ASSERT_TRUE(mesh.has_value());
    EXPECT_EQ(*mesh, kSourceDir / "models" / "humanoid" / "humanoid.md5mesh");
}

TEST(ResourceIndexSamples, Md5FilesAreParsedOnceAndShared) {
    const ResourceIndex index({kSourceDir});
    const MeshLoad first = index.loadMesh("models/humanoid/humanoid.md5mesh");
    const MeshLoad second = index.loadMesh("models/Humanoid/humanoid.md5mesh");
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(first.mesh, second.mesh);
    const AFResources r = index.resolveAFEntity("ragdoll_humanoid");
    EXPECT_EQ(r.mesh.mesh, first.mesh);
}

// ---- search order ---------------------------------------------------------------------------

TEST(ResourceIndexRoots, LaterRootReplacesFilesOfTheSamePath) {
    const TempRoot base("base"), mod("mod");
    writeStick(base);
    // The mod replaces the def file (the entity now names figure "long") and the mesh.
    mod.write("def/STICK.def", stickModel("stick") + afEntity("af_stick", "stick", "long"));
    mod.write("af/long.af", stickFigure("long"));
    mod.write("models/stick/stick.md5mesh", kStickMesh);

    const ResourceIndex index({base.path(), mod.path()});
    EXPECT_FALSE(index.hasErrors()) << index.formatDiagnostics();
    ASSERT_EQ(index.defFiles().size(), 1u);
    EXPECT_EQ(fs::path(index.defFiles()[0]), mod.path() / "def" / "STICK.def");

    const AFResources r = index.resolveAFEntity("af_stick");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_EQ(r.figure->decl.name, "long");
    EXPECT_EQ(fs::path(r.mesh.path), mod.path() / "models" / "stick" / "stick.md5mesh");
    EXPECT_EQ(fs::path(r.afPose.path), base.path() / "models" / "stick" / "af_pose.md5anim");

    // The other order: the base is searched last, so its files win.
    const ResourceIndex reversed({mod.path(), base.path()});
    EXPECT_EQ(reversed.resolveAFEntity("af_stick").figure->decl.name, "stick");
}

TEST(ResourceIndexRoots, DeclDefinedInTwoFilesKeepsTheFirstReadAndWarns) {
    const TempRoot base("base"), mod("mod");
    writeStick(base);
    mod.write("af/z_other.af", stickFigure("stick", "other_model"));

    const ResourceIndex index({base.path(), mod.path()});
    EXPECT_FALSE(index.hasErrors()) << index.formatDiagnostics();
    ASSERT_NE(index.findFigure("stick"), nullptr);
    EXPECT_EQ(index.findFigure("stick")->decl.settings.model, "stick");
    ASSERT_EQ(index.diagnostics().size(), 1u);
    const Diagnostic& warning = index.diagnostics()[0];
    EXPECT_EQ(warning.severity, Severity::Warning);
    EXPECT_EQ(warning.file, mod.str("af/z_other.af"));
    EXPECT_NE(warning.message.find("already defined at " + base.str("af/stick.af") + ":1:19"), std::string::npos)
        << warning.format();
}

TEST(ResourceIndexRoots, FilePathsFallBackToASpellingThatDiffersInCase) {
    const TempRoot mod("mod");
    mod.write("Models/Stick/Stick.MD5MESH", kStickMesh);
    mod.write("Models/Stick/af_pose.md5anim", kStickAnim);
    mod.write("AF/Stick.AF", stickFigure("Stick"));
    mod.write("Def/stick.def", stickModel("stick"));

    const ResourceIndex index({mod.path()});
    EXPECT_FALSE(index.hasErrors()) << index.formatDiagnostics();
    const std::optional<fs::path> mesh = index.resolvePath("models/stick/stick.md5mesh");
    ASSERT_TRUE(mesh.has_value());
    EXPECT_EQ(*mesh, mod.path() / "Models" / "Stick" / "Stick.MD5MESH");
    const AFResources r = index.resolveFigure("stick");
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
}

TEST(ResourceIndexRoots, ExactSpellingWinsOverOneThatDiffersInCase) {
    const TempRoot mod("mod");
    mod.write("models/a.md5mesh", kStickMesh);
    mod.write("Models/a.md5mesh", kStickMesh);
    const ResourceIndex index({mod.path()});
    EXPECT_EQ(index.resolvePath("Models/a.md5mesh"), mod.path() / "Models" / "a.md5mesh");
    EXPECT_EQ(index.resolvePath("models/a.md5mesh"), mod.path() / "models" / "a.md5mesh");
    EXPECT_EQ(index.resolvePath("MODELS/A.md5mesh"), mod.path() / "Models" / "a.md5mesh");  // sorted first
}

TEST(ResourceIndexRoots, PathsThatLeaveTheRootAreNotSearched) {
    const TempRoot mod("mod");
    writeStick(mod);
    const ResourceIndex index({mod.path() / "models"});
    EXPECT_FALSE(index.resolvePath("../def/stick.def").has_value());
    const MeshLoad load = index.loadMesh("../models/stick/stick.md5mesh");
    ASSERT_EQ(errorsOf(load.diagnostics).size(), 1u);
    EXPECT_NE(load.diagnostics[0].message.find("leaves the root folder"), std::string::npos);
}

// Mod folders are untrusted: a decl that names a file outside the roots must not get it opened,
// however the path is spelled, and the message says where it was written and which rule refused it.
TEST(ResourceIndexRoots, AbsoluteMeshPathIsRefusedAtItsPlaceInTheDecl) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("def/stick.def", stickModel("stick", "/etc/passwd") + afEntity("af_stick", "stick", "stick"));
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("af_stick");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def/stick.def") +
                                       ":2:7: error: mesh \"/etc/passwd\" cannot be searched: the path is absolute, and "
                                       "files are only opened inside the root folders (as Doom's file system opens "
                                       "them only inside its search paths)"});
    EXPECT_FALSE(r.mesh.mesh);
}

TEST(ResourceIndexRoots, NoSpellingOfAnAbsolutePathIsSearched) {
    const TempRoot mod("mod");
    writeStick(mod);
    const ResourceIndex index({mod.path()});
    // Each names the stick's mesh itself, which exists: only the spelling is refused.
    const std::string inside = mod.str("models/stick/stick.md5mesh");
    for (const std::string& path : {inside, "\\" + inside.substr(1), std::string("C:/models/stick/stick.md5mesh"),
                                    std::string("c:models\\stick\\stick.md5mesh")}) {
        EXPECT_FALSE(index.resolvePath(path).has_value()) << path;
        const MeshLoad load = index.loadMesh(path);
        ASSERT_EQ(errorsOf(load.diagnostics).size(), 1u) << path;
        EXPECT_NE(load.diagnostics[0].message.find("the path is absolute"), std::string::npos) << path;
    }
    EXPECT_TRUE(index.resolvePath("models/stick/stick.md5mesh").has_value());
}

// A file that is not of the expected format is quoted only as a short printable token: a decl
// may name any file in the mod folder, and its content must not end up in a log.
TEST(ResourceIndexRoots, FileOfAnotherFormatIsQuotedShortAndPrintable) {
    const TempRoot mod("mod");
    writeStick(mod);
    const std::string secret = "root:x:0:0:root:/root:/bin/bash:and_a_secret_that_must_not_show";
    mod.write("models/stick/stick.md5mesh", secret + "\ndaemon:x:1:1\n");
    const ResourceIndex index({mod.path()});
    const MeshLoad load = index.loadMesh("models/stick/stick.md5mesh");
    ASSERT_EQ(errorsOf(load.diagnostics).size(), 1u);
    EXPECT_EQ(load.diagnostics[0].format(), mod.str("models/stick/stick.md5mesh") +
                                                ":1:1: error: expected 'MD5Version' at the start of the file, found '" +
                                                secret.substr(0, kMaxQuotedChars) + "...'");
    EXPECT_EQ(kMaxQuotedChars, 32u);  // docs/formats.md §1.3 says so

    // Control and high bytes inside a token become '?'.
    mod.write("models/stick/stick.md5mesh", std::string("\"\x01\x1b[2J\xff\xfe\" rest"));
    const ResourceIndex again({mod.path()});
    const MeshLoad binary = again.loadMesh("models/stick/stick.md5mesh");
    ASSERT_EQ(errorsOf(binary.diagnostics).size(), 1u);
    EXPECT_EQ(binary.diagnostics[0].message, "expected 'MD5Version' at the start of the file, found \"??[2J??\"");
}

TEST(ResourceIndexRoots, MissingRootIsAnErrorAndTheOthersStillLoad) {
    const TempRoot mod("mod");
    writeStick(mod);
    const ResourceIndex index({mod.path() / "nowhere", mod.path()});
    EXPECT_EQ(errorsOf(index.diagnostics()),
              std::vector<std::string>{(mod.path() / "nowhere").string() +
                                       ": error: root folder does not exist or is not a folder"});
    EXPECT_TRUE(index.resolveAFEntity("af_stick").ok());
}

// ---- broken and missing things --------------------------------------------------------------

TEST(ResourceIndexErrors, BrokenAFFileIsReportedAndTheOthersLoad) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("af/a_broken.af", "articulatedFigure broken {\n\tbody \"root\" {\n\t\tjoint \"origin\"\n\t\tbogus 1\n}\n}\n");
    mod.write("af/more/z_good.af", stickFigure("good"));

    const ResourceIndex index({mod.path()});
    ASSERT_EQ(index.afFiles().size(), 3u);
    EXPECT_EQ(fs::path(index.afFiles()[0]), mod.path() / "af" / "a_broken.af");
    EXPECT_EQ(fs::path(index.afFiles()[1]), mod.path() / "af" / "more" / "z_good.af");  // sorted, recursive
    const std::vector<std::string> errors = errorsOf(index.diagnostics());
    ASSERT_EQ(errors.size(), 1u) << index.formatDiagnostics();
    EXPECT_EQ(errors[0].rfind(mod.str("af/a_broken.af") + ":4:3: error: ", 0), 0u) << errors[0];
    EXPECT_NE(index.findFigure("stick"), nullptr);
    EXPECT_NE(index.findFigure("good"), nullptr);
    EXPECT_EQ(index.findFigure("broken"), nullptr);

    const AFResources r = index.resolveFigure("a_broken");
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("af") + ": error: figure \"a_broken\" not found; looked in " +
                                       mod.str("af") + " (3 files, 2 figures); " + mod.str("af/a_broken.af") +
                                       " has errors and was not loaded"});
}

TEST(ResourceIndexErrors, MissingEntityDefListsTheFoldersAndWhatTheyHold) {
    const TempRoot base("base"), mod("mod");
    writeStick(base);
    mod.write("def/other.def", afEntity("af_other", "stick", "stick") + afEntity("af_third", "stick", "stick"));
    const ResourceIndex index({base.path(), mod.path()});
    const AFResources r = index.resolveAFEntity("ragdoll_x");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def") + ": error: entityDef \"ragdoll_x\" not found; looked in " +
                                       mod.str("def") + ", " + base.str("def") + " (2 files, 3 entityDefs)"});
}

TEST(ResourceIndexErrors, MissingModelAndFigurePointAtTheKeysThatNameThem) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("def/x.def", afEntity("ragdoll_x", "nosuch", "nofigure"));
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("ragdoll_x");
    EXPECT_FALSE(r.ok());
    const std::string file = mod.str("def/x.def");
    EXPECT_EQ(errorsOf(r.diagnostics),
              (std::vector<std::string>{
                  file + ":3:2: error: figure \"nofigure\" not found; looked in " + mod.str("af") +
                      " (1 file, 1 figure)",
                  file + ":2:2: error: model \"nosuch\" not found; looked in " + mod.str("def") +
                      " (2 files, 1 model decl)"}));
}

TEST(ResourceIndexErrors, ModelWithoutAfPoseAnimIsAnErrorAtTheModel) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("def/stick.def", "model stick {\n\tmesh models/stick/stick.md5mesh\n\tanim idle "
                               "models/stick/af_pose.md5anim\n}\n" +
                                   afEntity("af_stick", "stick", "stick"));
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("af_stick");
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(r.mesh.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def/stick.def") +
                                       ":1:7: error: model \"stick\" has no anim \"af_pose\", the pose the figure "
                                       "is defined in (its anims: idle)"});
}

TEST(ResourceIndexErrors, MissingMeshFileListsEveryPathTried) {
    const TempRoot base("base"), mod("mod");
    writeStick(base);
    mod.write("def/stick.def", stickModel("stick", "models/stick/gone.md5mesh") +
                                   afEntity("af_stick", "stick", "stick"));
    const ResourceIndex index({base.path(), mod.path()});
    const AFResources r = index.resolveAFEntity("af_stick");
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(r.afPose.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def/stick.def") + ":2:7: error: mesh \"models/stick/gone.md5mesh\" "
                                       "not found; looked in " + mod.str("models/stick/gone.md5mesh") + ", " +
                                       base.str("models/stick/gone.md5mesh") + " (each also ignoring case)"});
}

TEST(ResourceIndexErrors, AfPoseThatDoesNotFitTheMeshIsAnError) {
    const TempRoot mod("mod");
    writeStick(mod);
    std::string renamed(kStickAnim);
    renamed.replace(renamed.find("\"tip\""), 5, "\"top\"");
    mod.write("models/stick/af_pose.md5anim", renamed);
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("af_stick");
    EXPECT_FALSE(r.ok());
    EXPECT_FALSE(r.afPose.ok());
    const std::vector<std::string> errors = errorsOf(r.diagnostics);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].rfind(mod.str("models/stick/af_pose.md5anim") + ":9:2: error: ", 0), 0u) << errors[0];
    EXPECT_NE(errors[0].find("\"top\""), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("(mesh " + mod.str("models/stick/stick.md5mesh") + " of model \"stick\")"),
              std::string::npos)
        << errors[0];
}

TEST(ResourceIndexErrors, EntityWithoutFigureOrModelKeysSaysWhichKeysAreMissing) {
    const TempRoot mod("mod");
    mod.write("def/x.def", "entityDef bare {\n\t\"spawnclass\" \"idAFEntity_Generic\"\n}\n");
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("bare");
    const std::string at = mod.str("def/x.def") + ":1:11: error: ";
    EXPECT_EQ(errorsOf(r.diagnostics),
              (std::vector<std::string>{at + "entityDef \"bare\" names no figure: it has no \"articulatedFigure\" key "
                                             "(AF entities) and no \"ragdoll\" key (actors)",
                                        at + "entityDef \"bare\" has no \"model\" key, so the figure has no skeleton"}));
}

// ---- entity forms -----------------------------------------------------------------------------

TEST(ResourceIndexEntities, ActorRagdollKeyAndInheritedKeysResolve) {
    const TempRoot base("base"), mod("mod");
    writeStick(base);
    base.write("def/monster_base.def", "entityDef monster_base {\n\t\"model\" \"stick\"\n}\n");
    mod.write("def/monster.def", "entityDef monster_stick {\n\t\"inherit\" \"monster_base\"\n"
                                 "\t\"ragdoll\" \"nofigure\"\n}\n");
    const ResourceIndex index({base.path(), mod.path()});
    AFResources r = index.resolveAFEntity("monster_stick");
    EXPECT_TRUE(r.model.has_value());
    EXPECT_TRUE(r.mesh.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def/monster.def") + ":3:2: error: figure \"nofigure\" not found; "
                                       "looked in " + mod.str("af") + ", " + base.str("af") + " (1 file, 1 figure)"});

    // An inherited key that names something missing points into the parent's file.
    base.write("def/monster_base.def", "entityDef monster_base {\n\t\"model\" \"gone\"\n}\n");
    mod.write("def/monster.def", "entityDef monster_stick {\n\t\"inherit\" \"monster_base\"\n"
                                 "\t\"ragdoll\" \"stick\"\n}\n");
    const ResourceIndex again({base.path(), mod.path()});
    r = again.resolveAFEntity("monster_stick");
    ASSERT_NE(r.figure, nullptr);
    EXPECT_EQ(r.figure->decl.name, "stick");
    const std::vector<std::string> errors = errorsOf(r.diagnostics);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].rfind(base.str("def/monster_base.def") + ":2:2: error: model \"gone\" not found", 0), 0u)
        << errors[0];
}

TEST(ResourceIndexEntities, IddevnetEntityWithMeshPathAndAnimKeyMakesAnImplicitModel) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("def/iddevnet.def", "entityDef ragdoll_iddevnet {\n"
                                  "\t\"spawnclass\" \"idAFEntity\"\n"
                                  "\t\"model\" \"models\\\\stick\\\\stick.md5mesh\"\n"
                                  "\t\"anim af_pose\" \"models/stick/af_pose.md5anim\"\n"
                                  "\t\"articulatedFigure\" \"stick.af\"\n"
                                  "\t\"sleep\" \"1\"\n}\n");
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("ragdoll_iddevnet");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_TRUE(r.implicitModel);
    EXPECT_EQ(r.model->mesh, r.entity->valueOr("model"));
    ASSERT_NE(r.model->findAnim("af_pose"), nullptr);
    EXPECT_EQ(fs::path(r.mesh.path), mod.path() / "models" / "stick" / "stick.md5mesh");
    EXPECT_EQ(r.afPose.anim->frameCount, 1);
    EXPECT_EQ(r.figure->decl.name, "stick");
}

TEST(ResourceIndexEntities, IddevnetMeshPathWithoutAnimKeyIsAnErrorAtTheModelKey) {
    const TempRoot mod("mod");
    writeStick(mod);
    mod.write("def/x.def", afEntity("ragdoll_x", "models/stick/stick.md5mesh", "stick"));
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveAFEntity("ragdoll_x");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("def/x.def") + ":2:2: error: \"model\" names the mesh "
                                       "\"models/stick/stick.md5mesh\" directly; that needs an \"anim af_pose\" key "
                                       "next to it (the iddevnet form), or else a model decl with a mesh and an "
                                       "af_pose anim"});
}

TEST(ResourceIndexEntities, FigureWithoutSettingsModelCannotFindItsSkeleton) {
    const TempRoot mod("mod");
    mod.write("af/bare.af", "articulatedFigure bare {\nbody \"root\" {\n\tjoint \"origin\"\n}\n}\n");
    const ResourceIndex index({mod.path()});
    const AFResources r = index.resolveFigure("bare");
    ASSERT_NE(r.figure, nullptr);
    EXPECT_EQ(errorsOf(r.diagnostics),
              std::vector<std::string>{mod.str("af/bare.af") + ":1:19: error: figure \"bare\" names no model in its "
                                       "settings, so its skeleton is unknown"});
}

}  // namespace
}  // namespace af
