// Vertex positions of every .af shape against values worked out by hand from
// docs/formats.md §1.6 and docs/figures.md §3.3, side-count clamping, the bone frame, and body placement.

#include "geometry_test_util.h"

#include <cmath>

namespace af {
namespace {

using test::nearRelM;
using test::sameVertexSet;

const Real kS3 = std::sqrt(Real(3));

TEST(Shapes, BoxVerticesAreTheEightCorners) {
    const Polytope p = makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6));
    EXPECT_TRUE(sameVertexSet(p.vertices,
                              {{-1, -2, -3}, {4, -2, -3}, {4, 5, -3}, {-1, 5, -3},
                               {-1, -2, 6}, {4, -2, 6}, {4, 5, 6}, {-1, 5, 6}},
                              0));
}

TEST(Shapes, OctahedronVerticesAreBoxFaceCentres) {
    // c = (1, 1, 1), h = (2, 3, 4).
    const Polytope p = makeOctahedron(Vec3(-1, -2, -3), Vec3(3, 4, 5));
    EXPECT_TRUE(sameVertexSet(p.vertices,
                              {{3, 1, 1}, {-1, 1, 1}, {1, 4, 1}, {1, -2, 1}, {1, 1, 5}, {1, 1, -3}}, 0));
}

TEST(Shapes, DodecahedronVerticesUseTheSpecConstantsScaledPerAxis) {
    // The literals of docs/figures.md §3.3, with v2 picked so that s_k = (v2 − v1)/(2c) is (1, 2, 3).
    const Real a = 0.5773502691896257, b = 0.3568220897730899, c = 0.9341723589627156;
    const Vec3 s(1, 2, 3);
    const Vec3 v1(1, 2, 3);
    const Vec3 v2 = v1 + 2 * c * s;
    const Vec3 centre = v1 + c * s;
    std::vector<Vec3> expected;
    for (int sx : {-1, 1}) {
        for (int sy : {-1, 1}) {
            for (int sz : {-1, 1}) {
                expected.push_back(centre + Vec3(sx * a * 1, sy * a * 2, sz * a * 3));
            }
        }
    }
    for (int s0 : {-1, 1}) {
        for (int s1 : {-1, 1}) {
            expected.push_back(centre + Vec3(s0 * b * 1, s1 * c * 2, 0));
            expected.push_back(centre + Vec3(s0 * c * 1, 0, s1 * b * 3));
            expected.push_back(centre + Vec3(0, s0 * b * 2, s1 * c * 3));
        }
    }
    const Polytope p = makeDodecahedron(v1, v2);
    EXPECT_TRUE(sameVertexSet(p.vertices, expected, 1e-14));
}

TEST(Shapes, DodecahedronFitsItsBoundsExactly) {
    const Vec3 v1(-2, 1, 0.5), v2(3, 2, 9);
    const Polytope p = makeDodecahedron(v1, v2);
    Vec3 lo = p.vertices[0], hi = p.vertices[0];
    for (const Vec3& v : p.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    EXPECT_TRUE(nearRelM(lo, v1, 1e-15, 10));
    EXPECT_TRUE(nearRelM(hi, v2, 1e-15, 10));
}

TEST(Shapes, CylinderRingsFollowTheEllipseOfTheBounds) {
    // c = (0, 0, 2), h = (2, 1, 2); vertex i at angle 2πi/n, bottom ring first.
    const Polytope p = makeCylinder(Vec3(-2, -1, 0), Vec3(2, 1, 4), 6);
    const Real r = kS3 / 2;
    const std::vector<Vec3> ring = {{2, 0, 0}, {1, r, 0}, {-1, r, 0}, {-2, 0, 0}, {-1, -r, 0}, {1, -r, 0}};
    ASSERT_EQ(p.vertices.size(), 12u);
    for (int i = 0; i < 6; ++i) {
        EXPECT_TRUE(nearRelM(p.vertices[i], ring[i], 1e-15)) << "bottom " << i;
        EXPECT_TRUE(nearRelM(p.vertices[6 + i], Vec3(ring[i] + Vec3(0, 0, 4)), 1e-15)) << "top " << i;
    }
}

TEST(Shapes, ConeApexIsAtTheBodyOriginAndTheBaseHangsBelow) {
    // Shifted bounds: min = (2, −1, 5 − 9), max = (6, 3, 0); c = (4, 1, −2), h = (2, 2, 2).
    const Polytope p = makeCone(Vec3(2, -1, 5), Vec3(6, 3, 9), 4);
    const std::vector<Vec3> expected = {{6, 1, -4}, {4, 3, -4}, {2, 1, -4}, {4, -1, -4}, {0, 0, 0}};
    ASSERT_EQ(p.vertices.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_TRUE(nearRelM(p.vertices[i], expected[i], 1e-15)) << i;
    }
}

TEST(Shapes, BoneVerticesFollowTheWidthSemantics) {
    const Polytope p = makeBone(10, 4);
    const std::vector<Vec3> expected = {{0, 0, -5}, {0, -2, 0}, {2, 1, 0}, {-2, 1, 0}, {0, 0, 5}};
    ASSERT_EQ(p.vertices.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_TRUE(nearRelM(p.vertices[i], expected[i], 0)) << i;
    }
}

TEST(Shapes, CylinderSidesClampedToTen) {
    EXPECT_EQ(clampCylinderSides(11), 10);
    EXPECT_EQ(clampCylinderSides(17), 10);
    EXPECT_EQ(clampCylinderSides(10), 10);
    EXPECT_EQ(clampCylinderSides(2), 3);
    EXPECT_EQ(clampCylinderSides(-4), 3);

    ShapeSpec spec;
    spec.kind = ShapeKind::cylinder;
    spec.sides = 11;
    const BodyShape clamped = buildShape(spec);
    EXPECT_EQ(clamped.sides, 10);
    EXPECT_EQ(clamped.local.vertices.size(), 20u);
    ASSERT_EQ(clamped.warnings.size(), 1u);
    EXPECT_NE(clamped.warnings[0].find("clamped to 10"), std::string::npos);

    spec.sides = 10;
    EXPECT_TRUE(buildShape(spec).warnings.empty());
    spec.sides = 1;  // Doom raises this silently
    const BodyShape raised = buildShape(spec);
    EXPECT_EQ(raised.sides, 3);
    EXPECT_TRUE(raised.warnings.empty());
}

TEST(Shapes, ConeSidesClampedToFifteenAndTwoIsKept) {
    EXPECT_EQ(clampConeSides(16), 15);
    EXPECT_EQ(clampConeSides(40), 15);
    EXPECT_EQ(clampConeSides(15), 15);
    EXPECT_EQ(clampConeSides(2), 2);
    EXPECT_EQ(clampConeSides(1), 3);
    EXPECT_EQ(clampConeSides(0), 3);

    ShapeSpec spec;
    spec.kind = ShapeKind::cone;
    spec.sides = 16;
    const BodyShape clamped = buildShape(spec);
    EXPECT_EQ(clamped.sides, 15);
    EXPECT_EQ(clamped.local.vertices.size(), 16u);
    EXPECT_EQ(clamped.warnings.size(), 1u);

    spec.sides = 2;
    const BodyShape flat = buildShape(spec);
    EXPECT_EQ(flat.sides, 2);
    EXPECT_EQ(flat.local.vertices.size(), 3u);
    EXPECT_TRUE(flat.warnings.empty());
}

TEST(Shapes, BoneFrameRunsFromV1ToV2) {
    // d = (0.6, 0.8, 0): X = (−0.8, 0.6, 0), Y = d × X = (0, 0, 1).
    Mat3 expected;
    expected.col(0) << -0.8, 0.6, 0;
    expected.col(1) << 0, 0, 1;
    expected.col(2) << 0.6, 0.8, 0;
    EXPECT_TRUE(nearRelM(boneRotation(Vec3(1, 1, 1), Vec3(4, 5, 1)), expected, 1e-15));
}

TEST(Shapes, VerticalBoneFrameUsesWorldX) {
    Mat3 up = Mat3::Identity();
    EXPECT_TRUE(nearRelM(boneRotation(Vec3(0, 0, 0), Vec3(0, 0, 7)), up, 0));
    Mat3 down;
    down.col(0) << 1, 0, 0;
    down.col(1) << 0, -1, 0;
    down.col(2) << 0, 0, -1;
    EXPECT_TRUE(nearRelM(boneRotation(Vec3(2, 2, 9), Vec3(2, 2, 1)), down, 0));
}

TEST(Shapes, BoneFrameIsAProperRotationForAnyDirection) {
    const Vec3 dirs[] = {{1, 2, 3}, {-4, 0.5, -1}, {0, -1, 0}, {1e-3, 0, -1}};
    for (const Vec3& d : dirs) {
        const Mat3 r = boneRotation(Vec3(5, 5, 5), Vec3(Vec3(5, 5, 5) + d));
        EXPECT_TRUE(nearRelM(Mat3(r.transpose() * r), Mat3::Identity(), 1e-15));
        EXPECT_NEAR(r.determinant(), 1, 1e-15);
        EXPECT_TRUE(nearRelM(Vec3(r.col(2)), Vec3(d.normalized()), 1e-15));
        EXPECT_EQ(r(2, 0), 0);  // X stays horizontal
    }
}

TEST(Shapes, BoneIgnoresAnglesAndIsCentredOnOrigin) {
    ShapeSpec spec;
    spec.kind = ShapeKind::bone;
    spec.v1 = Vec3(0, 0, 0);
    spec.v2 = Vec3(3, 4, 0);
    spec.width = 2;
    spec.origin = Vec3(10, 20, 30);
    spec.angles = Vec3(45, 45, 45);
    const BodyShape b = buildShape(spec);
    EXPECT_TRUE(nearRelM(b.rotation, boneRotation(spec.v1, spec.v2), 0));
    EXPECT_TRUE(nearRelM(b.origin, spec.origin, 0));
    // The bone's ends sit at origin ± (L/2)·d, not at v1 and v2.
    EXPECT_TRUE(nearRelM(Vec3(b.origin + b.rotation * b.local.vertices[4]), Vec3(11.5, 22, 30), 1e-15));
    EXPECT_TRUE(nearRelM(Vec3(b.origin + b.rotation * b.local.vertices[0]), Vec3(8.5, 18, 30), 1e-15));
}

TEST(Shapes, ZeroLengthBoneWarnsAndUsesIdentity) {
    ShapeSpec spec;
    spec.kind = ShapeKind::bone;
    spec.v1 = spec.v2 = Vec3(1, 2, 3);
    spec.width = 2;
    const BodyShape b = buildShape(spec);
    EXPECT_EQ(b.warnings.size(), 1u);
    EXPECT_TRUE(nearRelM(b.rotation, Mat3::Identity(), 0));
}

TEST(Shapes, BodyFramePlacesBoundsRelativeToOriginAndAngles) {
    ShapeSpec spec;
    spec.kind = ShapeKind::box;
    spec.v1 = Vec3(0, 0, 0);
    spec.v2 = Vec3(2, 1, 1);
    spec.origin = Vec3(10, 0, 5);
    spec.angles = Vec3(0, 90, 0);  // yaw: body X → model Y
    const BodyShape b = buildShape(spec);
    std::vector<Vec3> model;
    for (const Vec3& v : b.local.vertices) {
        model.push_back(b.origin + b.rotation * v);
    }
    EXPECT_TRUE(sameVertexSet(model,
                              {{10, 0, 5}, {10, 2, 5}, {9, 2, 5}, {9, 0, 5},
                               {10, 0, 6}, {10, 2, 6}, {9, 2, 6}, {9, 0, 6}},
                              1e-14));
    EXPECT_TRUE(b.warnings.empty());
}

TEST(Shapes, InvertedBoundsWarnPerAxis) {
    ShapeSpec spec;
    spec.kind = ShapeKind::octahedron;
    spec.v1 = Vec3(1, -1, 1);
    spec.v2 = Vec3(-1, 1, -1);
    EXPECT_EQ(buildShape(spec).warnings.size(), 2u);
}

TEST(Shapes, RecentringKeepsModelSpacePointsInPlace) {
    ShapeSpec spec;
    spec.kind = ShapeKind::cone;
    spec.v1 = Vec3(1, 2, -3);
    spec.v2 = Vec3(4, 6, 5);
    spec.sides = 7;
    spec.origin = Vec3(-3, 8, 2);
    spec.angles = Vec3(20, -40, 75);
    const BodyShape b = buildShape(spec);
    const Vec3 centre(0.5, -1, 2);
    const BodyShape m = recentred(b, centre);
    ASSERT_EQ(m.local.vertices.size(), b.local.vertices.size());
    for (size_t i = 0; i < b.local.vertices.size(); ++i) {
        EXPECT_TRUE(nearRelM(Vec3(m.local.vertices[i] + centre), b.local.vertices[i], 1e-15, 10));
        EXPECT_TRUE(nearRelM(Vec3(m.origin + m.rotation * m.local.vertices[i]),
                             Vec3(b.origin + b.rotation * b.local.vertices[i]), 1e-14, 10));
    }
}

}  // namespace
}  // namespace af
