// The viewer's camera in its two modes (tools/af-view/orbit_camera.h): the orbit turns about the
// target, the fly mode's look turns about the eye and its moves carry eye and target together,
// so that a switch between them keeps the picture.

#include "orbit_camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace af::view {
namespace {

constexpr Real kTolerance = 1e-9;  // units: pure rotations and translations of doubles

OrbitCamera lookingNorth() {
    OrbitCamera cam;
    cam.lookAt(Vec3(0, -100, 50), Vec3(0, 0, 50));
    return cam;
}

TEST(FlyCamera, LookTurnsAboutTheEyeToTheRightOfAMouseMovedRight) {
    OrbitCamera cam = lookingNorth();
    const Vec3 eye = cam.eye(), forward = cam.forward();
    cam.look(100, 0);
    EXPECT_LT((cam.eye() - eye).norm(), kTolerance) << "the eye stays";
    EXPECT_NEAR(cam.forward().dot(forward), std::cos(0.8), kTolerance) << "100 pixels of 0.008 radians";
    EXPECT_GT(cam.forward().x(), 0.5) << "looking north, the right is east";
    EXPECT_NEAR(cam.distance(), 100, kTolerance);
    cam.look(0, 50);
    EXPECT_LT(cam.forward().z(), -0.3) << "the mouse moved down looks down";
    EXPECT_LT((cam.eye() - eye).norm(), kTolerance);
}

TEST(FlyCamera, FlyCarriesEyeAndTargetAlongTheViewTheRightAndUp) {
    OrbitCamera cam = lookingNorth();
    cam.fly(10, 3, 2);
    EXPECT_LT((cam.eye() - Vec3(3, -90, 52)).norm(), kTolerance);
    EXPECT_LT((cam.target() - Vec3(3, 10, 52)).norm(), kTolerance);
    EXPECT_LT((cam.forward() - Vec3(0, 1, 0)).norm(), kTolerance) << "a move does not turn";
}

TEST(OrbitCameraModes, OrbitTurnsAboutTheTargetWhereLookTurnsAboutTheEye) {
    OrbitCamera orbit = lookingNorth(), fly = lookingNorth();
    orbit.rotate(100, 0);
    fly.look(100, 0);
    EXPECT_LT((orbit.target() - Vec3(0, 0, 50)).norm(), kTolerance);
    EXPECT_GT((orbit.eye() - Vec3(0, -100, 50)).norm(), 10);
    EXPECT_LT((orbit.forward() - fly.forward()).norm(), kTolerance) << "the same turn of the view";
}

}  // namespace
}  // namespace af::view
