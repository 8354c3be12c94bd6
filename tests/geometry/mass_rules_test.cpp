// Structural properties of the inertia tensor (symmetric positive definite, invariant under
// translation, R·I·Rᵀ under rotation) and Doom's rules around it: degenerate fallbacks, density,
// inertiaScale, totalMass, principal moments (docs/figures.md §3.4).

#include "geometry_test_util.h"

#include "af/geometry/mass_properties.h"

#include <Eigen/Eigenvalues>

#include <limits>
#include <vector>

namespace af {
namespace {

using test::nearRel;
using test::nearRelM;

TEST(MassRules, InertiaIsSymmetricPositiveDefiniteForEveryShape) {
    for (const test::NamedShape& s : test::sampleShapes()) {
        const MassProperties mp = massProperties(s.polytope, 1);
        ASSERT_EQ(mp.status, MassStatus::ok) << s.name;
        EXPECT_TRUE(nearRelM(mp.inertia, Mat3(mp.inertia.transpose()), 1e-15)) << s.name;
        const Vec3 ev = Eigen::SelfAdjointEigenSolver<Mat3>(mp.inertia).eigenvalues();
        EXPECT_GT(ev[0], 0) << s.name;
        // Principal moments of a real solid obey the triangle inequality.
        EXPECT_GE(ev[0] + ev[1], ev[2] * (1 - 1e-12)) << s.name;
    }
}

TEST(MassRules, TranslationMovesOnlyTheCentreOfMass) {
    const Vec3 t(1000, -2000, 500);
    for (const test::NamedShape& s : test::sampleShapes()) {
        const MassProperties a = massProperties(s.polytope, 0.5);
        const MassProperties b = massProperties(translated(s.polytope, t), 0.5);
        EXPECT_TRUE(nearRel(b.mass, a.mass, 1e-12, 0)) << s.name;
        EXPECT_TRUE(nearRelM(b.centreOfMass, Vec3(a.centreOfMass + t), 1e-13)) << s.name;
        EXPECT_TRUE(nearRelM(b.inertia, a.inertia, 1e-9, 0)) << s.name;
    }
}

TEST(MassRules, RotationTransformsInertiaAsRIRt) {
    const Mat3 r = test::rotationAbout(Vec3(-1, 3, 2), 2.2);
    const Vec3 t(5, 6, -7);
    for (const test::NamedShape& s : test::sampleShapes()) {
        const MassProperties a = massProperties(s.polytope, 2);
        const MassProperties b = massProperties(transformed(s.polytope, r, t), 2);
        EXPECT_TRUE(nearRel(b.mass, a.mass, 1e-12, 0)) << s.name;
        EXPECT_TRUE(nearRelM(b.centreOfMass, Vec3(r * a.centreOfMass + t), 1e-13)) << s.name;
        EXPECT_TRUE(nearRelM(b.inertia, Mat3(r * a.inertia * r.transpose()), 1e-12, 0)) << s.name;
    }
}

TEST(MassRules, MassIsDensityTimesVolume) {
    const Polytope p = makeBox(Vec3(0, 0, 0), Vec3(2, 3, 4));
    EXPECT_TRUE(nearRel(massProperties(p, 0.2).mass, 4.8, 1e-14, 0));
    const MassProperties one = massProperties(p, 1), two = massProperties(p, 2);
    EXPECT_TRUE(nearRelM(two.inertia, Mat3(2 * one.inertia), 1e-14, 0));
    EXPECT_TRUE(nearRelM(two.centreOfMass, one.centreOfMass, 0));
}

void expectDoomFallback(const MassProperties& mp, MassStatus why) {
    EXPECT_EQ(mp.status, why);
    EXPECT_EQ(mp.mass, 1);
    EXPECT_EQ(mp.centreOfMass, Vec3::Zero());
    EXPECT_EQ(mp.inertia, Mat3::Identity());
}

TEST(MassRules, FlatShapesFallBackToUnitMass) {
    expectDoomFallback(massProperties(makeBox(Vec3(0, 0, 3), Vec3(2, 3, 3)), 1), MassStatus::zeroVolume);
    expectDoomFallback(massProperties(makeCone(Vec3(-1, -1, -1), Vec3(1, 1, 1), 2), 1), MassStatus::zeroVolume);
    expectDoomFallback(massProperties(makeBone(0, 2), 1), MassStatus::zeroVolume);
    expectDoomFallback(massProperties(makeBone(5, 0), 1), MassStatus::zeroVolume);
    expectDoomFallback(massProperties(makeCylinder(Vec3(0, 0, 0), Vec3(0, 2, 2), 5), 1), MassStatus::zeroVolume);
}

TEST(MassRules, NonPositiveDensityFallsBackToUnitMass) {
    const Polytope p = makeBox(Vec3(0, 0, 0), Vec3(2, 3, 4));
    expectDoomFallback(massProperties(p, 0), MassStatus::nonPositiveMass);
    expectDoomFallback(massProperties(p, -0.2), MassStatus::nonPositiveMass);
    expectDoomFallback(massProperties(p, std::numeric_limits<Real>::quiet_NaN()), MassStatus::nonPositiveMass);
}

TEST(MassRules, InertiaScaleIsARightMultiplication) {
    Mat3 inertia;
    inertia << 4, -1, 0.5, -1, 6, 2, 0.5, 2, 9;
    Mat3 scale;
    scale << 1, 2, 0, 0, 1, 3, 4, 0, 1;
    const Mat3 got = applyInertiaScale(inertia, scale);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const Real expected = inertia(i, 0) * scale(0, j) + inertia(i, 1) * scale(1, j) + inertia(i, 2) * scale(2, j);
            EXPECT_EQ(got(i, j), expected) << i << j;
        }
    }
}

TEST(MassRules, DiagonalInertiaScaleScalesColumns) {
    Mat3 inertia;
    inertia << 4, -1, 0.5, -1, 6, 2, 0.5, 2, 9;
    const Mat3 got = applyInertiaScale(inertia, Vec3(2, 3, 0.5).asDiagonal());
    Mat3 expected;
    expected << 8, -3, 0.25, -2, 18, 1, 1, 6, 4.5;
    EXPECT_EQ(got, expected);
}

TEST(MassRules, IdentityInertiaScaleChangesNothing) {
    Mat3 inertia;
    inertia << 4, -1, 0.5, -1, 6, 2, 0.5, 2, 9;
    EXPECT_EQ(applyInertiaScale(inertia, Mat3::Identity()), inertia);
}

std::vector<MassProperties> threeBodies() {
    std::vector<MassProperties> bodies(3);
    for (int i = 0; i < 3; ++i) {
        bodies[i].mass = i + 1;
        bodies[i].inertia = Vec3(1, 2, 3).asDiagonal() * Real(i + 1);
        bodies[i].inertia(0, 1) = bodies[i].inertia(1, 0) = 0.25;
        bodies[i].centreOfMass = Vec3(i, -i, 2 * i);
    }
    return bodies;
}

TEST(MassRules, TotalMassRescalesEveryBodyByTheSameFactor) {
    const std::vector<MassProperties> bodies = threeBodies();
    EXPECT_EQ(totalMassScale(bodies, 12), 2);
    const std::vector<MassProperties> scaled = rescaledToTotalMass(bodies, 12);
    ASSERT_EQ(scaled.size(), 3u);
    Real sum = 0;
    for (size_t i = 0; i < 3; ++i) {
        sum += scaled[i].mass;
        EXPECT_EQ(scaled[i].mass, 2 * bodies[i].mass);
        EXPECT_EQ(scaled[i].inertia, Mat3(2 * bodies[i].inertia));
        EXPECT_EQ(scaled[i].centreOfMass, bodies[i].centreOfMass);
    }
    EXPECT_TRUE(nearRel(sum, 12, 1e-15, 0));
}

TEST(MassRules, UnforcedTotalMassLeavesBodiesAlone) {
    const std::vector<MassProperties> bodies = threeBodies();
    for (Real total : {0.0, -5.0}) {
        EXPECT_EQ(totalMassScale(bodies, total), 1);
        const std::vector<MassProperties> same = rescaledToTotalMass(bodies, total);
        for (size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(same[i].mass, bodies[i].mass);
            EXPECT_EQ(same[i].inertia, bodies[i].inertia);
        }
    }
    EXPECT_EQ(totalMassScale({}, 10), 1);
}

TEST(MassRules, PrincipalMomentsOfARotatedBoxAreItsDiagonal) {
    const Mat3 r = test::rotationAbout(Vec3(1, 1, -2), 0.9);
    const MassProperties mp = massProperties(transformed(makeBox(Vec3(-1, -2, -3), Vec3(1, 2, 3)), r, Vec3(3, 3, 3)), 1);
    const PrincipalInertia pi = principalInertia(mp.inertia);
    const Real m = 2 * 4 * 6;
    // Ascending: about z (a² + b²), about y (a² + c²), about x (b² + c²), with sides 2, 4, 6.
    EXPECT_TRUE(nearRelM(pi.moments, Vec3(m * (4 + 16) / 12, m * (4 + 36) / 12, m * (16 + 36) / 12), 1e-12, 0));
    EXPECT_TRUE(nearRelM(Mat3(pi.axes.transpose() * pi.axes), Mat3::Identity(), 1e-14));
    EXPECT_NEAR(pi.axes.determinant(), 1, 1e-14);
    EXPECT_TRUE(nearRelM(Mat3(pi.axes * pi.moments.asDiagonal() * pi.axes.transpose()), mp.inertia, 1e-12, 0));
    // The smallest moment is about the box's long axis, body z, now r·z.
    EXPECT_NEAR(std::abs(pi.axes.col(0).dot(r.col(2))), 1, 1e-12);
}

TEST(MassRules, RecentringOnTheCentreOfMassPutsItAtTheBodyOrigin) {
    ShapeSpec spec;
    spec.kind = ShapeKind::cone;
    spec.v1 = Vec3(1, 2, -3);
    spec.v2 = Vec3(4, 6, 5);
    spec.sides = 6;
    spec.angles = Vec3(10, 20, 30);
    const BodyShape body = buildShape(spec);
    const MassProperties before = massProperties(body.local, 1);
    const BodyShape centred = recentred(body, before.centreOfMass);
    const MassProperties after = massProperties(centred.local, 1);
    EXPECT_TRUE(nearRelM(after.centreOfMass, Vec3::Zero(), 1e-14, 10));
    EXPECT_TRUE(nearRelM(after.inertia, before.inertia, 1e-12, 0));
    EXPECT_TRUE(nearRelM(centred.origin, Vec3(body.origin + body.rotation * before.centreOfMass), 0));
}

}  // namespace
}  // namespace af
