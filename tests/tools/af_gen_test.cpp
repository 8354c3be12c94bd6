// af-gen run as a modder runs it, from a mod folder: on our humanoid, the figure has the bodies
// and joint kinds a person would give it; on made-up skeletons (a chain, a quadruped, 100 joints)
// the figure loads without warnings, every joint is contained once, and dropped by af-sim into
// the default world it comes to rest with its joints closed and its limits kept. Bad input is
// refused with one message and exit status 2, and nothing is written.

#include "af/figure/figure.h"
#include "af/text/af_parser.h"
#include "af/text/md5_skin.h"
#include "af/text/resource_index.h"

#include "af_gen_skeletons.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using af::test::runTool;
using af::test::ToolRun;
using namespace af::test::gen;

const std::string kGen = AF_GEN_PATH;
const std::string kCheck = AF_CHECK_PATH;
const std::string kSim = AF_SIM_PATH;

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// af-gen run from `modFolder`, as the modder runs it.
ToolRun afGen(const fs::path& modFolder, const std::string& arguments) {
    return runTool("cd " + quoted(modFolder) + " && " + kGen + " " + arguments);
}

fs::path modWith(const std::string& name, const std::vector<SynthJoint>& joints) {
    const fs::path mod = af::test::scratchDir() / "mod";
    fs::create_directories(mod / "models" / name);
    af::test::writeAll(mod / "models" / name / (name + ".md5mesh"), md5meshText(joints));
    return mod;
}

// ---- what a generated figure must do ----

struct Dropped {
    double restTime = -1;  // -1: not at rest
    double jointError = 0;
    double limitViolationDeg = 0;
    std::map<std::string, double> masses;  // per body, as built
};

// Each body's mass in the built figure of an AF entity.
std::map<std::string, double> massesOf(const af::Figure& figure) {
    std::map<std::string, double> masses;
    for (const af::FigureBody& body : figure.bodies) masses[body.name] = body.mass;
    return masses;
}

// The generated entity, checked as a modder would, then dropped by af-sim into the default world.
Dropped checkAndDrop(const fs::path& mod, const fs::path& out, const std::string& name, std::size_t jointCount) {
    const std::string roots = "--root " + quoted(mod) + " --root " + quoted(out);

    // It loads, by its figure's name and by its entityDef's, and af-check has nothing to say.
    for (const char* form : {" --figure ", " --entity "}) {
        const ToolRun check = runTool(kCheck + " " + roots + form + name + " 2>&1");
        EXPECT_EQ(check.status, 0) << check.out;
        EXPECT_EQ(check.out.find("warning"), std::string::npos) << check.out;
    }

    // Every joint is contained by exactly one body.
    const af::ResourceIndex index({mod, out});
    const af::AFResources found = index.resolveAFEntity(name);
    EXPECT_TRUE(found.ok()) << found.formatDiagnostics();
    af::FigureResult built = af::buildFigure(found);
    EXPECT_TRUE(built.ok()) << built.formatDiagnostics();
    if (!built.ok()) return {};
    std::size_t claims = 0;
    for (const af::FigureBody& body : built.figure->bodies) claims += body.containedJoints.size();
    EXPECT_EQ(built.figure->jointBody.size(), jointCount);
    EXPECT_EQ(claims, jointCount) << "a joint claimed twice or not at all";
    for (std::size_t j = 0; j < built.figure->jointBody.size(); ++j) EXPECT_GE(built.figure->jointBody[j], 0) << j;

    const ToolRun sim = runTool(kSim + " " + roots + " --entity " + name + " --seconds 6 --json");
    EXPECT_EQ(sim.status, 0) << sim.out << sim.err;
    if (sim.status != 0) return {};
    const nlohmann::json j = nlohmann::json::parse(sim.out);
    Dropped d;
    d.masses = massesOf(*built.figure);
    if (j["rest_time_s"].is_number()) d.restTime = j["rest_time_s"].get<double>();
    d.jointError = j["max_joint_error"].get<double>();
    d.limitViolationDeg = j["max_limit_violation_deg"].get<double>();
    EXPECT_TRUE(j["invalid_motion"].empty()) << sim.out;
    std::printf("%s: %zu bodies, at rest after %.2f s, max joint error %.2g units, max limit violation %.2g deg\n",
                name.c_str(), built.figure->bodies.size(), d.restTime, d.jointError, d.limitViolationDeg);
    return d;
}

// The issue asks for rest within 5 s and joint error under 1e-3 units; the figures hold their
// joints to about 1e-10 units and their limits to about 5e-9° (af-sim's largest over the run), so
// those are held to 1e-8 units and 1e-7°.
void expectRestsSoundly(const Dropped& d) {
    EXPECT_GE(d.restTime, 0) << "never came to rest";
    EXPECT_LT(d.restTime, 5.0);
    EXPECT_LT(d.jointError, 1e-8);
    EXPECT_LT(d.limitViolationDeg, 1e-7);
}

std::map<std::string, std::string> constraintTypesByBody(const fs::path& afFile) {
    const af::AFParseResult parsed = af::loadAFFile(afFile.string());
    EXPECT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    std::map<std::string, std::string> types;
    if (!parsed.ok()) return types;
    for (const af::AFConstraint& c : parsed.file.decls.front().constraints) types[c.body1] = af::toString(c.type);
    return types;
}

std::vector<std::string> bodyNames(const fs::path& afFile) {
    const af::AFParseResult parsed = af::loadAFFile(afFile.string());
    std::vector<std::string> names;
    if (parsed.ok())
        for (const af::AFBody& b : parsed.file.decls.front().bodies) names.push_back(b.name);
    return names;
}

// A hinge's range of our angle about `axis` (docs/figures.md §3.8: centre a3 − a1, half-width
// a2/2), in degrees.
std::pair<double, double> hingeRange(const af::AFConstraint& c, const af::Vec3& axis) {
    const double centre = c.limitAngles[2] - c.limitAngles[0], half = c.limitAngles[1] / 2;
    const af::Vec3 own(c.axis.coordinates[0], c.axis.coordinates[1], c.axis.coordinates[2]);
    if (own.dot(axis) > 0) return {centre - half, centre + half};
    return {-centre - half, -centre + half};  // the same range about the opposite axis
}

const af::AFConstraint* constraintOf(const af::DeclAF& decl, const std::string& body1) {
    for (const af::AFConstraint& c : decl.constraints)
        if (c.body1 == body1) return &c;
    return nullptr;
}

// ---- the tests ----

TEST(AfGen, OurHumanoidGetsTheHandMadeFiguresBodiesAndJointKindsAndRests) {
    const fs::path out = af::test::scratchDir() / "out";
    const ToolRun run = afGen(AF_SOURCE_DIR, "models/humanoid/humanoid.md5mesh --anim models/humanoid/af_pose.md5anim "
                                             "--name genhuman --out " + quoted(out));
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_EQ(run.err, "") << "the figure builds without warnings";
    EXPECT_NE(run.out.find("figure genhuman: 16 bodies, 15 constraints, 25 joints, total mass 150.0"), std::string::npos)
        << run.out;

    // The bodies of af/humanoid.af, made by hand: clavicles, fingers, toes and the head's top are
    // contained by their parents' bodies.
    const std::vector<std::string> expected{"pelvis", "waist",  "chest",  "head",   "luparm", "lloarm",
                                            "lhand",  "ruparm", "rloarm", "rhand",  "lthigh", "lshin",
                                            "lfoot",  "rthigh", "rshin",  "rfoot"};
    EXPECT_EQ(bodyNames(out / "af/genhuman.af"), expected);
    const std::map<std::string, std::string> types = constraintTypesByBody(out / "af/genhuman.af");
    for (const char* hinge : {"lloarm", "rloarm", "lshin", "rshin"}) EXPECT_EQ(types.at(hinge), "hinge") << hinge;
    for (const char* ball : {"luparm", "ruparm", "lthigh", "rthigh", "lhand", "rhand", "lfoot", "rfoot"})
        EXPECT_EQ(types.at(ball), "ballAndSocketJoint") << ball;
    for (const char* spine : {"waist", "chest", "head"}) EXPECT_EQ(types.at(spine), "universalJoint") << spine;

    // Knees and elbows bend the way af/humanoid.af's do: about the same axis, their ranges on the
    // same side of straight (the hand-made ones: 5° past straight to 145°; ours to 150°).
    const af::AFParseResult made = af::loadAFFile(AF_SOURCE_DIR "/af/humanoid.af");
    const af::AFParseResult generated = af::loadAFFile((out / "af/genhuman.af").string());
    ASSERT_TRUE(made.ok() && generated.ok());
    for (const auto& [ours, theirs] : std::map<std::string, std::string>{
             {"lloarm", "lloarm"}, {"rloarm", "rloarm"}, {"lshin", "lshin"}, {"rshin", "rshin"}}) {
        const af::AFConstraint* g = constraintOf(generated.file.decls.front(), ours);
        const af::AFConstraint* m = constraintOf(made.file.decls.front(), theirs);
        using Kind = af::AFVector::Kind;
        ASSERT_TRUE(g && m && g->axis.kind == Kind::Coordinates && m->axis.kind == Kind::Coordinates && !m->axis.negated);
        const auto vec = [](const af::AFVector& v) { return af::Vec3(v.coordinates[0], v.coordinates[1], v.coordinates[2]); };
        const af::Vec3 axis = vec(m->axis).normalized();
        EXPECT_NEAR(std::fabs(vec(g->axis).normalized().dot(axis)), 1.0, 1e-6) << ours;
        const auto [gLo, gHi] = hingeRange(*g, axis);
        const auto [mLo, mHi] = hingeRange(*m, axis);
        std::printf("%s: hinge range %.1f..%.1f deg, hand-made %.1f..%.1f\n", ours.c_str(), gLo, gHi, mLo, mHi);
        EXPECT_NEAR(gLo, mLo, 10) << ours;
        EXPECT_NEAR(gHi, mHi, 10) << ours;
    }

    // The def: the model names the files by the paths given, the entityDef is an AF entity.
    const std::string def = af::test::readAll(out / "def/genhuman.def");
    EXPECT_NE(def.find("mesh\t\t\t\"models/humanoid/humanoid.md5mesh\""), std::string::npos) << def;
    EXPECT_NE(def.find("anim af_pose\t\"models/humanoid/af_pose.md5anim\""), std::string::npos) << def;
    EXPECT_NE(def.find("\"spawnclass\"\t\t\t\"idAFEntity_Generic\""), std::string::npos) << def;
    EXPECT_FALSE(fs::exists(out / "models")) << "an af_pose was given, so none is written";

    const Dropped dropped = checkAndDrop(AF_SOURCE_DIR, out, "genhuman", 25);
    expectRestsSoundly(dropped);

    // Its mass is shared out as the hand-made figure's is: the trunk and head carry about half
    // (85 of 150 there), a thigh more than a forearm.
    af::FigureResult handMade = af::buildFigure(af::ResourceIndex({AF_SOURCE_DIR}).resolveAFEntity("ragdoll_humanoid"));
    ASSERT_TRUE(handMade.ok()) << handMade.formatDiagnostics();
    const std::map<std::string, double> theirs = massesOf(*handMade.figure);
    const auto trunk = [](const std::map<std::string, double>& m) {
        return m.at("pelvis") + m.at("waist") + m.at("chest") + m.at("head");
    };
    std::printf("trunk and head: %.1f of 150 (hand-made %.1f)\n", trunk(dropped.masses), trunk(theirs));
    EXPECT_NEAR(trunk(dropped.masses), trunk(theirs), 15);
    EXPECT_GT(dropped.masses.at("lthigh"), 2 * dropped.masses.at("lloarm"));
}

TEST(AfGen, KeepAndMergeOverrideTheGrouping) {
    const fs::path out = af::test::scratchDir() / "out";
    const ToolRun run = afGen(AF_SOURCE_DIR, "models/humanoid/humanoid.md5mesh --anim models/humanoid/af_pose.md5anim "
                                             "--name kept --keep neck --merge lhand,rhand --out " + quoted(out));
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const std::vector<std::string> names = bodyNames(out / "af/kept.af");
    const std::set<std::string> bodies(names.begin(), names.end());
    EXPECT_TRUE(bodies.count("neck")) << "tiny, and kept";
    EXPECT_FALSE(bodies.count("lhand"));
    EXPECT_FALSE(bodies.count("rhand"));
    EXPECT_EQ(names.size(), 15u);
    expectRestsSoundly(checkAndDrop(AF_SOURCE_DIR, out, "kept", 25));
}

TEST(AfGen, AChainWithASkinWritesItsBindPoseAndRests) {
    const std::vector<SynthJoint> joints = chain();
    const fs::path mod = modWith("rope", joints);
    const ToolRun run = afGen(mod, "models/rope/rope.md5mesh --out gen --total-mass 20");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("total mass 20.0"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("18 vertices"), std::string::npos) << "sized from the skin: " << run.out;
    // No --anim: the bind pose is written as the af_pose, and the def names it.
    EXPECT_TRUE(fs::exists(mod / "gen/models/rope/af_pose.md5anim"));
    EXPECT_NE(af::test::readAll(mod / "gen/def/rope.def").find("\"models/rope/af_pose.md5anim\""), std::string::npos);
    // Eight links, the last one a body because it carries skin.
    EXPECT_EQ(bodyNames(mod / "gen/af/rope.af").size(), 8u);
    expectRestsSoundly(checkAndDrop(mod, mod / "gen", "rope", joints.size()));
}

// A skeleton whose subtrees are not runs in joint order (a leg comes between the hand's end nub
// and its long digit, a body of its own). `*hand` means the run "hand, nub" (docs/formats.md
// §1.6, as Doom reads it), not the hand's whole subtree: written for the whole subtree, it would
// leave joints unclaimed; the digit keeps its own.
TEST(AfGen, SubtreesOutOfJointOrderAreContainedOnce) {
    Builder s;
    const int origin = s.add("origin", -1, af::Vec3::Zero());
    const int body = s.add("body", origin, af::Vec3(0, 0, 30), 3);
    const int arm = s.add("arm", body, af::Vec3(0, 0, 40), 1.5);
    const int hand = s.add("hand", arm, af::Vec3(0, 10, 40), 1);
    s.add("nub", hand, af::Vec3(0, 11, 41));
    const int leg = s.add("leg", arm, af::Vec3(0, -10, 40), 1.5);
    const int digit = s.add("digit", hand, af::Vec3(0, 20, 40), 1);
    s.add("tip", digit, af::Vec3(0, 28, 40), 0.5);
    s.add("foot", leg, af::Vec3(0, -20, 40), 1);
    const fs::path mod = modWith("odd", s.joints);
    const ToolRun run = afGen(mod, "models/odd/odd.md5mesh --out gen");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const std::vector<std::string> names = bodyNames(mod / "gen/af/odd.af");
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).count("digit"), 1u) << run.out;
    expectRestsSoundly(checkAndDrop(mod, mod / "gen", "odd", s.joints.size()));
}

// Without an `origin` joint the root body drives the skeleton root's first child, as the
// builder binds it (docs/figures.md §3.6), and contains the root.
// A long figure lying flat has hundreds of contact rows with the floor: its block solves them by
// projected Gauss–Seidel through its joint tree (TreeSolver::setPivotRowLimit), where pivoting
// over them took seconds a step (af-sim ran minutes for 3 s). Its joints still hold.
TEST(AfGen, AFigureOfFiftySevenBodiesLandingFlatRestsWithItsJointsClosed) {
    const std::vector<SynthJoint> joints = centipede();
    const fs::path mod = modWith("centi", joints);
    ASSERT_EQ(afGen(mod, "models/centi/centi.md5mesh --out gen").status, 0);
    const Dropped dropped = checkAndDrop(mod, mod / "gen", "centi", joints.size());
    EXPECT_EQ(dropped.masses.size(), 57u);
    expectRestsSoundly(dropped);
}

TEST(AfGen, WithoutAnOriginJointTheRootBodyDrivesTheRootsFirstChild) {
    std::vector<SynthJoint> joints = chain();
    joints[0].name = "base";
    const fs::path mod = modWith("rope", joints);
    const ToolRun run = afGen(mod, "models/rope/rope.md5mesh --out gen");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_EQ(bodyNames(mod / "gen/af/rope.af").front(), "link1");
    expectRestsSoundly(checkAndDrop(mod, mod / "gen", "rope", joints.size()));
}

TEST(AfGen, AQuadrupedGetsLegsOfHipsKneesAndPawsAndRests) {
    const std::vector<SynthJoint> joints = quadruped();
    const fs::path mod = modWith("dog", joints);
    const ToolRun run = afGen(mod, "models/dog/dog.md5mesh --out gen");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const std::vector<std::string> names = bodyNames(mod / "gen/af/dog.af");
    const std::set<std::string> bodies(names.begin(), names.end());
    for (const char* merged : {"jaw", "eye_l", "fronttoe_l", "hindtoe_r", "tail3"})
        EXPECT_FALSE(bodies.count(merged)) << merged << " is an end part";
    const std::map<std::string, std::string> types = constraintTypesByBody(mod / "gen/af/dog.af");
    EXPECT_EQ(types.at("knee_l"), "hinge");
    EXPECT_EQ(types.at("elbow_r"), "hinge");
    EXPECT_EQ(types.at("thigh_l"), "ballAndSocketJoint");
    EXPECT_EQ(types.at("shoulder_r"), "ballAndSocketJoint");
    EXPECT_EQ(types.at("chest"), "universalJoint");
    expectRestsSoundly(checkAndDrop(mod, mod / "gen", "dog", joints.size()));
}

TEST(AfGen, AHundredJointsOfFingersFaceAndTagsFoldIntoAFewBodiesAndRest) {
    const std::vector<SynthJoint> joints = detailedHumanoid();
    ASSERT_EQ(joints.size(), 100u);
    const fs::path mod = modWith("hero", joints);
    const ToolRun run = afGen(mod, "models/hero/hero.md5mesh --out gen");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const std::vector<std::string> names = bodyNames(mod / "gen/af/hero.af");
    const std::vector<std::string> expected{"pelvis",     "spine1",  "spine2",     "spine3",    "neck",   "head",
                                            "upperarm_l", "forearm_l", "hand_l",   "thigh_l",   "calf_l", "foot_l",
                                            "upperarm_r", "forearm_r", "hand_r",   "thigh_r",   "calf_r", "foot_r"};
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), std::set<std::string>(expected.begin(), expected.end()))
        << run.out;
    const std::map<std::string, std::string> types = constraintTypesByBody(mod / "gen/af/hero.af");
    for (const char* hinge : {"forearm_l", "forearm_r", "calf_l", "calf_r"}) EXPECT_EQ(types.at(hinge), "hinge") << hinge;
    expectRestsSoundly(checkAndDrop(mod, mod / "gen", "hero", joints.size()));
}

// The skin af-gen sizes bodies from: the same parser as the skeleton keeps every vertex's weights.
TEST(AfGen, TheMd5ParserKeepsTheSkinWhenAsked) {
    const std::vector<SynthJoint> joints = chain();
    const std::string text = md5meshText(joints);
    const af::Md5MeshWithSkin withSkin = af::parseMd5MeshWithSkin(text, "rope.md5mesh");
    ASSERT_TRUE(withSkin.parsed.ok()) << withSkin.parsed.diagnostics.formatAll();
    EXPECT_EQ(withSkin.parsed.mesh.joints.size(), af::parseMd5Mesh(text, "rope.md5mesh").mesh.joints.size());
    ASSERT_EQ(withSkin.skin.size(), 1u);
    const af::Md5SkinSection& section = withSkin.skin.front();
    ASSERT_EQ(section.vertices.size(), 8u * 18u);  // 18 a link
    ASSERT_EQ(section.weights.size(), section.vertices.size());
    // The eleventh vertex of link3 (joint 3) sits 1.5 units off its bone, weighted wholly to it.
    const af::Md5Vertex& vertex = section.vertices[2 * 18 + 10];
    EXPECT_EQ(vertex.weightCount, 1);
    const af::Md5Weight& weight = section.weights[static_cast<std::size_t>(vertex.firstWeight)];
    EXPECT_EQ(weight.joint, 3);
    EXPECT_EQ(weight.bias, 1.0);
    EXPECT_NEAR(std::hypot(weight.position[1], weight.position[2]), 1.5, 1e-5);
}

// ---- bad input: one message, exit status 2, nothing written ----

void expectRefused(const fs::path& mod, const std::string& arguments, const std::string& message) {
    const ToolRun run = afGen(mod, arguments + " --out gen");
    EXPECT_EQ(run.status, 2) << run.out << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    EXPECT_EQ(run.out, "");
    EXPECT_FALSE(fs::exists(mod / "gen")) << "nothing is written";
}

TEST(AfGen, BadInputIsRefusedWithOneMessageAndNothingWritten) {
    const fs::path mod = modWith("ok", chain());
    expectRefused(mod, "models/missing.md5mesh", "models/missing.md5mesh");
    af::test::writeAll(mod / "models/broken.md5mesh", "MD5Version 10\ncommandline \"\"\nnumJoints 2\nnumMeshes 0\n"
                                                       "joints {\n\t\"origin\" -1 ( 0 0 0 ) ( 0 0 0 )\n}\n");
    expectRefused(mod, "models/broken.md5mesh", "models/broken.md5mesh:");
    std::vector<SynthJoint> world = chain();
    world[3].name = "world";
    af::test::writeAll(mod / "models/world.md5mesh", md5meshText(world));
    expectRefused(mod, "models/world.md5mesh", "\"world\"");
    af::test::writeAll(mod / "models/lonely.md5mesh", md5meshText({{"origin", -1, af::Vec3::Zero(), 0}}));
    expectRefused(mod, "models/lonely.md5mesh", "origin");
    expectRefused(mod, "models/ok/ok.md5mesh --anim models/humanoid/af_pose.md5anim", "af_pose.md5anim");
    expectRefused(mod, "models/ok/ok.md5mesh --name 'bad name'", "bad name");
    expectRefused(mod, "models/ok/ok.md5mesh --keep link3,linkx", "\"linkx\"");
    expectRefused(mod, "models/ok/ok.md5mesh --keep link3 --merge link3", "both kept and merged");
}

TEST(AfGen, ExistingFilesAreKeptUnlessForced) {
    const fs::path mod = modWith("rope", chain());
    ASSERT_EQ(afGen(mod, "models/rope/rope.md5mesh --out gen").status, 0);
    const ToolRun again = afGen(mod, "models/rope/rope.md5mesh --out gen --total-mass 30");
    EXPECT_EQ(again.status, 2);
    EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
    EXPECT_EQ(af::test::readAll(mod / "gen/af/rope.af").find("totalMass 30"), std::string::npos);
    ASSERT_EQ(afGen(mod, "models/rope/rope.md5mesh --out gen --total-mass 30 --force").status, 0);
    EXPECT_NE(af::test::readAll(mod / "gen/af/rope.af").find("totalMass 30"), std::string::npos);
}

}  // namespace
