// Saved ragdoll poses as `body` keys (docs/formats.md §5.5): the game's spelling byte for byte,
// strict reading, round trips through the text and through a whole .map file, and every refusal
// and warning said.

#include "af/figure/saved_pose.h"
#include "figure_test_util.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace af {
namespace {

// Round trips through the text. A position is read back as the game reads it, a float: half a
// float step is 6.1e-5 units below 2048 units (measured worst over the poses below: 6.1e-5). The
// angles keep eight decimals of a degree and are read back as floats too (half a step at 180° is
// 7.6e-6°); measured worst rotation error 1.4e-5°, gimbal lock included.
constexpr Real kPositionTolerance = 1e-4;       // units
constexpr Real kRotationToleranceDeg = 1e-3;    // degrees, angle of the rotation between the two
constexpr Real kPositionRange = 2000;           // units either way of the origin
constexpr Real kRadToDeg = 180 / std::numbers::pi_v<Real>;

// The angle in degrees of the rotation that takes `a` to `b`: ‖a − b‖_F = 2√2 sin(θ/2), which
// stays accurate for small angles where acos of the trace does not.
Real rotationErrorDeg(const Mat3& a, const Mat3& b) {
    const Real s = std::min<Real>((a - b).norm() / (2 * std::sqrt(Real(2))), 1);
    return 2 * std::asin(s) * kRadToDeg;
}

Figure humanoid(const RigidPose& placement = {}) {
    const FigureResult r = buildFigure(test::humanoidDecl(), test::humanoidPose(), "humanoid.af", placement);
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    return r.figure.value_or(Figure{});
}

// A pose the figure might rest in: every body turned and moved from its spawn pose.
std::vector<RigidPose> scatteredPoses(const Figure& figure, std::mt19937& random) {
    std::normal_distribution<Real> normal;
    std::uniform_real_distribution<Real> offset(-30, 30);
    std::vector<RigidPose> poses;
    for (const FigureBody& b : figure.bodies) {
        const Eigen::Quaternion<Real> q(normal(random), normal(random), normal(random), normal(random));
        poses.push_back({b.pose.position + Vec3(offset(random), offset(random), offset(random)),
                         q.normalized().toRotationMatrix() * b.pose.rotation});
    }
    return poses;
}

std::string parseError(std::string_view value) {
    std::string error;
    EXPECT_FALSE(parseSavedBodyPose(value, &error).has_value()) << value;
    return error;
}

TEST(SavedPose, IsSpelledAsTheGameSpellsIt) {
    EXPECT_EQ(formatSavedBodyPose({}), "0 0 0 0 0 0");
    EXPECT_EQ(formatSavedBodyPose({Vec3(-12.5, 3.25, 100), rotationFromAngles(30, -90, 45)}), "-12.5 3.25 100 30 -90 45");
    // Eight decimals, rounded; trailing zeros go but not the digits before the point.
    EXPECT_EQ(formatSavedBodyPose({Vec3(1.0 / 3, 2.0 / 3, 1200.000000004), Mat3::Identity()}),
              "0.33333333 0.66666667 1200 0 0 0");
    // Below half the eighth decimal a value is zero, from either side: `0` where the game's
    // printf would leave `-0`.
    EXPECT_EQ(formatSavedBodyPose({Vec3(4e-9, -4e-9, 123456.789), rotationFromAngles(0, 180, 0)}),
              "0 0 123456.789 0 180 0");
    EXPECT_EQ(formatSavedBodyPose({Vec3(-0.0, 0.0000000051, -0.0000000051), rotationFromAngles(-1e-9, 0, 1e-9)}),
              "0 0.00000001 -0.00000001 0 0 0");
}

TEST(SavedPose, ReadsSixNumbersAsFloats) {
    const std::optional<RigidPose> pose = parseSavedBodyPose("-12.5 3.25\t 0.1 30  -90 45", nullptr);
    ASSERT_TRUE(pose.has_value());
    EXPECT_EQ(pose->position, Vec3(-12.5, 3.25, Real(0.1f)));
    EXPECT_LE(rotationErrorDeg(pose->rotation, rotationFromAngles(30, -90, 45)), 1e-12);
    // What the game's sscanf also takes: a leading plus, an exponent.
    ASSERT_TRUE(parseSavedBodyPose("+1 2e1 3 0 0 0", nullptr).has_value());
    EXPECT_EQ(parseSavedBodyPose("+1 2e1 3 0 0 0", nullptr)->position, Vec3(1, 20, 3));
}

TEST(SavedPose, RefusesAnythingButSixFiniteNumbers) {
    EXPECT_EQ(parseError(""), "expected six numbers `x y z pitch yaw roll`, found 0");
    EXPECT_EQ(parseError("1 2 3 4 5"), "expected six numbers `x y z pitch yaw roll`, found 5");
    EXPECT_EQ(parseError("1 2 3 4 5 6 7"), "expected six numbers `x y z pitch yaw roll`, found 7");
    EXPECT_EQ(parseError("1 2 x 4 5 6"), "`x` is not a number");
    EXPECT_EQ(parseError("1,2,3 4 5 6"), "`1,2,3` is not a number");
    EXPECT_EQ(parseError("1 2 3 4 5 6deg"), "`6deg` is not a number");
    EXPECT_EQ(parseError("1 2 3 nan 5 6"), "`nan` is not a finite number");
    EXPECT_EQ(parseError("1 2 3 4 -inf 6"), "`-inf` is not a finite number");
    EXPECT_EQ(parseError("1e39 2 3 4 5 6"), "`1e39` is beyond the range of a float");
    EXPECT_FALSE(parseSavedBodyPose("1 2 3", nullptr).has_value());  // no error wanted, none written
}

// Random poses, and poses at and near gimbal lock (pitch ±90°) and the yaw seam (±180°), where
// Doom's own angle reading would lose up to 0.1°.
TEST(SavedPose, RoundTripsThroughTheTextWithinAFloat) {
    std::vector<RigidPose> poses;
    std::mt19937 random(20261206);
    std::normal_distribution<Real> normal;
    std::uniform_real_distribution<Real> coordinate(-kPositionRange, kPositionRange);
    for (int i = 0; i < 2000; ++i) {
        const Eigen::Quaternion<Real> q(normal(random), normal(random), normal(random), normal(random));
        poses.push_back({Vec3(coordinate(random), coordinate(random), coordinate(random)), q.normalized().toRotationMatrix()});
    }
    for (Real pitch : {90.0, -90.0})
        for (Real away : {0.0, 1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.05, 0.1})
            for (Real yaw : {180.0, -180.0, 179.99999, -179.99999, 0.0, 37.0})
                for (Real roll : {0.0, 90.0, -135.0, 180.0})
                    poses.push_back({Vec3(coordinate(random), 1999.99, -1999.99),
                                     rotationFromAngles(pitch - std::copysign(away, pitch), yaw, roll)});

    Real worstPosition = 0, worstRotation = 0;
    for (const RigidPose& pose : poses) {
        const std::string text = formatSavedBodyPose(pose);
        std::string error;
        const std::optional<RigidPose> back = parseSavedBodyPose(text, &error);
        ASSERT_TRUE(back.has_value()) << text << ": " << error;
        worstPosition = std::max(worstPosition, (back->position - pose.position).cwiseAbs().maxCoeff());
        worstRotation = std::max(worstRotation, rotationErrorDeg(back->rotation, pose.rotation));
    }
    EXPECT_LE(worstPosition, kPositionTolerance);
    EXPECT_LE(worstRotation, kRotationToleranceDeg);
    std::printf("saved pose round trip: worst position error %.3g units, worst rotation error %.3g deg\n", worstPosition,
                worstRotation);
}

TEST(SavedPose, RoundTripsThroughAMapFile) {
    const Figure figure = humanoid({Vec3(100, -40, 25), rotationFromAngles(10, 120, -30)});
    std::mt19937 random(7);
    const std::vector<RigidPose> poses = scatteredPoses(figure, random);

    MapFile map;
    map.entities.resize(2);
    map.entities[0].set("classname", "worldspawn");
    map.entities[1].set("classname", "af_humanoid");
    map.entities[1].set("name", "ragdoll_1");
    map.entities[1].set("origin", "100 -40 25");
    map.entities[1].set("nodrop", "1");
    const SavedPosesWrite written = writeSavedPoses(map.entities[1], figure, poses);
    ASSERT_TRUE(written.ok()) << written.error;

    // The game's layout: the other keys in place, no origin, one key per body in body order.
    const MapKeyValues& keys = map.entities[1].keys;
    EXPECT_FALSE(keys.contains("origin"));
    ASSERT_EQ(keys.size(), 3 + figure.bodies.size());
    EXPECT_EQ(keys.items()[2].key, "nodrop");
    for (std::size_t b = 0; b < figure.bodies.size(); ++b) {
        EXPECT_EQ(keys.items()[3 + b].key, "body " + figure.bodies[b].name);
        EXPECT_EQ(keys.items()[3 + b].value, formatSavedBodyPose(poses[b]));
    }

    const MapParseResult parsed = parseMapFile(writeMapFile(map), "saved.map");
    ASSERT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    const MapEntity* entity = parsed.map.findEntity("ragdoll_1");
    ASSERT_NE(entity, nullptr);
    const SavedPoses saved = readSavedPoses(*entity, figure, "saved.map");
    EXPECT_EQ(saved.diagnostics.formatAll(), "");
    ASSERT_EQ(saved.poses.size(), figure.bodies.size());
    for (std::size_t b = 0; b < figure.bodies.size(); ++b) {
        ASSERT_TRUE(saved.poses[b].has_value()) << figure.bodies[b].name;
        EXPECT_LE((saved.poses[b]->position - poses[b].position).cwiseAbs().maxCoeff(), kPositionTolerance)
            << figure.bodies[b].name;
        EXPECT_LE(rotationErrorDeg(saved.poses[b]->rotation, poses[b].rotation), kRotationToleranceDeg)
            << figure.bodies[b].name;
    }
}

TEST(SavedPose, SavingAgainReplacesTheKeysInPlace) {
    const Figure figure = humanoid();
    MapEntity entity;
    entity.set("classname", "af_humanoid");
    entity.set("BODY Pelvis", "1 2 3 0 0 0");  // another spelling of the same key
    entity.set("name", "ragdoll_1");
    std::vector<RigidPose> poses;
    for (const FigureBody& b : figure.bodies) poses.push_back(b.pose);
    ASSERT_TRUE(writeSavedPoses(entity, figure, poses).ok());
    poses[0].position.x() += 10;
    ASSERT_TRUE(writeSavedPoses(entity, figure, poses).ok());

    ASSERT_EQ(entity.keys.size(), 2 + figure.bodies.size());
    EXPECT_EQ(entity.keys.items()[1].key, "BODY Pelvis");
    EXPECT_EQ(entity.keys.items()[1].value, formatSavedBodyPose(poses[0]));
    EXPECT_EQ(entity.keys.items()[2].key, "name");
    EXPECT_EQ(entity.keys.items()[3].key, "body " + figure.bodies[1].name);
}

TEST(SavedPose, ReadsBodyNamesIgnoringCaseAndLeavesUnlistedBodiesEmpty) {
    const Figure figure = humanoid();
    MapEntity entity;
    entity.set("Body PELVIS", "1 2 3 0 90 0");
    entity.set("bodyguard", "not a saved pose");  // no space after `body`: another key
    const SavedPoses saved = readSavedPoses(entity, figure);
    EXPECT_TRUE(saved.ok());
    EXPECT_EQ(saved.diagnostics.all().size(), 0u);
    ASSERT_TRUE(saved.poses[0].has_value());
    EXPECT_EQ(saved.poses[0]->position, Vec3(1, 2, 3));
    EXPECT_EQ(std::count_if(saved.poses.begin(), saved.poses.end(), [](const auto& p) { return p.has_value(); }), 1);
}

TEST(SavedPose, UnknownBodiesWarnAndMalformedValuesAreErrorsAtTheirKeys) {
    const Figure figure = humanoid();
    const MapParseResult parsed = parseMapFile("Version 2\n"
                                               "{\n"
                                               "\"classname\" \"worldspawn\"\n"
                                               "}\n"
                                               "{\n"
                                               "\"name\" \"ragdoll_1\"\n"
                                               "\"body tail\" \"1 2 3 0 0 0\"\n"
                                               "  \"body head\" \"1 2 3 0 0\"\n"
                                               "\"body pelvis\" \"1 2 3 4 5 6\"\n"
                                               "}\n",
                                               "saved.map");
    ASSERT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    const SavedPoses saved = readSavedPoses(parsed.map.entities[1], figure, "saved.map");
    EXPECT_FALSE(saved.ok());
    EXPECT_EQ(saved.diagnostics.formatAll(),
              "saved.map:7:1: warning: key `body tail`: figure `humanoid` has no body `tail`; the saved pose is "
              "ignored\n"
              "saved.map:8:3: error: key `body head`: expected six numbers `x y z pitch yaw roll`, found 5\n");
    EXPECT_TRUE(saved.poses[0].has_value());  // read, though a caller applies none of them now
    EXPECT_FALSE(saved.poses[static_cast<std::size_t>(figure.findBody("head"))].has_value());
}

// Each refusal says why and leaves the entity as it was.
TEST(SavedPose, RefusesWhatTheMapCannotCarryAndChangesNothing) {
    const Figure good = humanoid();
    std::vector<RigidPose> poses;
    for (const FigureBody& b : good.bodies) poses.push_back(b.pose);
    MapEntity entity;
    entity.set("name", "ragdoll_1");
    entity.set("origin", "0 0 40");
    const MapEntity before = entity;

    auto refusal = [&](const Figure& figure, const std::vector<RigidPose>& bodyPoses) {
        const SavedPosesWrite r = writeSavedPoses(entity, figure, bodyPoses);
        EXPECT_FALSE(r.ok());
        EXPECT_EQ(entity, before);
        return r.error;
    };
    auto renamed = [&](std::size_t body, std::string name) {
        Figure f = good;
        f.bodies[body].name = std::move(name);
        return f;
    };

    EXPECT_EQ(refusal(renamed(1, "wa\"ist"), poses),
              "cannot save body `wa\"ist` of figure `humanoid`: a map key cannot hold a `\"` (the format has no escapes)");
    EXPECT_EQ(refusal(renamed(1, "wa\nist"), poses), "cannot save body `wa\nist` of figure `humanoid`: a map key "
                                                     "cannot hold a line break or another control character");
    EXPECT_EQ(refusal(renamed(1, "waist "), poses),
              "cannot save body `waist ` of figure `humanoid`: white space at either end of a map key is lost on reading");
    EXPECT_EQ(refusal(renamed(1, ""), poses), "cannot save body `` of figure `humanoid`: the name is empty");
    EXPECT_EQ(refusal(renamed(1, "PELVIS"), poses),
              "cannot save body `PELVIS` of figure `humanoid`: body `pelvis` would share its key (map keys ignore case)");
    EXPECT_EQ(refusal(good, {poses.begin(), poses.end() - 1}),
              "cannot save the poses of figure `humanoid`: 15 poses for 16 bodies");

    std::vector<RigidPose> bad = poses;
    bad[2].position.y() = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_EQ(refusal(good, bad), "cannot save body `chest` of figure `humanoid`: its pose is not finite");
    bad = poses;
    bad[3].rotation *= 2;
    EXPECT_EQ(refusal(good, bad), "cannot save body `head` of figure `humanoid`: its rotation matrix is not a rotation");
    bad[3].rotation = -poses[3].rotation;  // a mirror
    EXPECT_EQ(refusal(good, bad), "cannot save body `head` of figure `humanoid`: its rotation matrix is not a rotation");
}

// A space inside a name is an ordinary character of a quoted key, in our reader and the game's.
TEST(SavedPose, NamesWithInnerSpacesRoundTrip) {
    Figure figure = humanoid();
    figure.bodies[1].name = "lower back";
    std::vector<RigidPose> poses;
    for (const FigureBody& b : figure.bodies) poses.push_back(b.pose);
    MapFile map;
    map.entities.resize(1);
    ASSERT_TRUE(writeSavedPoses(map.entities[0], figure, poses).ok());
    const MapParseResult parsed = parseMapFile(writeMapFile(map), "saved.map");
    ASSERT_TRUE(parsed.ok());
    const SavedPoses saved = readSavedPoses(parsed.map.entities[0], figure, "saved.map");
    EXPECT_EQ(saved.diagnostics.formatAll(), "");
    ASSERT_TRUE(saved.poses[1].has_value());
    EXPECT_LE((saved.poses[1]->position - poses[1].position).norm(), kPositionTolerance);
}

}  // namespace
}  // namespace af
