// Skeletons from md5 files: Doom's quaternion convention and the composition of local poses.

#include "af/geometry/math.h"
#include "figure_test_util.h"

#include <cmath>

namespace af {
namespace {

using test::expectNear;

// docs/conventions.md §0.2: idAngles(0, θ, 0).ToQuat() has z = −sin(θ/2); as an md5 orientation it must turn
// the joint counter-clockwise about +Z by θ, the same rotation as the angles.
TEST(Skeleton, Md5QuaternionsAreConjugatedOnce) {
    for (Real yaw : {30.0, 90.0, -135.0}) {
        const Real h = yaw * M_PI / 360;
        const Mat3 r = rotationFromMd5({0, 0, -std::sin(h), std::cos(h)});
        expectNear(r, rotationFromAngles(0, yaw, 0), 1e-12, "yaw " + std::to_string(yaw));
        expectNear(Vec3(r * Vec3::UnitX()), Vec3(std::cos(2 * h), std::sin(2 * h), 0), 1e-12, "forward");
    }
}

TEST(Skeleton, AnimFrameComposesLocalPosesIntoModelSpace) {
    const Md5AnimParseResult r = parseMd5Anim(R"(MD5Version 10
commandline ""
numFrames 1
numJoints 3
frameRate 24
numAnimatedComponents 0
hierarchy {
	"root" -1 0 0
	"a" 0 0 0
	"b" 1 0 0
}
bounds {
	( -1 -1 -1 ) ( 1 1 1 )
}
baseframe {
	( 0 0 0 ) ( 0 0 0 )
	( 0 0 10 ) ( 0 0 -0.7071067812 )
	( 5 0 0 ) ( 0 0 0 )
}
frame 0 {
}
)",
                                              "t.md5anim");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    const Skeleton s = skeletonFromMd5Anim(r.anim, 0, Vec3(1, 2, 3));
    ASSERT_EQ(s.size(), 3u);
    expectNear(s.joints[0].position, Vec3(1, 2, 3), 1e-12, "root with the model offset");
    expectNear(s.joints[1].position, Vec3(1, 2, 13), 1e-12, "a");
    // a is turned 90° counter-clockwise about Z, so b's local +X offset points along model +Y.
    expectNear(s.joints[2].position, Vec3(1, 7, 13), 1e-6, "b");
    expectNear(Vec3(s.joints[2].rotation * Vec3::UnitX()), Vec3(Vec3::UnitY()), 1e-6, "b's forward axis");
    EXPECT_EQ(s.find("B"), 2);
    expectNear(s.local(2).position, Vec3(5, 0, 0), 1e-6, "local offset of b");
}

// The humanoid's af_pose frame 0 must reproduce the md5mesh bind pose (docs/formats.md §2.3).
TEST(Skeleton, HumanoidAfPoseMatchesBindPose) {
    const Md5MeshParseResult mesh = loadMd5MeshFile(test::sourcePath("models/humanoid/humanoid.md5mesh"));
    ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.formatAll();
    const Skeleton bind = skeletonFromMd5Mesh(mesh.mesh);
    const Skeleton pose = test::humanoidPose();
    ASSERT_EQ(bind.size(), pose.size());
    for (std::size_t i = 0; i < bind.size(); ++i) {
        EXPECT_EQ(bind.names[i], pose.names[i]);
        expectNear(pose.joints[i].position, bind.joints[i].position, 1e-5, bind.names[i]);
        expectNear(pose.joints[i].rotation, bind.joints[i].rotation, 1e-6, bind.names[i]);
    }
}

}  // namespace
}  // namespace af
