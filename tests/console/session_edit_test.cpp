// The figure editor's commands driven as a modder drives them (session_edit.cpp): an edit
// respawns every entity of the decl with the new figure, saveAF writes what was edited, bad
// edits print one error and change nothing, respawnRagdolls puts figures back where they spawned.

#include "console/session.h"
#include "session_console.h"

#include "af/text/af_parser.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace af::console {
namespace {

namespace fs = std::filesystem;

struct EditConsole : test::SessionConsole {
    using SessionConsole::SessionConsole;
    FigureId figure(std::size_t i = 0) const { return session.world().figureIds().at(i); }
    const FigureBody& body(const std::string& name, std::size_t figureIndex = 0) const {
        const Figure& f = session.world().definition(figure(figureIndex));
        return f.bodies.at(std::size_t(f.findBody(name)));
    }
};

fs::path editScratch(const std::string& name) { return test::scratchFile("af_session_edit_test", name); }

std::string readText(const fs::path& path) { return test::readText(path); }

// A copy of the repository's mod folder, for saves into the decl's own file.
fs::path editableMod(const std::string& name) {
    const fs::path root = editScratch(name);
    fs::remove_all(root);
    fs::create_directories(root);
    for (const char* dir : {"af", "def", "models"}) fs::copy(fs::path(AF_SOURCE_DIR) / dir, root / dir, fs::copy_options::recursive);
    return root;
}

DeclAF lampAsFileSays(const fs::path& file) {
    const AFParseResult read = loadAFFile(file.string());
    EXPECT_TRUE(read.ok()) << read.diagnostics.formatAll();
    const DeclAF* lamp = read.file.findDecl("lamp");
    return lamp ? *lamp : DeclAF{};
}

const AFConstraint& constraintOf(const DeclAF& d, const std::string& name) {
    const AFConstraint* c = d.findConstraint(name);
    if (!c) throw std::runtime_error("no constraint " + name);
    return *c;
}

TEST(SessionEdit, AnEditedLimitIsWhatTheSavedAfSaysAndTheRestIsAsItWas) {
    const fs::path root = editableMod("limit");
    const fs::path af = root / "af" / "lamp.af";
    const DeclAF before = lampAsFileSays(af);
    ASSERT_EQ(constraintOf(before, "shade").limitAngles, (Real3{0, 90, 0}));
    EditConsole c({root});
    ASSERT_TRUE(c.run("spawn af_lamp\neditConstraint af_lamp_1 shade limit 10, 45, 0\nsaveAF af_lamp_1").ok()) << c.errors;
    EXPECT_NE(c.info.find("saved articulatedFigure lamp to " + af.string()), std::string::npos) << c.info;

    DeclAF after = lampAsFileSays(af);
    EXPECT_EQ(constraintOf(after, "shade").limitAngles, (Real3{10, 45, 0}));
    after.constraints[std::size_t(&constraintOf(after, "shade") - after.constraints.data())].limitAngles = {0, 90, 0};
    EXPECT_EQ(after, before) << "only the limit changed";

    // A fresh console reads the saved file and builds the new limit.
    EditConsole fresh({root});
    ASSERT_TRUE(fresh.run("spawn af_lamp").ok()) << fresh.errors;
    const Figure& f = fresh.session.world().definition(fresh.figure());
    ASSERT_EQ(f.constraints.size(), 2u);
    bool found = false;
    for (const FigureConstraint& fc : f.constraints)
        if (fc.name == "shade") {
            found = true;
            EXPECT_EQ(fc.limitAngles[1], 45);
        }
    EXPECT_TRUE(found);
}

TEST(SessionEdit, SaveAFIntoAnotherFileAddsTheDeclAndLeavesTheSourceAlone) {
    const fs::path out = editScratch("other.af");
    fs::remove(out);
    const std::string source = readText(fs::path(AF_SOURCE_DIR) / "af" / "lamp.af");
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp\neditBody af_lamp_1 shade density 0.05\nsaveAF af_lamp_1 " + out.string()).ok()) << c.errors;
    EXPECT_EQ(readText(fs::path(AF_SOURCE_DIR) / "af" / "lamp.af"), source);
    EXPECT_FLOAT_EQ(float(lampAsFileSays(out).findBody("shade")->density), 0.05f);
}

// saveAF goes through the atomic writer: a save that dies part way leaves the .af as it was, and a
// file that does not parse is not overwritten.
TEST(SessionEdit, ASaveAFCutShortOrOntoABrokenFileLeavesTheFileAsItWas) {
    const fs::path root = editableMod("cut");
    const fs::path af = root / "af" / "lamp.af";
    const std::string before = readText(af);
    EditConsole c({root});
    ASSERT_TRUE(c.run("spawn af_lamp\neditBody af_lamp_1 shade density 0.05").ok()) << c.errors;
    for (const WriteStage stage : {WriteStage::Opened, WriteStage::Wrote, WriteStage::Synced, WriteStage::Renaming}) {
        c.session.setWriteFaultHook([stage](WriteStage at, std::size_t) { return at == stage ? WriteFault::Crash : WriteFault::None; });
        EXPECT_FALSE(c.run("saveAF af_lamp_1").ok());
        EXPECT_EQ(readText(af), before);
    }
    c.session.setWriteFaultHook({});
    const fs::path broken = editScratch("broken.af");
    std::ofstream(broken, std::ios::binary) << "articulatedFigure lamp {\n  settings {\n";
    c.errors.clear();
    EXPECT_FALSE(c.run("saveAF af_lamp_1 " + broken.string()).ok());
    EXPECT_NE(c.errors.find("does not read cleanly, so it is not overwritten"), std::string::npos) << c.errors;
    EXPECT_EQ(readText(broken), "articulatedFigure lamp {\n  settings {\n");
    ASSERT_TRUE(c.run("saveAF af_lamp_1").ok()) << c.errors;
    EXPECT_NE(readText(af), before);
}

TEST(SessionEdit, ADensityEditRespawnsEveryLampAtItsSpawnPlacementWithTheNewMass) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp origin \"0 0 0\"\nspawn af_lamp origin \"40 0 0\"").ok()) << c.errors;
    EditConsole still;  // the same spawns, never stepped: the spawn poses
    ASSERT_TRUE(still.run("spawn af_lamp origin \"0 0 0\"\nspawn af_lamp origin \"40 0 0\"").ok()) << still.errors;
    ASSERT_TRUE(c.run("drag af_lamp_1 shade 30 30 30\nrun 0.5\ndrag off").ok()) << c.errors;
    const Real mass = c.body("shade").mass;
    const FigureId old = c.figure();
    ASSERT_GT((c.session.world().bodyPoses(old)[1].position - still.session.world().bodyPoses(still.figure())[1].position).norm(), 1)
        << "the drag moved the shade";

    ASSERT_TRUE(c.run("editBody af_lamp_1 shade density 0.05").ok()) << c.errors;
    EXPECT_NE(c.info.find("edited af_lamp_1 shade: density 0.05 (2 ragdolls respawned)"), std::string::npos) << c.info;
    ASSERT_EQ(c.session.world().figureIds().size(), 2u);
    EXPECT_NE(c.figure(), old);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_NEAR(c.body("shade", i).mass, 2 * mass, 1e-6 * mass) << "density 0.025 doubled, the same shape";
        const std::vector<RigidPose> now = c.session.world().bodyPoses(c.figure(i)), spawned = still.session.world().bodyPoses(still.figure(i));
        ASSERT_EQ(now.size(), spawned.size());
        for (std::size_t b = 0; b < now.size(); ++b) EXPECT_LT((now[b].position - spawned[b].position).norm(), 1e-9) << i << " " << b;
    }
    EXPECT_FLOAT_EQ(float(c.session.decl("af_lamp_2")->findBody("shade")->density), 0.05f) << "one decl, shared";
}

TEST(SessionEdit, AShapeEditChangesTheBodysSizeAndQuotesGoBackAroundJointNames) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp").ok()) << c.errors;
    const Real volume = c.body("shade").volume;
    ASSERT_TRUE(c.run("editBody af_lamp_1 shade model \"cone( ( -16, -16, -5 ), ( 16, 16, 0 ), 12 )\"").ok()) << c.errors;
    EXPECT_NEAR(c.body("shade").volume, 4 * volume, 1e-6 * volume) << "twice as wide, as high";
    // The console strips double quotes; the file needs them around joint names.
    ASSERT_TRUE(c.run("editBody af_lamp_1 shade origin joint( shade )").ok()) << c.errors;
    const AFBody* shade = c.session.decl("af_lamp_1")->findBody("shade");
    ASSERT_NE(shade, nullptr);
    EXPECT_EQ(shade->origin.kind, AFVector::Kind::Joint);
    EXPECT_EQ(shade->origin.joint1, "shade");
}

// Every bad edit: one error line naming what is wrong, the decl, the figure and the world as they were.
TEST(SessionEdit, BadEditsPrintOneErrorAndChangeNothing) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp\nrun 0.2").ok()) << c.errors;
    const DeclAF decl = *c.session.decl("af_lamp_1");
    const FigureId figure = c.figure();
    const std::vector<RigidPose> poses = c.session.world().bodyPoses(figure);
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"editBody nobody shade density 1", "no entity named nobody"},
        {"editBody af_lamp_1 bulb density 1", "af_lamp_1 has no body bulb"},
        {"editConstraint af_lamp_1 wire friction 1", "af_lamp_1 has no constraint wire"},
        {"editBody af_lamp_1 shade density nan", "density nan"},
        {"editBody af_lamp_1 shade density 0", "density must be greater than 0"},
        {"editBody af_lamp_1 shade density -1", "density must be greater than 0"},
        {"editBody af_lamp_1 shade densty 1", "densty 1"},
        {"editBody af_lamp_1 shade model sphere( 3 )", "model sphere"},
        {"editBody af_lamp_1 shade density 1 } body \"x\" {", "shade: density 1 } body x {: "},
        {"editConstraint af_lamp_1 shade limit 0, wide, 0", "limit 0, wide, 0: "},
        {"editConstraint af_lamp_1 shade axis ( 0, 0, 0 )", "axis"},
        {"saveAF af_lamp_1 /nonexistent-dir/lamp.af", "saveAF"},
    };
    for (const auto& [command, says] : bad) {
        c.errors.clear();
        const ExecuteResult r = c.run(command);
        EXPECT_EQ(r.errors, 1u) << command;
        EXPECT_EQ(std::count(c.errors.begin(), c.errors.end(), '\n'), 1) << command << "\n" << c.errors;
        EXPECT_NE(c.errors.find(says), std::string::npos) << command << "\n" << c.errors;
        EXPECT_EQ(*c.session.decl("af_lamp_1"), decl) << command;
        ASSERT_EQ(c.session.world().figureIds().size(), 1u) << command;
        EXPECT_EQ(c.figure(), figure) << command << ": not respawned";
        const std::vector<RigidPose> now = c.session.world().bodyPoses(figure);
        for (std::size_t b = 0; b < now.size(); ++b) EXPECT_EQ(now[b].position, poses[b].position) << command;
    }
}

// The lamp's thin cable is lopsided already (a warning about the body); a heavy shade adds one
// about the hinge between them, printed by the edit, and going again when the shade is light.
TEST(SessionEdit, AnEditThatMakesAMassRatioTooLargeIsWarnedOfBesideTheJoint) {
    using Subject = FigureWarning::Subject;
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp").ok()) << c.errors;
    const auto subjects = [&c] {
        std::vector<std::pair<Subject, std::string>> out;
        const Figure& f = c.session.world().definition(c.figure());
        for (const FigureWarning& w : c.session.warnings("af_lamp_1"))
            out.emplace_back(w.subject, w.subject == Subject::Body ? f.bodies[std::size_t(w.index)].name : f.constraints[std::size_t(w.index)].name);
        return out;
    };
    using Expected = std::vector<std::pair<Subject, std::string>>;
    EXPECT_EQ(subjects(), (Expected{{Subject::Body, "cable"}}));
    ASSERT_TRUE(c.run("editBody af_lamp_1 shade density 20").ok()) << c.errors;
    EXPECT_NE(c.info.find("warning: hinge \"shade\" joins \"shade\" and \"cable\", whose masses differ by"), std::string::npos) << c.info;
    EXPECT_EQ(c.info.find("warning: body \"cable\""), std::string::npos) << "the edit prints the warnings it brings: " << c.info;
    EXPECT_EQ(subjects(), (Expected{{Subject::Body, "cable"}, {Subject::Constraint, "shade"}}));
    ASSERT_TRUE(c.run("checkFigure af_lamp_1").ok());
    EXPECT_NE(c.info.find("af_lamp_1: 2 warnings"), std::string::npos) << c.info;
    ASSERT_TRUE(c.run("editBody af_lamp_1 shade density 0.025").ok()) << c.errors;
    EXPECT_EQ(subjects(), (Expected{{Subject::Body, "cable"}})) << "updated after each edit";
}

TEST(SessionEdit, AJointTheSkeletonLacksIsWarnedOfByTheEdit) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp\neditBody af_lamp_1 shade joint shadow").ok()) << c.errors;
    EXPECT_NE(c.info.find("warning: body \"shade\": joint \"shadow\" is not in the skeleton"), std::string::npos) << c.info;
    EXPECT_EQ(c.session.decl("af_lamp_1")->findBody("shade")->joint, "shadow") << "quoted again for the file";
}

TEST(SessionEdit, RespawnRagdollsPutsEveryFigureBackAtItsSpawnPose) {
    EditConsole c, still;
    const std::string spawn = "spawn ragdoll_humanoid origin \"0 0 0\"\n";
    ASSERT_TRUE(c.run(spawn + "drag ragdoll_humanoid_1 head 0 40 90\nrun 1").ok()) << c.errors;
    ASSERT_TRUE(still.run(spawn).ok()) << still.errors;
    ASSERT_TRUE(c.run("respawnRagdolls").ok()) << c.errors;
    EXPECT_NE(c.info.find("respawned 1 ragdoll"), std::string::npos) << c.info;
    EXPECT_FALSE(c.session.world().drag().has_value());
    const std::vector<RigidPose> now = c.session.world().bodyPoses(c.figure()), spawned = still.session.world().bodyPoses(still.figure());
    ASSERT_EQ(now.size(), 16u);
    for (std::size_t b = 0; b < now.size(); ++b) EXPECT_LT((now[b].position - spawned[b].position).norm(), 1e-9) << b;
}

TEST(SessionEdit, ReloadDeclsDropsEditsNotSaved) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp\neditBody af_lamp_1 shade density 0.05\nreloadDecls").ok()) << c.errors;
    EXPECT_NE(c.info.find("1 ragdoll respawned"), std::string::npos) << c.info;
    EXPECT_FLOAT_EQ(float(c.session.decl("af_lamp_1")->findBody("shade")->density), 0.025f);
}

TEST(SessionEdit, TabCompletesEntitiesItemsAndKeys) {
    EditConsole c;
    ASSERT_TRUE(c.run("spawn af_lamp").ok()) << c.errors;
    EXPECT_EQ(c.commands.complete("editBody af_"), std::vector<std::string>{"af_lamp_1"});
    EXPECT_EQ(c.commands.complete("editBody af_lamp_1 sh"), std::vector<std::string>{"shade"});
    EXPECT_EQ(c.commands.complete("editBody af_lamp_1 shade dens"), std::vector<std::string>{"density"});
    EXPECT_EQ(c.commands.complete("editConstraint af_lamp_1 su"), std::vector<std::string>{"suspension"});
    EXPECT_EQ(c.commands.complete("editConstraint af_lamp_1 shade li"), std::vector<std::string>{"limit"});
    EXPECT_EQ(c.commands.complete("editConstraint af_lamp_1 suspension rest"), std::vector<std::string>{"restLength"});
}

}  // namespace
}  // namespace af::console
