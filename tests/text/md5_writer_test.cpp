// .md5anim writer: what it writes reads back through our parser with the same header, hierarchy
// and values; the humanoid's af_pose survives read → write → read; evaluating a written anim
// gives the joint transforms it was built from; and anims the reader would refuse are refused.

#include "af/text/md5_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace af {
namespace {

const std::string kAfPose = std::string(AF_SOURCE_DIR) + "/models/humanoid/af_pose.md5anim";
const std::string kHumanoidMesh = std::string(AF_SOURCE_DIR) + "/models/humanoid/humanoid.md5mesh";

Md5Anim parseWrittenAnim(const std::string& text) {
    const Md5AnimParseResult r = parseMd5Anim(text, "written.md5anim");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll() << "\n" << text;
    return r.anim;
}

// Doom quaternion (x, y, z, w) of a turn by `degrees` about `axis`, scaled by `scale`: the builder
// must normalise it and, for scale < 0, flip it to w >= 0.
Md5Quat turn(Real degrees, Real3 axis, Real scale = 1) {
    const Real n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const Real h = degrees * std::numbers::pi_v<Real> / 360;
    const Real s = scale * std::sin(h) / n;
    return {s * axis[0], s * axis[1], s * axis[2], scale * std::cos(h)};
}

// Three joints, three frames: a root that travels and turns (up to 170 degrees, w = 0.087),
// a chain that bends; some orientations are not unit length, some have w < 0.
struct Source {
    std::vector<std::string> names{"origin", "hips", "spine"};
    std::vector<int> parents{-1, 0, 1};
    std::vector<std::vector<Md5JointPose>> frames{
        {{{1.25, -3, 37.5}, turn(0, {0, 0, 1})}, {{0, 0, 4}, turn(30, {1, 2, 3})}, {{0, 0, 11.1}, turn(-45, {0, 1, 0})}},
        {{{2.5, -2.75, 36}, turn(10, {0, 0, 1})}, {{0.1, 0, 4}, turn(60, {1, -2, 3}, 2)}, {{0, 0.3, 11.1}, turn(20, {1, 1, 0}, -1)}},
        {{{-107.3, 64.01, 35}, turn(170, {0, 0, 1}, -0.5)}, {{0, 0, 4}, turn(90, {3, 1, 0})}, {{0, 0, 11.1}, turn(-100, {0, 1, 1})}},
    };
    std::vector<Md5Bounds> bounds{{{-10, -10, 0}, {10, 10, 70}}, {{-11, -9, 0}, {12, 10, 69.5}}, {{-120, 50, 0}, {-95, 80, 71}}};

    Md5Anim build() const { return makeMd5Anim(names, parents, frames, bounds, 30, "exported by a test"); }
};

// The input orientation as the file means it: unit length, w >= 0.
Md5Quat canonical(const Md5Quat& q) {
    const Real n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w) * (q.w < 0 ? -1 : 1);
    return {q.x / n, q.y / n, q.z / n, q.w / n};
}

TEST(Md5Writer, WrittenAnimReadsBackWithTheSameHeaderHierarchyAndValues) {
    const Md5Anim built = Source().build();
    const Md5Anim back = parseWrittenAnim(writeMd5Anim(built));
    EXPECT_EQ(back.commandLine, "exported by a test");
    EXPECT_EQ(back.frameCount, 3);
    EXPECT_EQ(back.frameRate, 30);
    EXPECT_EQ(back.animatedComponentCount, 18);
    ASSERT_EQ(back.joints.size(), 3u);
    for (std::size_t j = 0; j < 3; ++j) {
        EXPECT_EQ(back.joints[j].name, built.joints[j].name);
        EXPECT_EQ(back.joints[j].parent, built.joints[j].parent);
        EXPECT_EQ(back.joints[j].flags, md5anim::AllBits);
        EXPECT_EQ(back.joints[j].firstComponent, static_cast<int>(6 * j));
    }
    // The builder rounds to float as a file does, and every number is spelled to read back as
    // the same float, so nothing moves at all.
    EXPECT_EQ(back.components, built.components);
    ASSERT_EQ(back.bounds.size(), 3u);
    for (std::size_t f = 0; f < 3; ++f) {
        EXPECT_EQ(back.bounds[f].min, built.bounds[f].min);
        EXPECT_EQ(back.bounds[f].max, built.bounds[f].max);
    }
    ASSERT_EQ(back.baseFrame.size(), 3u);
    for (std::size_t j = 0; j < 3; ++j) {
        EXPECT_EQ(back.baseFrame[j].translation, built.baseFrame[j].translation);
        EXPECT_EQ(back.baseFrame[j].orientation, built.baseFrame[j].orientation);
    }
    EXPECT_EQ(back.baseFrame[0].translation, (Real3{0, 0, 0}));
}

TEST(Md5Writer, EvaluatingTheWrittenFileGivesTheInputTransforms) {
    const Source source;
    const Md5Anim back = parseWrittenAnim(writeMd5Anim(source.build()));
    for (int f = 0; f < 3; ++f) {
        const std::vector<Md5JointPose> poses = evaluateMd5AnimFrame(back, f);
        for (std::size_t j = 0; j < 3; ++j) {
            const Md5JointPose& in = source.frames[static_cast<std::size_t>(f)][j];
            for (int k = 0; k < 3; ++k) {
                // float rounding: half an ulp, 6e-8 relative
                EXPECT_NEAR(poses[j].translation[k], in.translation[k], 6e-8 * std::max(Real(1), std::abs(in.translation[k])))
                    << "frame " << f << " joint " << j;
            }
            const Md5Quat want = canonical(in.orientation);
            const Md5Quat got = poses[j].orientation;
            EXPECT_NEAR(got.x, want.x, 1e-7) << "frame " << f << " joint " << j;
            EXPECT_NEAR(got.y, want.y, 1e-7) << "frame " << f << " joint " << j;
            EXPECT_NEAR(got.z, want.z, 1e-7) << "frame " << f << " joint " << j;
            // w is recovered from x, y, z rounded to float: off by up to 6e-8·(x² + y² + z²)/w.
            EXPECT_NEAR(got.w, want.w, 6e-8 / want.w) << "frame " << f << " joint " << j;
        }
    }
}

TEST(Md5Writer, HumanoidAfPoseRoundTrips) {
    const Md5AnimParseResult read = loadMd5AnimFile(kAfPose);
    ASSERT_TRUE(read.ok()) << read.diagnostics.formatAll();
    const Md5Anim& a = read.anim;
    const std::string written = writeMd5Anim(a);
    const Md5Anim b = parseWrittenAnim(written);

    EXPECT_EQ(b.commandLine, a.commandLine);
    EXPECT_EQ(b.frameCount, a.frameCount);
    EXPECT_EQ(b.frameRate, a.frameRate);
    EXPECT_EQ(b.animatedComponentCount, a.animatedComponentCount);
    ASSERT_EQ(b.joints.size(), a.joints.size());
    for (std::size_t j = 0; j < a.joints.size(); ++j) {
        EXPECT_EQ(b.joints[j].name, a.joints[j].name);
        EXPECT_EQ(b.joints[j].parent, a.joints[j].parent);
        EXPECT_EQ(b.joints[j].flags, a.joints[j].flags);
        EXPECT_EQ(b.joints[j].firstComponent, a.joints[j].firstComponent);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.baseFrame[j].translation[k], a.baseFrame[j].translation[k], 1e-6);
        EXPECT_NEAR(b.baseFrame[j].orientation.x, a.baseFrame[j].orientation.x, 1e-6);
        EXPECT_NEAR(b.baseFrame[j].orientation.y, a.baseFrame[j].orientation.y, 1e-6);
        EXPECT_NEAR(b.baseFrame[j].orientation.z, a.baseFrame[j].orientation.z, 1e-6);
        EXPECT_NEAR(b.baseFrame[j].orientation.w, a.baseFrame[j].orientation.w, 1e-6);
    }
    ASSERT_EQ(b.bounds.size(), a.bounds.size());
    for (std::size_t f = 0; f < a.bounds.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(b.bounds[f].min[k], a.bounds[f].min[k], 1e-6);
            EXPECT_NEAR(b.bounds[f].max[k], a.bounds[f].max[k], 1e-6);
        }
    }
    ASSERT_EQ(b.components.size(), a.components.size());
    for (std::size_t k = 0; k < a.components.size(); ++k) EXPECT_NEAR(b.components[k], a.components[k], 1e-6) << k;

    // A second pass changes nothing, and the skeleton still fits its mesh.
    EXPECT_EQ(writeMd5Anim(b), written);
    const Md5MeshParseResult mesh = loadMd5MeshFile(kHumanoidMesh);
    ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.formatAll();
    Diagnostics fit("written.md5anim");
    checkMd5AnimMatchesMesh(b, mesh.mesh, fit);
    EXPECT_FALSE(fit.hasErrors()) << fit.formatAll();
}

TEST(Md5Writer, LayoutIsThatOfIdsExporter) {
    const Md5Anim a = makeMd5Anim({"origin", "arm"}, {-1, 0},
                                  {{{{1, 2, 3}, {0, 0, 0, 1}}, {{0.5, 0, 0}, {0, 0.6, 0, 0.8}}}},
                                  {{{-1, -2, 0}, {1, 2, 0.25}}}, 24);
    EXPECT_EQ(writeMd5Anim(a),
              "MD5Version 10\n"
              "commandline \"\"\n"
              "\n"
              "numFrames 1\n"
              "numJoints 2\n"
              "frameRate 24\n"
              "numAnimatedComponents 12\n"
              "\n"
              "hierarchy {\n"
              "\t\"origin\"\t-1 63 0\t// ( Tx Ty Tz Qx Qy Qz )\n"
              "\t\"arm\"\t0 63 6\t// origin ( Tx Ty Tz Qx Qy Qz )\n"
              "}\n"
              "\n"
              "bounds {\n"
              "\t( -1 -2 0 ) ( 1 2 0.25 )\n"
              "}\n"
              "\n"
              "baseframe {\n"
              "\t( 0 0 0 ) ( 0 0 0 )\n"
              "\t( 0.5 0 0 ) ( 0 0.6000000238 0 )\n"
              "}\n"
              "\n"
              "frame 0 {\n"
              "\t1 2 3 0 0 0\n"
              "\t0.5 0 0 0 0.6000000238 0\n"
              "}\n"
              "\n");
}

TEST(Md5Writer, BaseframeQuaternionWithNegativeWIsWrittenNegated) {
    Md5Anim a = makeMd5Anim({"origin"}, {-1}, {{{{0, 0, 0}, {0, 0, 0, 1}}}}, {{}}, 24);
    a.baseFrame[0].orientation = {0.5, -0.5, 0.5, -0.5};
    const Md5Anim back = parseWrittenAnim(writeMd5Anim(a));
    EXPECT_EQ(back.baseFrame[0].orientation, (Md5Quat{-0.5, 0.5, -0.5, 0.5}));
}

TEST(Md5Writer, SmallValuesKeepTheirFloatValue) {
    Md5Anim a = Source().build();
    a.components[0] = Real(1.234567e-7f);
    a.components[1] = Real(-3.1415926e-5f);
    const std::string text = writeMd5Anim(a);
    EXPECT_NE(text.find("\t1.234567e-07 "), std::string::npos) << "ten decimals would lose this one";
    const Md5Anim back = parseWrittenAnim(text);
    EXPECT_EQ(back.components[0], a.components[0]);
    EXPECT_EQ(back.components[1], a.components[1]);
}

TEST(Md5Writer, RefusesWhatTheReaderWouldRefuse) {
    const Md5Anim good = Source().build();
    const auto refused = [&](auto change) {
        Md5Anim a = good;
        change(a);
        EXPECT_THROW(writeMd5Anim(a), std::invalid_argument);
    };
    refused([](Md5Anim& a) { a.commandLine = "say \"hi\""; });
    refused([](Md5Anim& a) { a.joints[1].name = "two\nlines"; });
    refused([](Md5Anim& a) { a.joints[0].parent = 0; });
    refused([](Md5Anim& a) { a.joints[1].parent = 2; });
    refused([](Md5Anim& a) { a.joints[2].flags = 64; });
    refused([](Md5Anim& a) { a.joints[2].firstComponent = 13; });
    refused([](Md5Anim& a) { a.bounds.pop_back(); });
    refused([](Md5Anim& a) { a.components.pop_back(); });
    refused([](Md5Anim& a) { a.baseFrame.pop_back(); });
    refused([](Md5Anim& a) { a.frameRate = -1; });
    refused([](Md5Anim& a) { a.components[4] = std::numeric_limits<Real>::quiet_NaN(); });
    refused([](Md5Anim& a) { a.bounds[0].max[2] = 1e39; });  // finite as a double, not as a float
    EXPECT_NO_THROW(writeMd5Anim(good));
}

TEST(Md5Writer, BuilderRefusesInconsistentInput) {
    Source s;
    EXPECT_NO_THROW(s.build());
    Source zeroTurn = s;
    zeroTurn.frames[1][2].orientation = {0, 0, 0, 0};
    EXPECT_THROW(zeroTurn.build(), std::invalid_argument);
    Source shortFrame = s;
    shortFrame.frames[2].pop_back();
    EXPECT_THROW(shortFrame.build(), std::invalid_argument);
    Source fewBounds = s;
    fewBounds.bounds.pop_back();
    EXPECT_THROW(fewBounds.build(), std::invalid_argument);
    Source badParent = s;
    badParent.parents[1] = 1;
    EXPECT_THROW(badParent.build(), std::invalid_argument);
    EXPECT_THROW(makeMd5Anim({}, {}, {}, {}, 24), std::invalid_argument);
}

}  // namespace
}  // namespace af
