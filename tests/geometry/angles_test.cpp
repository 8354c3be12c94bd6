// rotationFromAngles against Doom's stated behaviour (docs/conventions.md §0.2), checked through
// independent routes: the sense of each angle, a product of axis rotations, and Doom's own
// matrix → angles formulas applied to the transpose.

#include "geometry_test_util.h"

#include "af/geometry/math.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace af {
namespace {

using test::nearRelM;

constexpr Real kDeg = std::numbers::pi_v<Real> / 180;

TEST(Angles, ZeroAnglesGiveIdentity) {
    EXPECT_TRUE(nearRelM(rotationFromAngles(0, 0, 0), Mat3::Identity(), 1e-15));
}

TEST(Angles, PositiveYawTurnsForwardCounterClockwiseSeenFromAbove) {
    const Mat3 r = rotationFromAngles(0, 90, 0);
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitX()), Vec3(0, 1, 0), 1e-15));
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitY()), Vec3(-1, 0, 0), 1e-15));
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitZ()), Vec3(0, 0, 1), 1e-15));
}

TEST(Angles, PositivePitchPointsTheNoseDown) {
    const Mat3 r = rotationFromAngles(90, 0, 0);
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitX()), Vec3(0, 0, -1), 1e-15));
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitZ()), Vec3(1, 0, 0), 1e-15));
}

TEST(Angles, PositiveRollLiftsTheLeftAxis) {
    const Mat3 r = rotationFromAngles(0, 0, 90);
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitY()), Vec3(0, 0, 1), 1e-15));
    EXPECT_TRUE(nearRelM(Vec3(r * Vec3::UnitX()), Vec3(1, 0, 0), 1e-15));
}

TEST(Angles, EqualsYawTimesPitchTimesRollAxisRotations) {
    const Real angles[][3] = {{10, 20, 30}, {-35, 170, 5}, {80, -60, -120}, {0.5, 359, 181}};
    for (const auto& a : angles) {
        const Mat3 expected = test::rotationAbout(Vec3::UnitZ(), a[1] * kDeg) *
                              test::rotationAbout(Vec3::UnitY(), a[0] * kDeg) *
                              test::rotationAbout(Vec3::UnitX(), a[2] * kDeg);
        EXPECT_TRUE(nearRelM(rotationFromAngles(a[0], a[1], a[2]), expected, 1e-14));
    }
}

TEST(Angles, IsAProperRotation) {
    const Mat3 r = rotationFromAngles(33, -71, 140);
    EXPECT_TRUE(nearRelM(Mat3(r.transpose() * r), Mat3::Identity(), 1e-14));
    EXPECT_NEAR(r.determinant(), 1, 1e-14);
}

TEST(Angles, DoomAxisIsTheTransposeAndInvertsWithDoomsFormulas) {
    // docs/conventions.md §0.2: with axis A (rows = local axes), pitch = −asin(A[0][2]),
    // yaw = atan2(A[0][1], A[0][0]), roll = atan2(A[1][2], A[2][2]). A = Rᵀ, so A[i][j] = R(j, i).
    const Real pitch = 25, yaw = -130, roll = 65;
    const Mat3 a = rotationFromAngles(pitch, yaw, roll).transpose();
    EXPECT_NEAR(-std::asin(a(0, 2)) / kDeg, pitch, 1e-12);
    EXPECT_NEAR(std::atan2(a(0, 1), a(0, 0)) / kDeg, yaw, 1e-12);
    EXPECT_NEAR(std::atan2(a(1, 2), a(2, 2)) / kDeg, roll, 1e-12);
}

}  // namespace
}  // namespace af

namespace af {
namespace {

TEST(Angles, AnglesFromRotationInvertsRotationFromAngles) {
    for (Real pitch : {-80.0, -30.0, 0.0, 45.0, 89.0})
        for (Real yaw : {-170.0, -90.0, 0.0, 60.0, 179.0})
            for (Real roll : {-120.0, 0.0, 33.0}) {
                const Vec3 back = anglesFromRotation(rotationFromAngles(pitch, yaw, roll));
                EXPECT_NEAR(back[0], pitch, 1e-9);
                EXPECT_NEAR(back[1], yaw, 1e-9);
                EXPECT_NEAR(back[2], roll, 1e-9);
            }
}

TEST(Angles, StraightDownUsesDoomsGimbalLockRule) {
    // Pitch 90 points the nose down; yaw and roll then turn about the same axis, and Doom puts
    // all of it into yaw.
    const Mat3 r = rotationFromAngles(90, 30, 20);
    const Vec3 back = anglesFromRotation(r);
    EXPECT_NEAR(back[0], 90, 1e-6);
    EXPECT_NEAR(back[2], 0, 1e-12);
    EXPECT_LE((rotationFromAngles(back[0], back[1], back[2]) - r).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace
}  // namespace af

namespace af {
namespace {

// The angle in degrees of the rotation between a and b (‖a − b‖_F = 2√2 sin(θ/2)).
Real rotationBetweenDeg(const Mat3& a, const Mat3& b) {
    return 2 * std::asin(std::min<Real>((a - b).norm() / (2 * std::sqrt(Real(2))), 1)) / kDeg;
}

TEST(Angles, PreciseAnglesAreDoomsAwayFromGimbalLock) {
    for (Real pitch : {-80.0, -30.0, 0.0, 45.0, 89.0})
        for (Real yaw : {-170.0, -90.0, 0.0, 60.0, 179.0})
            for (Real roll : {-120.0, 0.0, 33.0}) {
                const Mat3 r = rotationFromAngles(pitch, yaw, roll);
                EXPECT_LE((anglesFromRotationPrecise(r) - anglesFromRotation(r)).cwiseAbs().maxCoeff(), 1e-9);
            }
}

// Within 0.056° of pitch ±90° Doom's reading puts the whole turn into yaw and drops roll, which
// moves the rebuilt rotation by up to cos(pitch) × 2 sin(roll / 2) rad: 0.11° at the edge, roll
// 180°. The precise angles rebuild it to rounding there (measured worst 2.0e-12°, at 1e-12° from the
// lock, where they too put the turn into yaw), and at the
// lock itself keep Doom's choice of roll 0.
TEST(Angles, PreciseAnglesRebuildTheRotationNearGimbalLock) {
    Real worstDoom = 0, worstPrecise = 0;
    for (Real pitch : {90.0, -90.0})
        for (Real away : {0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.05})
            for (Real yaw : {-180.0, -179.99999, 0.0, 30.0, 180.0})
                for (Real roll : {-180.0, -90.0, 0.0, 20.0, 179.0}) {
                    const Mat3 r = rotationFromAngles(pitch - std::copysign(away, pitch), yaw, roll);
                    const Vec3 doom = anglesFromRotation(r), precise = anglesFromRotationPrecise(r);
                    worstDoom = std::max(worstDoom, rotationBetweenDeg(rotationFromAngles(doom[0], doom[1], doom[2]), r));
                    worstPrecise = std::max(worstPrecise,
                                            rotationBetweenDeg(rotationFromAngles(precise[0], precise[1], precise[2]), r));
                    EXPECT_LE(std::abs(precise[0]), 90.0);
                }
    EXPECT_LE(worstPrecise, 1e-9);
    std::printf("angles near gimbal lock: worst rebuilt rotation error Doom %.3g deg, precise %.3g deg\n", worstDoom, worstPrecise);
    EXPECT_GE(worstDoom, 0.05);  // what the precise reading is for
    const Vec3 locked = anglesFromRotationPrecise(rotationFromAngles(90, 30, 20));
    EXPECT_NEAR(locked[0], 90, 1e-12);
    EXPECT_NEAR(locked[1], 10, 1e-9);
    EXPECT_NEAR(locked[2], 0, 1e-9);
}

}  // namespace
}  // namespace af
