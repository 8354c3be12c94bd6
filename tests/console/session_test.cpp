// The ragdoll console driven by scripts, as a modder drives it: spawn, rest, save and load poses,
// drag, delete, reload an edited figure, and a save cut short (session.h).

#include "console/session.h"
#include "session_console.h"

#include "af/collision/narrowphase.h"
#include "af/figure/saved_pose.h"
#include "af/text/map_file.h"
#include "text/map_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace af::console {
namespace {

namespace fs = std::filesystem;

using test::SessionConsole;

fs::path scratch(const std::string& name) { return test::scratchFile("af_session_test", name); }

std::string readFile(const fs::path& path) { return test::readText(path); }

// The `body` poses of every AF entity of a map file, by entity then body key.
std::map<std::string, std::map<std::string, RigidPose>> savedPoses(const fs::path& path) {
    std::map<std::string, std::map<std::string, RigidPose>> out;
    const MapParseResult parsed = loadMapFile(path.string());
    EXPECT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    for (const MapEntity& e : parsed.map.entities)
        for (const MapKeyValue& kv : e.keys)
            if (kv.key.rfind("body ", 0) == 0) out[std::string(e.value("name"))][kv.key] = *parseSavedBodyPose(kv.value);
    return out;
}

// Two ragdolls dropped across one another rest; their poses saved into a map and loaded by a
// fresh console come back as saved: saving again without a step writes the same keys.
TEST(Session, APileSavedAndLoadedAgainSavesTheSamePoses) {
    const fs::path first = scratch("pile.map"), second = scratch("pile_again.map");
    {
        SessionConsole c;
        ASSERT_TRUE(c.run("map " AF_SOURCE_DIR "/maps/default.map").ok()) << c.errors;
        ASSERT_TRUE(c.run("spawn ragdoll_humanoid origin \"0 0 40\" angles \"80 0 0\"\n"
                          "spawn ragdoll_humanoid origin \"5 0 60\" angles \"80 90 0\"\n"
                          "waitRest 10")
                        .ok())
            << c.errors;
        EXPECT_LT(c.session.world().maxJointError(), 1e-9);
        ASSERT_TRUE(c.run("saveRagdolls " + first.string()).ok()) << c.errors;
        EXPECT_NE(c.info.find("saved 2 ragdolls"), std::string::npos) << c.info;
    }
    SessionConsole fresh;
    ASSERT_TRUE(fresh.run("map " + first.string()).ok()) << fresh.errors;
    EXPECT_NE(fresh.info.find("2 ragdolls"), std::string::npos) << fresh.info;
    ASSERT_TRUE(fresh.run("saveRagdolls " + second.string()).ok()) << fresh.errors;
    const auto a = savedPoses(first), b = savedPoses(second);
    ASSERT_EQ(a.size(), 2u);
    ASSERT_EQ(b.size(), 2u);
    for (const auto& [entity, bodies] : a) {
        ASSERT_EQ(bodies.size(), 16u) << entity;
        for (const auto& [key, pose] : bodies) {
            const RigidPose& again = b.at(entity).at(key);
            EXPECT_LT((pose.position - again.position).norm(), 1e-4) << entity << " " << key;
            const Real angle = Eigen::AngleAxis<Real>(pose.rotation.transpose() * again.rotation).angle();
            EXPECT_LT(angle * 180 / 3.14159265358979, 1e-3) << entity << " " << key;
        }
    }
    // Every other part of the map is as it was read: the brushes of the default map are there.
    EXPECT_EQ(loadMapFile(second.string()).map.entities.front().primitives.size(),
              loadMapFile(AF_SOURCE_DIR "/maps/default.map").map.entities.front().primitives.size());
}

// docs/doom-physics.md §5.2: a hand dragged to 40 units above the floor and held there for 2 s
// ends within 2 units of the target with the figure hanging from it.
TEST(Session, ADraggedHandIsHeldAtTheTargetWithTheFigureHangingBelow) {
    SessionConsole c;
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid origin \"0 0 1\" angles \"90 0 0\"\nwaitRest 5").ok()) << c.errors;
    ASSERT_TRUE(c.run("drag ragdoll_humanoid_1 rhand 0 0 40\nrun 2").ok()) << c.errors;
    const World& world = c.session.world();
    const FigureId id = world.figureIds().front();
    const int hand = world.definition(id).findBody("rhand");
    const Vec3 held = world.body({id, hand}).position;
    EXPECT_LT((held - Vec3(0, 0, 40)).norm(), 2) << held.transpose();
    for (int b = 0; b < world.range(id).bodyCount; ++b) {
        if (b != hand) {
            EXPECT_LT(world.body({id, b}).position.z(), held.z() + 1) << "body " << b << " hangs below the hand";
        }
    }
    EXPECT_LT(world.maxJointError(), 1e-9);
    ASSERT_TRUE(c.run("drag off\nwaitRest 5").ok()) << c.errors;
}

TEST(Session, DeleteSelectedAndKillRagdollsRemoveEntities) {
    SessionConsole c;
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid\nspawn ragdoll_humanoid origin \"200 0 40\" name corpse").ok()) << c.errors;
    EXPECT_EQ(c.session.world().figureIds().size(), 2u);
    ASSERT_TRUE(c.run("deleteSelected").ok()) << c.errors;
    EXPECT_NE(c.info.find("deleted corpse"), std::string::npos);
    EXPECT_EQ(c.session.world().figureIds().size(), 1u);
    EXPECT_FALSE(c.run("deleteSelected").ok()) << "nothing is selected any more";
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid origin \"-200 0 40\"\nkillRagdolls\nlist").ok()) << c.errors;
    EXPECT_TRUE(c.session.world().figureIds().empty());
    EXPECT_NE(c.info.find("0 entities"), std::string::npos);
}

TEST(Session, BadCommandsSayWhatIsWrongAndChangeNothing) {
    SessionConsole c;
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid").ok());
    const Vec3 before = c.session.world().bodies().front().position;
    for (const char* bad : {"spawn no_such_def", "spawn ragdoll_humanoid origin \"1 nan 3\"", "spawn ragdoll_humanoid origin",
                            "drag nobody rhand 0 0 0", "drag ragdoll_humanoid_1 nohand 0 0 0",
                            "drag ragdoll_humanoid_1 rhand 0 inf 0", "step -1", "run x", "map /no/such.map",
                            "saveRagdolls", "spawn ragdoll_humanoid name ragdoll_humanoid_1"}) {
        c.errors.clear();
        EXPECT_FALSE(c.run(bad).ok()) << bad;
        EXPECT_FALSE(c.errors.empty()) << bad;
    }
    EXPECT_EQ(c.session.world().figureIds().size(), 1u);
    EXPECT_EQ(c.session.world().bodies().front().position, before);
    EXPECT_FALSE(c.session.world().drag().has_value());
}

// A copy of the repository's mod folder whose .af is edited while the console runs.
fs::path modCopy() {
    const fs::path root = scratch("mod");
    fs::remove_all(root);
    fs::create_directories(root);
    for (const char* dir : {"af", "def", "models"})
        fs::copy(fs::path(AF_SOURCE_DIR) / dir, root / dir, fs::copy_options::recursive);
    return root;
}

TEST(Session, ReloadDeclsRespawnsAFigureWhoseAfChanged) {
    const fs::path root = modCopy();
    SessionConsole c({root});
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid").ok()) << c.errors;
    EXPECT_NEAR(c.session.world().definition(c.session.world().figureIds().front()).totalMass(), 150, 1e-9);
    ASSERT_TRUE(c.run("reloadDecls").ok());
    EXPECT_NE(c.info.find("0 ragdolls respawned"), std::string::npos) << "nothing changed yet";
    const fs::path af = root / "af" / "humanoid.af";
    std::string text = readFile(af);
    const std::size_t at = text.find("totalMass 150");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 13, "totalMass 90");
    std::ofstream(af, std::ios::binary) << text;
    ASSERT_TRUE(c.run("reloadDecls").ok()) << c.errors;
    EXPECT_NE(c.info.find("1 ragdoll respawned"), std::string::npos) << c.info;
    const World& world = c.session.world();
    ASSERT_EQ(world.figureIds().size(), 1u);
    EXPECT_NEAR(world.definition(world.figureIds().front()).totalMass(), 90, 1e-9);
}

// A save that dies part way (after its first bytes, or just before the rename) leaves the map
// that was there byte for byte.
TEST(Session, ASaveCutShortLeavesTheOldMapWhole) {
    const fs::path path = scratch("cut.map");
    SessionConsole c;
    ASSERT_TRUE(c.run("spawn ragdoll_humanoid\nwaitRest 5\nsaveRagdolls " + path.string()).ok()) << c.errors;
    const std::string before = readFile(path);
    ASSERT_TRUE(c.run("drag ragdoll_humanoid_1 head 0 0 60\nrun 0.5\ndrag off").ok()) << c.errors;
    for (const WriteStage stage : {WriteStage::Opened, WriteStage::Wrote, WriteStage::Synced, WriteStage::Renaming}) {
        c.session.setWriteFaultHook([stage](WriteStage at, std::size_t) { return at == stage ? WriteFault::Crash : WriteFault::None; });
        EXPECT_FALSE(c.run("saveRagdolls " + path.string()).ok());
        EXPECT_EQ(readFile(path), before);
    }
    c.session.setWriteFaultHook({});
    ASSERT_TRUE(c.run("saveRagdolls " + path.string()).ok()) << c.errors;
    EXPECT_NE(readFile(path), before) << "the figure moved, so the new save differs";
}

// A wall beside (0, 0) that a ragdoll dropped there would reach into: `spawn` without an origin
// lifts the figure clear of it (placement.h), as af-sim does; an origin given inside it is obeyed,
// with a warning, as Doom's af_testSolid warns.
TEST(Session, ASpawnBesideAWallIsLiftedClearAndAnOriginInsideItIsWarnedOf) {
    const fs::path map = scratch("wall.map");
    std::ofstream(map) << af::test::floorBesideWallMap();
    SessionConsole c;
    ASSERT_TRUE(c.run("map " + map.string() + "; spawn ragdoll_humanoid").ok()) << c.errors;
    const World& world = c.session.world();
    const FigureId lifted = world.figureIds().at(0);
    std::vector<Polytope> shapes;
    for (const FigureBody& b : world.definition(lifted).bodies) shapes.push_back(b.shape);
    EXPECT_EQ(deepestOverlap(shapes, world.bodyPoses(lifted), c.session.statics()), 0);
    // The wall (x from 2 to 100, up to z = 80) is in the way of the usual drop, 32 units up.
    for (const RigidPose& p : world.bodyPoses(lifted)) EXPECT_GT(p.position.z(), 80) << "not lifted over the wall";
    EXPECT_EQ(c.info.find("warning"), std::string::npos) << c.info;

    ASSERT_TRUE(c.run("spawn ragdoll_humanoid origin \"0 0 40\" name inwall").ok()) << c.errors;
    const FigureId inWall = world.figureIds().at(1);
    EXPECT_NEAR(world.bodyPoses(inWall)[0].position.x(), world.bodyPoses(lifted)[0].position.x(), 1e-9) << "placed where asked";
    EXPECT_NE(c.info.find("warning: inwall starts "), std::string::npos) << c.info;
}

}  // namespace
}  // namespace af::console
