// .md5anim reader and frame evaluation: Doom's override rules, w recomputation, the root
// translation rule, and one positioned diagnostic for each kind of malformed file.

#include "af/text/md5.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace af {
namespace {

// origin animates Tx Ty (components 0, 1), Hips animates Qx Qz (2, 3), Spine animates Tz (4).
const std::string kAnim =
    "MD5Version 10\n"                                   // 1
    "commandline \"\"\n"                                // 2
    "\n"                                                // 3
    "numFrames 2\n"                                     // 4
    "numJoints 3\n"                                     // 5
    "frameRate 24\n"                                    // 6
    "numAnimatedComponents 5\n"                         // 7
    "\n"                                                // 8
    "hierarchy {\n"                                     // 9
    "\t\"origin\"\t-1 3 0\t// ( Tx Ty )\n"              // 10
    "\t\"Hips\"\t0 40 2\t// origin ( Qx Qz )\n"         // 11
    "\t\"Spine\"\t1 4 4\t// Hips ( Tz )\n"              // 12
    "}\n"                                               // 13
    "\n"                                                // 14
    "bounds {\n"                                        // 15
    "\t( -1 -1 0 ) ( 1 1 70 )\n"                        // 16
    "\t( -2 -2 0 ) ( 2 2 70 )\n"                        // 17
    "}\n"                                               // 18
    "\n"                                                // 19
    "baseframe {\n"                                     // 20
    "\t( 10 20 30 ) ( 0 0 0 )\n"                        // 21
    "\t( 0 0 40 ) ( 0.5 0.5 0.5 )\n"                    // 22
    "\t( 0 0 10 ) ( 0 0.6 0 )\n"                        // 23
    "}\n"                                               // 24
    "\n"                                                // 25
    "frame 0 {\n"                                       // 26
    "\t10 20 0 0 10\n"                                  // 27
    "}\n"                                               // 28
    "\n"                                                // 29
    "frame 1 {\n"                                       // 30
    "\t12.5 16 0.25 -0.5 12\n"                          // 31
    "}\n";                                              // 32

std::string animWith(const std::string& from, const std::string& to) {
    std::string text = kAnim;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

Md5Anim parseAnimGood(const std::string& text) {
    const Md5AnimParseResult r = parseMd5Anim(text, "test.md5anim");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    return r.anim;
}

std::string onlyAnimError(const std::string& text) {
    const Md5AnimParseResult r = parseMd5Anim(text, "bad.md5anim");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.all().size(), 1u) << r.diagnostics.formatAll();
    return r.diagnostics.all().empty() ? std::string() : r.diagnostics.all().front().format();
}

void expectQuat(const Md5Quat& q, Real x, Real y, Real z, Real w) {
    EXPECT_DOUBLE_EQ(q.x, x);
    EXPECT_DOUBLE_EQ(q.y, y);
    EXPECT_DOUBLE_EQ(q.z, z);
    EXPECT_NEAR(q.w, w, 1e-7);
}

TEST(Md5Anim, KeepsHeaderHierarchyBoundsBaseframeAndComponentsAsWritten) {
    const Md5Anim a = parseAnimGood(kAnim);
    EXPECT_EQ(a.frameCount, 2);
    EXPECT_EQ(a.frameRate, 24);
    EXPECT_EQ(a.animatedComponentCount, 5);
    ASSERT_EQ(a.joints.size(), 3u);
    EXPECT_EQ(a.joints[1].name, "Hips");
    EXPECT_EQ(a.joints[1].parent, 0);
    EXPECT_EQ(a.joints[1].flags, md5anim::Qx | md5anim::Qz);
    EXPECT_EQ(a.joints[1].firstComponent, 2);
    ASSERT_EQ(a.bounds.size(), 2u);
    EXPECT_EQ(a.bounds[1].min, (Real3{-2, -2, 0}));
    EXPECT_EQ(a.bounds[1].max, (Real3{2, 2, 70}));
    ASSERT_EQ(a.baseFrame.size(), 3u);
    // The data is as written: the root baseframe translation is not zeroed here.
    EXPECT_EQ(a.baseFrame[0].translation, (Real3{10, 20, 30}));
    expectQuat(a.baseFrame[1].orientation, 0.5, 0.5, 0.5, 0.5);
    ASSERT_EQ(a.components.size(), 10u);
    EXPECT_EQ(a.frameComponents(1)[0], 12.5);
    EXPECT_EQ(a.frameComponents(1)[3], -0.5);
}

TEST(Md5Anim, RootTranslationIsRelativeToBaseframe) {
    const Md5Anim a = parseAnimGood(kAnim);
    // Frame 1: Tx 12.5 - 10, Ty 16 - 20; Tz is not animated, so 0 although the baseframe says 30.
    const std::vector<Md5JointPose> f1 = evaluateMd5AnimFrame(a, 1);
    EXPECT_EQ(f1[0].translation, (Real3{2.5, -4, 0}));
    // Frame 0 sits exactly on the baseframe: the root does not move at all.
    const std::vector<Md5JointPose> f0 = evaluateMd5AnimFrame(a, 0);
    EXPECT_EQ(f0[0].translation, (Real3{0, 0, 0}));
}

TEST(Md5Anim, RootTranslationIsZeroWhenRootIsNotAnimated) {
    const Md5Anim a = parseAnimGood(animWith("\"origin\"\t-1 3 0", "\"origin\"\t-1 0 0"));
    EXPECT_EQ(evaluateMd5AnimFrame(a, 1)[0].translation, (Real3{0, 0, 0}));
}

TEST(Md5Anim, AnimatedComponentsOverrideBaseframe) {
    const Md5Anim a = parseAnimGood(kAnim);
    const std::vector<Md5JointPose> f1 = evaluateMd5AnimFrame(a, 1);
    ASSERT_EQ(f1.size(), 3u);
    // Hips: translation from the baseframe; Qx, Qz from the frame, Qy from the baseframe, so
    // w = sqrt(1 - 0.25² - 0.5² - 0.5²) = sqrt(0.4375).
    EXPECT_EQ(f1[1].translation, (Real3{0, 0, 40}));
    expectQuat(f1[1].orientation, 0.25, 0.5, -0.5, std::sqrt(0.4375));
    // Spine: Tz from the frame (not relative to anything: only the root is), the rest baseframe.
    EXPECT_EQ(f1[2].translation, (Real3{0, 0, 12}));
    expectQuat(f1[2].orientation, 0, Real(0.6f), 0, 0.8);
}

TEST(Md5Anim, RecomputesWOnlyForAnimatedQuaternions) {
    const Md5Anim a = parseAnimGood(kAnim);
    const std::vector<Md5JointPose> f0 = evaluateMd5AnimFrame(a, 0);
    // Hips frame 0 writes Qx = 0, Qz = 0 over (0.5, 0.5, 0.5): w is recomputed from (0, 0.5, 0).
    expectQuat(f0[1].orientation, 0, 0.5, 0, std::sqrt(0.75));
    // Spine's quaternion is not animated: the baseframe quaternion, w included, is kept whole.
    EXPECT_EQ(f0[2].orientation, a.baseFrame[2].orientation);
}

TEST(Md5Anim, FrameZeroUsesItsOwnComponentsNotJustTheBaseframe) {
    const Md5Anim a = parseAnimGood(animWith("\t10 20 0 0 10\n", "\t10 20 0 0 99\n"));
    EXPECT_EQ(evaluateMd5AnimFrame(a, 0)[2].translation, (Real3{0, 0, 99}));
}

TEST(Md5Anim, EvaluatingAFrameOutsideTheAnimThrows) {
    const Md5Anim a = parseAnimGood(kAnim);
    EXPECT_THROW(evaluateMd5AnimFrame(a, 2), std::out_of_range);
    EXPECT_THROW(evaluateMd5AnimFrame(a, -1), std::out_of_range);
    EXPECT_THROW(evaluateMd5AnimFrame(Md5Anim{}, 0), std::out_of_range);
}

TEST(Md5Anim, AcceptsUnanimatedJointWhoseFirstComponentIsOnePastTheEnd) {
    // Exporters write the running count there; the index is never read.
    const Md5Anim a = parseAnimGood(animWith("\"Spine\"\t1 4 4", "\"Spine\"\t1 0 5"));
    EXPECT_EQ(evaluateMd5AnimFrame(a, 1)[2].translation, (Real3{0, 0, 10}));
}

TEST(Md5Anim, RejectsFlagsBeyondTheSixComponentBits) {
    EXPECT_EQ(onlyAnimError(animWith("\"Hips\"\t0 40 2", "\"Hips\"\t0 64 2")),
              "bad.md5anim:11:11: error: expected flags from 0 to 63 (1 Tx, 2 Ty, 4 Tz, 8 Qx, 16 Qy, 32 Qz), "
              "found '64'");
}

TEST(Md5Anim, RejectsJointWhoseComponentsRunPastTheFrame) {
    EXPECT_EQ(onlyAnimError(animWith("\"Spine\"\t1 4 4", "\"Spine\"\t1 4 5")),
              "bad.md5anim:12:14: error: expected a first component index from 0 to 4 (numAnimatedComponents 5, "
              "this joint animates 1), found '5'");
    EXPECT_EQ(onlyAnimError(animWith("\"Hips\"\t0 40 2", "\"Hips\"\t0 40 4")),
              "bad.md5anim:11:14: error: expected a first component index from 0 to 3 (numAnimatedComponents 5, "
              "this joint animates 2), found '4'");
}

TEST(Md5Anim, RejectsSecondRoot) {
    EXPECT_EQ(onlyAnimError(animWith("\"Spine\"\t1", "\"Spine\"\t-1")),
              "bad.md5anim:12:10: error: expected a parent index from 0 to 1 (only the first joint is a root; a "
              "parent comes before its children), found '-1'");
}

TEST(Md5Anim, RejectsParentThatDoesNotPrecedeItsChild) {
    EXPECT_EQ(onlyAnimError(animWith("\"Hips\"\t0", "\"Hips\"\t1")),
              "bad.md5anim:11:9: error: expected a parent index from 0 to 0 (only the first joint is a root; a "
              "parent comes before its children), found '1'");
}

TEST(Md5Anim, RejectsFramesOutOfOrder) {
    EXPECT_EQ(onlyAnimError(animWith("frame 1 {", "frame 2 {")),
              "bad.md5anim:30:7: error: expected frame number 1 (frames count up from 0), found '2'");
}

TEST(Md5Anim, RejectsFrameWithTooFewComponents) {
    EXPECT_EQ(onlyAnimError(animWith("\t10 20 0 0 10\n", "\t10 20 0 0\n")),
              "bad.md5anim:28:1: error: expected a number for component 4 of frame 0 (numAnimatedComponents 5), "
              "found '}'");
}

TEST(Md5Anim, RejectsFrameWithTooManyComponents) {
    EXPECT_EQ(onlyAnimError(animWith("\t10 20 0 0 10\n", "\t10 20 0 0 10 11\n")),
              "bad.md5anim:27:15: error: expected '}' after the 5 components of frame 0 (numAnimatedComponents), "
              "found '11'");
}

TEST(Md5Anim, RejectsMissingFrames) {
    EXPECT_EQ(onlyAnimError(animWith("numFrames 2", "numFrames 3")),
              "bad.md5anim:18:1: error: expected '(' before the minimum of the bounds of frame 2, found '}'");
}

TEST(Md5Anim, RejectsZeroFrames) {
    EXPECT_EQ(onlyAnimError(animWith("numFrames 2", "numFrames 0")),
              "bad.md5anim:4:11: error: expected numFrames greater than 0, found '0'");
}

TEST(Md5Anim, RejectsMoreAnimatedComponentsThanSixPerJoint) {
    EXPECT_EQ(onlyAnimError(animWith("numAnimatedComponents 5", "numAnimatedComponents 19")),
              "bad.md5anim:7:23: error: expected numAnimatedComponents from 0 to 18 (6 per joint), found '19'");
}

TEST(Md5Anim, RejectsTrailingTokens) {
    EXPECT_EQ(onlyAnimError(kAnim + "frame 2 { }\n"),
              "bad.md5anim:33:1: error: expected end of file after the 2 frames (numFrames), found 'frame'");
}

TEST(Md5Anim, EveryTruncationIsOneErrorNeverACrash) {
    const std::size_t complete = kAnim.rfind('}');
    for (std::size_t n = 0; n <= complete; ++n) {
        const Md5AnimParseResult r = parseMd5Anim(kAnim.substr(0, n), "cut.md5anim");
        EXPECT_FALSE(r.ok()) << "cut at " << n;
        EXPECT_EQ(r.diagnostics.errorCount(), 1u) << "cut at " << n << "\n" << r.diagnostics.formatAll();
    }
}

const std::string kMatchingMesh =
    "MD5Version 10\ncommandline \"\"\nnumJoints 3\nnumMeshes 0\njoints {\n"
    "\"origin\" -1 ( 0 0 0 ) ( 0 0 0 )\n\"Hips\" 0 ( 0 0 40 ) ( 0 0 0 )\n\"Spine\" 1 ( 0 0 50 ) ( 0 0 0 )\n}\n";

TEST(Md5Anim, MatchesMeshWithSameNamesAndParents) {
    const Md5MeshParseResult mesh = parseMd5Mesh(kMatchingMesh, "m.md5mesh");
    ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.formatAll();
    Diagnostics d("test.md5anim");
    checkMd5AnimMatchesMesh(parseAnimGood(kAnim), mesh.mesh, d);
    EXPECT_FALSE(d.hasErrors()) << d.formatAll();
}

TEST(Md5Anim, MismatchWithMeshNamesTheJoint) {
    const Md5MeshParseResult mesh = parseMd5Mesh(kMatchingMesh, "m.md5mesh");
    Diagnostics names("test.md5anim");
    checkMd5AnimMatchesMesh(parseAnimGood(animWith("\"Hips\"", "\"hips\"")), mesh.mesh, names);
    EXPECT_EQ(names.formatAll(),
              "test.md5anim:11:2: error: expected joint 1 to be named \"Hips\" as in the mesh, found \"hips\"\n");

    Diagnostics parents("test.md5anim");
    checkMd5AnimMatchesMesh(parseAnimGood(animWith("\"Spine\"\t1", "\"Spine\"\t0")), mesh.mesh, parents);
    EXPECT_EQ(parents.formatAll(),
              "test.md5anim:12:2: error: expected parent 1 for joint \"Spine\" as in the mesh, found '0'\n");

    Diagnostics count("test.md5anim");
    Md5Mesh shorter = mesh.mesh;
    shorter.joints.pop_back();
    checkMd5AnimMatchesMesh(parseAnimGood(kAnim), shorter, count);
    EXPECT_EQ(count.formatAll(), "test.md5anim:5:11: error: expected numJoints 2 as in the mesh, found '3'\n");
}

}  // namespace
}  // namespace af
