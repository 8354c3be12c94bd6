// Boxes against planes and boxes: the geometry of each kind of contact (face, edge, vertex),
// libccd's known weak cases (face-to-face boxes, a huge box against a small one), deep
// penetration, and separated shapes within and beyond the margin.

#include "narrowphase_test_util.h"

namespace af {
namespace {

using test::box;
using test::deepest;
using test::pose;
using test::rotation;
using test::wellFormed;

using test::kTol;

TEST(PlaneContact, BoxLyingFlatGetsFourCornersWithExactDepths) {
    const Polytope b = box(Vec3(10, 6, 5));
    const Plane floor{Vec3::UnitZ(), 2};
    const Manifold m = collideWithPlane(b, pose(Vec3(1, -3, 6.9)), floor, 1);  // bottom at 1.9
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 4);
    EXPECT_EQ(m.normal, Vec3::UnitZ());
    std::set<std::pair<Real, Real>> corners;
    for (int i = 0; i < 4; ++i) {
        const ManifoldPoint& p = m.points[i];
        EXPECT_NEAR(p.depth, 0.1, kTol);
        EXPECT_NEAR(p.point.z(), 1.95, kTol);  // midway between the face (1.9) and the plane (2)
        EXPECT_NEAR(b.vertices[p.id].z(), -5, 0) << "id is the vertex index";
        corners.insert({std::round(p.point.x()), std::round(p.point.y())});
    }
    EXPECT_EQ(corners, (std::set<std::pair<Real, Real>>{{-9, -9}, {-9, 3}, {11, -9}, {11, 3}}));
}

TEST(PlaneContact, BoxTiltedOntoAnEdgeGetsTwoPointsAndOntoACornerOne) {
    const Polytope b = box(Vec3(5, 5, 5));
    const Plane floor{Vec3::UnitZ(), 0};
    // Rolled 30° about X: the bottom edge along X is lowest, the next corners 5 units higher.
    const Mat3 rolled = rotation(Vec3::UnitX(), 30);
    const Real lowest = -(rolled * Vec3(0, 5, 5)).cwiseAbs().z();
    const Manifold edge = collideWithPlane(b, pose(Vec3(0, 0, -lowest - 0.2), rolled), floor, 1);
    ASSERT_TRUE(wellFormed(edge, 1));
    ASSERT_EQ(edge.count, 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(edge.points[i].depth, 0.2, kTol);
    }
    EXPECT_NEAR(std::abs(edge.points[0].point.x() - edge.points[1].point.x()), 10, kTol);

    const Mat3 tipped = rotation(Vec3(1, 1, 0), 40) * rotation(Vec3::UnitZ(), 20);
    const Polytope world = test::placed(b, pose(Vec3::Zero(), tipped));
    Real minZ = 1e9;
    for (const Vec3& v : world.vertices) {
        minZ = std::min(minZ, v.z());
    }
    const Manifold corner = collideWithPlane(b, pose(Vec3(0, 0, -minZ - 0.05), tipped), floor, 0.5);
    ASSERT_TRUE(wellFormed(corner, 0.5));
    ASSERT_EQ(corner.count, 1);
    EXPECT_NEAR(corner.points[0].depth, 0.05, kTol);
}

TEST(PlaneContact, PlaneNormalNeedNotBeZ) {
    const Polytope b = box(Vec3(1, 2, 3));
    const Vec3 n = Vec3(1, 0, 1).normalized();
    const Plane wall{n, 0};
    // The box turned so that its -X face faces the plane, 0.25 inside it.
    const Mat3 r = rotation(Vec3::UnitY(), -45);
    const Manifold m = collideWithPlane(b, pose(n * 0.75, r), wall, 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 4);
    EXPECT_EQ(m.normal, n);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(m.points[i].depth, 0.25, kTol);
        EXPECT_NEAR(n.dot(m.points[i].point), -0.125, kTol);
    }
}

// libccd#25: GJK+EPA returns depth 0 and a NaN direction for stacked boxes face to face.
TEST(BoxContact, StackedBoxesFaceToFaceGetFourPointsAndAnExactNormal) {
    const Polytope b = box(Vec3(5, 5, 5));
    for (const Real overlap : {0.0, 0.01, 1e-7}) {
        const Manifold m = collide(b, pose(Vec3(0, 0, 10 - overlap)), b, pose(Vec3::Zero()), 1);
        ASSERT_TRUE(wellFormed(m, 1)) << overlap;
        ASSERT_EQ(m.count, 4) << overlap;
        EXPECT_EQ(m.normal, Vec3::UnitZ()) << overlap;
        for (int i = 0; i < 4; ++i) {
            EXPECT_NEAR(m.points[i].depth, overlap, kTol);
            EXPECT_NEAR(m.points[i].point.z(), 5 - overlap / 2, kTol);
            EXPECT_NEAR(m.points[i].point.x(), m.points[i].point.x() > 0 ? 5 : -5, kTol);
            EXPECT_NEAR(m.points[i].point.y(), m.points[i].point.y() > 0 ? 5 : -5, kTol);
        }
    }
}

TEST(BoxContact, TurnedBoxOnBoxKeepsTheFourPointsSpanningTheLargestArea) {
    // A square turned 45° on an equal square: the overlap is a regular octagon of circumradius R,
    // R² = 5² + (5√2 − 5)²; four of its corners span at most the square on alternate corners, 2R².
    const Polytope b = box(Vec3(5, 5, 5));
    const Manifold m = collide(b, pose(Vec3(0, 0, 9.9), rotation(Vec3::UnitZ(), 45)), b, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 4);
    EXPECT_NEAR(m.normal.z(), 1, 1e-15);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(m.points[i].depth, 0.1, kTol);
        const Vec3& p = m.points[i].point;
        EXPECT_LE(std::max(std::abs(p.x()), std::abs(p.y())), 5 + kTol);  // inside both squares
        EXPECT_LE(std::abs(p.x()) + std::abs(p.y()), 5 * std::sqrt(2.0) + kTol);
    }
    // Shoelace area of the four points taken in angular order.
    std::array<Vec3, 4> q;
    for (int i = 0; i < 4; ++i) {
        q[i] = m.points[i].point;
    }
    std::sort(q.begin(), q.end(), [](const Vec3& u, const Vec3& v) { return std::atan2(u.y(), u.x()) < std::atan2(v.y(), v.x()); });
    Real area = 0;
    for (int i = 0; i < 4; ++i) {
        area += q[i].x() * q[(i + 1) % 4].y() - q[(i + 1) % 4].x() * q[i].y();
    }
    const Real r2 = 25 + std::pow(5 * std::sqrt(2.0) - 5, 2);
    EXPECT_NEAR(area / 2, 2 * r2, 1e-9);
}

TEST(BoxContact, CrossedEdgesGetOnePointBetweenTheEdges) {
    // A lies along X rolled 45° (a roof edge down), B along Y pitched 45° (a roof edge up).
    const Polytope a = box(Vec3(10, 2, 2));
    const Polytope b = box(Vec3(2, 10, 2));
    const Real ridge = 2 * std::sqrt(2.0);
    const Manifold m = collide(a, pose(Vec3(1, -2, 2 * ridge - 0.1), rotation(Vec3::UnitX(), 45)), b,
                               pose(Vec3(1, -2, 0), rotation(Vec3::UnitY(), 45)), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.normal.z(), 1, 1e-12);
    EXPECT_NEAR(m.points[0].depth, 0.1, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(1, -2, ridge - 0.05), 1e-12));
}

TEST(BoxContact, CornerOnFaceGetsOnePointAtTheCorner) {
    const Polytope a = box(Vec3(3, 3, 3));
    const Polytope floor = box(Vec3(50, 50, 1));
    // Turn the corner (−1, −1, −1) straight down.
    const Mat3 r = Eigen::Quaternion<Real>::FromTwoVectors(Vec3(-1, -1, -1), Vec3(0, 0, -1)).toRotationMatrix();
    const Real reach = 3 * std::sqrt(3.0);
    const Manifold m = collide(a, pose(Vec3(4, 7, 1 + reach - 0.05), r), floor, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 1);
    EXPECT_EQ(m.normal, Vec3::UnitZ());  // B's face normal, exactly
    EXPECT_NEAR(m.points[0].depth, 0.05, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(4, 7, 1 - 0.025), 1e-12));
}

// libccd#17: the contact location was wrong for a large box against a small one.
TEST(BoxContact, SmallBoxOnAHugeBoxTouchesWithinItsOwnFootprint) {
    const Polytope huge = box(Vec3(500, 500, 10));
    const Polytope small = box(Vec3(0.5, 0.5, 0.5));
    const Vec3 centre(123, -77, 0.49);
    for (const bool smallIsA : {true, false}) {
        const Manifold m = smallIsA ? collide(small, pose(centre), huge, pose(Vec3(0, 0, -10)), 1)
                                    : collide(huge, pose(Vec3(0, 0, -10)), small, pose(centre), 1);
        ASSERT_TRUE(wellFormed(m, 1));
        ASSERT_EQ(m.count, 4);
        EXPECT_NEAR(std::abs(m.normal.z()), 1, 1e-15);
        EXPECT_NEAR(m.normal.z(), smallIsA ? 1 : -1, 1e-15);
        for (int i = 0; i < 4; ++i) {
            const Vec3& p = m.points[i].point;
            EXPECT_NEAR(m.points[i].depth, 0.01, 1e-9);
            EXPECT_NEAR(std::abs(p.x() - centre.x()), 0.5, 1e-9);
            EXPECT_NEAR(std::abs(p.y() - centre.y()), 0.5, 1e-9);
            EXPECT_NEAR(p.z(), -0.005, 1e-9);
        }
    }
}

TEST(BoxContact, FarFromTheOriginAWorldBrushStaysExact) {
    // A floor brush written in world coordinates (identity pose) thousands of units out, as map
    // brushes are, and a small turned box on it.
    const Vec3 corner(5000, -3000, 200);
    const Polytope brush = makeBox(corner + Vec3(-400, -400, -16), corner);
    const Polytope small = box(Vec3(1, 2, 0.5));
    const RigidPose on = pose(corner + Vec3(-100.25, -50.5, 0.49), rotation(Vec3::UnitZ(), 33));
    const Manifold m = collide(small, on, brush, RigidPose{}, 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 4);
    EXPECT_EQ(m.normal, Vec3::UnitZ());
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(m.points[i].depth, 0.01, 1e-9);
        EXPECT_NEAR(m.points[i].point.z(), corner.z() - 0.005, 1e-9);
    }
}

TEST(BoxContact, DeepPenetrationPushesOutAlongTheShortestWay) {
    // Centres 1 apart (10% of the width) along a diagonal-ish direction that favours X.
    const Polytope b = box(Vec3(5, 5, 5));
    const Manifold m = collide(b, pose(Vec3(1, 0.3, -0.2)), b, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_GE(m.count, 1);
    EXPECT_EQ(m.normal, Vec3::UnitX());
    EXPECT_NEAR(deepest(m), 9, kTol);
}

TEST(BoxContact, SeparatedBoxesWithinTheMarginGetNegativeDepths) {
    const Polytope b = box(Vec3(5, 5, 5));
    for (const Real gap : {0.0, 0.5, 1.999}) {
        const Manifold m = collide(b, pose(Vec3(0.5, 0.2, 10 + gap)), b, pose(Vec3::Zero()), 2);
        ASSERT_TRUE(wellFormed(m, 2)) << gap;
        ASSERT_EQ(m.count, 4) << gap;
        EXPECT_EQ(m.normal, Vec3::UnitZ());
        for (int i = 0; i < 4; ++i) {
            EXPECT_NEAR(m.points[i].depth, -gap, kTol);
            EXPECT_NEAR(m.points[i].point.z(), 5 + gap / 2, kTol);
        }
    }
    EXPECT_TRUE(collide(b, pose(Vec3(0.5, 0.2, 12.5)), b, pose(Vec3::Zero()), 2).empty());
}

TEST(BoxContact, CornersFartherThanTheMarginGetNothingThoughEveryAxisIsWithinIt) {
    // Corner to corner along the diagonal: every face and edge axis separates by only 1.5, but
    // the corners are 1.5·√3 ≈ 2.6 apart.
    const Polytope b = box(Vec3(1, 1, 1));
    EXPECT_TRUE(collide(b, pose(Vec3(3.5, 3.5, 3.5)), b, pose(Vec3::Zero()), 2).empty());
    // 1·√3 ≈ 1.73 apart: within the margin; the reported gap never exceeds the true one.
    const Manifold m = collide(b, pose(Vec3(3, 3, 3)), b, pose(Vec3::Zero()), 2);
    ASSERT_TRUE(wellFormed(m, 2));
    ASSERT_GE(m.count, 1);
    EXPECT_GE(deepest(m), -std::sqrt(3.0) - 1e-9);
    EXPECT_LE(deepest(m), -1 + 1e-9);
    EXPECT_GT(m.normal.minCoeff(), 0);  // pointing from B's corner out towards A's
}

TEST(BoxContact, FlatBoxOfZeroHeightRestsOnItsFace) {
    // A zero-height box: its four side faces have no area and a zero normal.
    const Polytope sheet = makeBox(Vec3(-4, -3, 0), Vec3(4, 3, 0));
    const Polytope b = box(Vec3(10, 10, 1));
    const Manifold m = collide(sheet, pose(Vec3(0, 0, 0.9)), b, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 4);
    EXPECT_NEAR(m.normal.z(), 1, 1e-12);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(m.points[i].depth, 0.1, kTol);
    }
    // Standing on its long edge: one edge's two ends.
    const Manifold edge = collide(sheet, pose(Vec3(0, 0, 3.9), rotation(Vec3::UnitX(), 90)), b, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(edge, 1));
    ASSERT_EQ(edge.count, 2);
    EXPECT_NEAR(edge.normal.z(), 1, 1e-12);
    EXPECT_NEAR(deepest(edge), 0.1, kTol);
}

}  // namespace
}  // namespace af

namespace af {
namespace {

// deepestOverlap: the deepest reach of any shape into any static; statics whose bounding boxes
// miss a shape's are skipped, which must not lose an overlap.
TEST(DeepestOverlap, IsTheDeepestPenetrationOfAnyShapeIntoAnyStatic) {
    const std::vector<Polytope> statics{makeBox(Vec3(-100, -100, -16), Vec3(100, 100, 0)),  // floor
                                        makeBox(Vec3(2, -64, 0), Vec3(100, 64, 80))};     // wall
    const std::vector<Polytope> shapes{test::box(Vec3(1, 1, 1)), test::box(Vec3(2, 2, 2))};
    const auto overlap = [&](const Vec3& a, const Vec3& b) {
        const std::vector<RigidPose> poses{test::pose(a), test::pose(b)};
        return deepestOverlap(shapes, poses, statics);
    };
    EXPECT_EQ(overlap(Vec3(0, 0, 10), Vec3(-10, 0, 10)), 0) << "both clear";
    EXPECT_NEAR(overlap(Vec3(0, 0, 0.75), Vec3(-10, 0, 10)), 0.25, 1e-12) << "the first 0.25 into the floor";
    EXPECT_NEAR(overlap(Vec3(0, 0, 10), Vec3(0.5, 0, 40)), 0.5, 1e-12) << "the second 0.5 into the wall";
    EXPECT_NEAR(overlap(Vec3(0, 0, 0.75), Vec3(0.5, 0, 40)), 0.5, 1e-12) << "the deeper of the two";
    EXPECT_NEAR(overlap(Vec3(0, 0, 10), Vec3(-10, 0, 79.5 + 2)), 0, 1e-12) << "above the wall's top and beside it";
}

}  // namespace
}  // namespace af
