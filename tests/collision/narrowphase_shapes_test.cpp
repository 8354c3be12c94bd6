// The other .af shapes (bone, cylinder, flat two-sided cone), point ids under small motions, the
// symmetry of swapping A and B, and random pairs against a brute-force separating-axis test.

#include "narrowphase_test_util.h"

#include <random>

namespace af {
namespace {

using test::box;
using test::deepest;
using test::pose;
using test::rotation;
using test::randomRotation;
using test::wellFormed;

using test::kTol;

RigidPose poseOf(const BodyShape& s) { return {s.origin, s.rotation}; }

// A named pair of posed shapes.
struct Case {
    const char* name;
    const Polytope& a;
    RigidPose poseA;
    const Polytope& b;
    RigidPose poseB;
};

TEST(ShapeContact, BoneLyingOnABoxTouchesWithItsLowestCorner) {
    ShapeSpec spec;
    spec.kind = ShapeKind::bone;
    spec.v1 = Vec3(-20, 0, 5);
    spec.v2 = Vec3(20, 0, 5);
    spec.width = 4;
    spec.origin = Vec3(0, 0, 5);
    const BodyShape bone = buildShape(spec);
    // The bone's middle triangle hangs its corner 2 below the axis (z = 3); its ends are at z = 5.
    const Polytope slab = box(Vec3(30, 30, 1));
    const Manifold m = collide(bone.local, poseOf(bone), slab, pose(Vec3(0, 0, 2.1)), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.normal.z(), 1, 1e-15);
    EXPECT_NEAR(m.points[0].depth, 0.1, kTol);
    EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0, 0, 3.05), 1e-12));
    // With a wider margin, speculative points 1.9 above the slab may join; the deepest stays.
    const Manifold wide = collide(bone.local, poseOf(bone), slab, pose(Vec3(0, 0, 2.1)), 2);
    ASSERT_TRUE(wellFormed(wide, 2));
    EXPECT_NEAR(deepest(wide), 0.1, kTol);
}

// A cylinder of radius 10 and length 40 with 8 sides.
Polytope cylinder8() { return makeCylinder(Vec3(-10, -10, -20), Vec3(10, 10, 20), 8); }

TEST(ShapeContact, CylinderOnItsSideTouchesAlongOneLine) {
    // Turned about X, the ring vertex at 270° is lowest at both ends; the next ones are
    // 10(1 − cos 45°) ≈ 2.9 higher, beyond the margin.
    const Polytope c = cylinder8();
    const RigidPose lying = pose(Vec3(3, 4, 9.9), rotation(Vec3::UnitX(), 90));
    const Manifold onPlane = collideWithPlane(c, lying, Plane{Vec3::UnitZ(), 0}, 2);
    ASSERT_TRUE(wellFormed(onPlane, 2));
    ASSERT_EQ(onPlane.count, 2);
    const Manifold onBox = collide(c, lying, box(Vec3(50, 50, 5)), pose(Vec3(0, 0, -5)), 2);
    ASSERT_TRUE(wellFormed(onBox, 2));
    ASSERT_EQ(onBox.count, 2);
    EXPECT_NEAR(onBox.normal.z(), 1, 1e-15);
    for (const Manifold* m : {&onPlane, &onBox}) {
        for (int i = 0; i < 2; ++i) {
            EXPECT_NEAR(m->points[i].depth, 0.1, kTol);
            EXPECT_NEAR(m->points[i].point.x(), 3, kTol);
            EXPECT_NEAR(std::abs(m->points[i].point.y() - 4), 20, kTol);
        }
    }
}

TEST(ShapeContact, UprightCylinderKeepsFourPointsSpanningTheLargestSquare) {
    // Eight bottom corners on the plane; the best four are alternate corners, area 2R² = 200.
    const Polytope c = cylinder8();
    const RigidPose upright = pose(Vec3(0, 0, 19.9));
    const Manifold onPlane = collideWithPlane(c, upright, Plane{Vec3::UnitZ(), 0}, 2);
    const Manifold onBox = collide(c, upright, box(Vec3(50, 50, 5)), pose(Vec3(0, 0, -5)), 2);
    for (const Manifold* m : {&onPlane, &onBox}) {
        ASSERT_TRUE(wellFormed(*m, 2));
        ASSERT_EQ(m->count, 4);
        std::array<Vec3, 4> q;
        for (int i = 0; i < 4; ++i) {
            EXPECT_NEAR(m->points[i].depth, 0.1, kTol);
            q[i] = m->points[i].point;
        }
        std::sort(q.begin(), q.end(),
                  [](const Vec3& u, const Vec3& v) { return std::atan2(u.y(), u.x()) < std::atan2(v.y(), v.x()); });
        Real area = 0;
        for (int i = 0; i < 4; ++i) {
            area += q[i].x() * q[(i + 1) % 4].y() - q[(i + 1) % 4].x() * q[i].y();
        }
        EXPECT_NEAR(area / 2, 200, 1e-9);
    }
}

// A two-sided cone is a flat triangle: base (±5, 0, −10), apex at the origin; its base "face"
// has two vertices, no area and a zero normal.
Polytope flatCone() {
    ShapeSpec spec;
    spec.kind = ShapeKind::cone;
    spec.v1 = Vec3(-5, -5, -10);
    spec.v2 = Vec3(5, 5, 0);
    spec.sides = 2;
    return buildShape(spec).local;
}

TEST(ShapeContact, FlatConeLyingOnABoxTouchesWithItsWholeTriangle) {
    const Polytope cone = flatCone();
    const Polytope slab = box(Vec3(30, 30, 1));
    // Turned about X the triangle lies in the horizontal plane.
    const Manifold m = collide(cone, pose(Vec3(0, 0, 0.9), rotation(Vec3::UnitX(), 90)), slab, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(m, 1));
    ASSERT_EQ(m.count, 3);
    EXPECT_NEAR(std::abs(m.normal.z()), 1, 1e-12);
    EXPECT_GT(m.normal.z(), 0);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m.points[i].depth, 0.1, 1e-9);
    }
    // Apex down: one point.
    const Manifold apex = collide(cone, pose(Vec3(0, 0, 0.95), rotation(Vec3::UnitX(), 180)), slab, pose(Vec3::Zero()), 1);
    ASSERT_TRUE(wellFormed(apex, 1));
    ASSERT_EQ(apex.count, 1);
    EXPECT_NEAR(apex.normal.z(), 1, 1e-12);
    EXPECT_NEAR(apex.points[0].depth, 0.05, 1e-9);
    EXPECT_TRUE(apex.points[0].point.isApprox(Vec3(0, 0, 0.975), 1e-12));
    // On a plane: the three corners.
    const Manifold onPlane =
        collideWithPlane(cone, pose(Vec3(0, 0, -0.1), rotation(Vec3::UnitX(), 90)), Plane{Vec3::UnitZ(), 0}, 1);
    ASSERT_TRUE(wellFormed(onPlane, 1));
    EXPECT_EQ(onPlane.count, 3);
}

TEST(ShapeContact, CoplanarFlatConesApartInTheirPlaneAreNotTouching) {
    // Two flat triangles in one plane, 0.5 apart within it: every face normal and edge cross
    // product is the plane's normal, along which they seem to touch; libccd finds the real gap.
    const Polytope cone = flatCone();
    const Mat3 flat = rotation(Vec3::UnitX(), 90);  // base from (−5, 10, 0) to (5, 10, 0), apex at 0
    const Manifold near = collide(cone, pose(Vec3(10.5, 0, 0), flat), cone, pose(Vec3::Zero(), flat), 2);
    ASSERT_TRUE(wellFormed(near, 2));
    ASSERT_EQ(near.count, 1);
    EXPECT_LT(deepest(near), -0.25);  // libccd's direction is approximate: the gap is 0.5 along x
    EXPECT_GE(deepest(near), -0.5 - 1e-9);
    EXPECT_GT(near.normal.x(), 0.9);
    EXPECT_TRUE(collide(cone, pose(Vec3(13, 0, 0), flat), cone, pose(Vec3::Zero(), flat), 2).empty());
}

std::optional<std::uint32_t> idNear(const Manifold& m, const Vec3& p, Real within) {
    for (int i = 0; i < m.count; ++i) {
        if ((m.points[i].point - p).norm() < within) {
            return m.points[i].id;
        }
    }
    return std::nullopt;
}

// Each point of `before` has a point of `after` within `within` carrying the same id.
::testing::AssertionResult sameIdsNearby(const Manifold& before, const Manifold& after, Real within) {
    if (before.count != after.count) {
        return ::testing::AssertionFailure() << before.count << " points before, " << after.count << " after";
    }
    for (int i = 0; i < before.count; ++i) {
        const std::optional<std::uint32_t> id = idNear(after, before.points[i].point, within);
        if (id != before.points[i].id) {
            return ::testing::AssertionFailure() << "point " << i << " id " << before.points[i].id;
        }
    }
    return ::testing::AssertionSuccess();
}

TEST(ContactIds, SurviveASmallTranslationAndRotation) {
    const Vec3 shift(0.01, -0.02, 0.003);
    const Mat3 turn = rotation(Vec3(0.3, 1, 0.2), 0.5);
    const Polytope small = box(Vec3(2, 3, 1.5));
    const Polytope big = box(Vec3(20, 20, 5));
    const Polytope barX = box(Vec3(10, 2, 2));
    const Polytope barY = box(Vec3(2, 10, 2));
    const std::vector<Case> cases = {
        {"small box on big", small, pose(Vec3(1, 2, 6.45), rotation(Vec3::UnitZ(), 10)), big, pose(Vec3::Zero())},
        // Hanging over the big box's corner: two points are crossings of the two faces' edges.
        {"overhanging", small, pose(Vec3(19, 19, 6.45), rotation(Vec3::UnitZ(), 30)), big, pose(Vec3::Zero())},
        {"crossed edges", barX, pose(Vec3(0, 0, 4 * std::sqrt(2.0) - 0.1), rotation(Vec3::UnitX(), 45)), barY,
         pose(Vec3::Zero(), rotation(Vec3::UnitY(), 45))},
    };
    for (const Case& c : cases) {
        const Manifold before = collide(c.a, c.poseA, c.b, c.poseB, 1);
        ASSERT_TRUE(wellFormed(before, 1)) << c.name;
        ASSERT_GE(before.count, 1) << c.name;
        const RigidPose moved{c.poseA.position + shift, turn * c.poseA.rotation};
        const Manifold after = collide(c.a, moved, c.b, c.poseB, 1);
        EXPECT_TRUE(sameIdsNearby(before, after, 0.1)) << c.name;
    }
    const Polytope post = box(Vec3(3, 3, 4));
    const Plane floor{Vec3::UnitZ(), 0};
    const RigidPose standing = pose(Vec3(0, 0, 3.95), rotation(Vec3::UnitY(), 3));
    const Manifold before = collideWithPlane(post, standing, floor, 1);
    ASSERT_EQ(before.count, 4);
    const Manifold after = collideWithPlane(post, {standing.position + shift, turn * standing.rotation}, floor, 1);
    EXPECT_TRUE(sameIdsNearby(before, after, 0.1)) << "box on plane";
}

TEST(ContactSymmetry, SwappingTheShapesFlipsTheNormalAndKeepsThePoints) {
    const Polytope cube = box(Vec3(5, 5, 5));
    const Polytope bar = box(Vec3(10, 2, 2));
    const Polytope dodeca = makeDodecahedron(Vec3(-4, -4, -4), Vec3(4, 4, 4));
    const std::vector<Case> cases = {
        {"stacked", cube, pose(Vec3(0, 0, 9.9)), cube, pose(Vec3::Zero())},
        {"offset stack", cube, pose(Vec3(3, -2, 9.9), rotation(Vec3::UnitZ(), 20)), cube, pose(Vec3::Zero())},
        {"crossed edges", bar, pose(Vec3(0, 0, 4 * std::sqrt(2.0) - 0.1), rotation(Vec3::UnitX(), 45)), bar,
         pose(Vec3::Zero(), rotation(Vec3::UnitZ(), 90) * rotation(Vec3::UnitX(), 45))},
        {"dodecahedron on cube", dodeca, pose(Vec3(1, 2, 8.5), rotation(Vec3(1, 2, 3), 17)), cube, pose(Vec3::Zero())},
        {"gap", cube, pose(Vec3(2, 1, 10.7)), cube, pose(Vec3::Zero(), rotation(Vec3::UnitZ(), 5))},
    };
    for (const Case& c : cases) {
        const Manifold ab = collide(c.a, c.poseA, c.b, c.poseB, 1);
        const Manifold ba = collide(c.b, c.poseB, c.a, c.poseA, 1);
        ASSERT_TRUE(wellFormed(ab, 1)) << c.name;
        ASSERT_TRUE(wellFormed(ba, 1)) << c.name;
        ASSERT_GE(ab.count, 1) << c.name;
        EXPECT_TRUE(ab.normal.isApprox(-ba.normal, 1e-12)) << c.name;
        EXPECT_NEAR(deepest(ab), deepest(ba), 1e-9) << c.name;
        ASSERT_EQ(ab.count, ba.count) << c.name;
        for (int i = 0; i < ab.count; ++i) {
            bool found = false;
            for (int j = 0; j < ba.count; ++j) {
                found |= (ab.points[i].point - ba.points[j].point).norm() < 1e-9 &&
                         std::abs(ab.points[i].depth - ba.points[j].depth) < 1e-9;
            }
            EXPECT_TRUE(found) << c.name << " point " << i;
        }
    }
}

bool inside(const Polytope& world, const Vec3& x, Real tol) {
    for (const Face& f : world.faces) {
        if (f.normal.dot(x) > f.offset + tol) {
            return false;
        }
    }
    return true;
}

// Overlapping pairs: the deepest point is exactly the penetration depth and the normal is a
// direction along which it is attained. Pairs beyond the margin: empty. Every point of a face
// contact, and of an overlapping edge pair, is a real pair of surface points: half its depth back
// along the normal lies in A, half forward in B. (For separated edges the axis gives only a lower
// bound of the gap, and single points follow libccd's approximate direction.)
void expectMatchesBruteForce(const Polytope& a, const RigidPose& pa, const Polytope& b, const RigidPose& pb,
                             Real margin, int& overlapping) {
    const Polytope wa = test::placed(a, pa), wb = test::placed(b, pb);
    const test::SatReference ref = test::bruteForceSat(wa, wb);
    const Manifold m = collide(a, pa, b, pb, margin);
    ASSERT_TRUE(wellFormed(m, margin));
    if (ref.separation < -1e-6) {
        ++overlapping;
        ASSERT_FALSE(m.empty());
        EXPECT_NEAR(deepest(m), -ref.separation, 1e-6);
        EXPECT_NEAR(test::separationAlong(wa, wb, m.normal), ref.separation, 1e-6);
    } else if (ref.separation > margin) {
        EXPECT_TRUE(m.empty());
    }
    for (int i = 0; i < m.count; ++i) {
        const ManifoldPoint& p = m.points[i];
        const std::uint32_t kind = p.id >> 30;  // src/collision/contact_ids.h
        if (kind == 2 || (kind == 1 && p.depth < 0)) {
            continue;
        }
        EXPECT_TRUE(inside(wa, p.point - 0.5 * p.depth * m.normal, 1e-7)) << "point " << i << " depth " << p.depth;
        EXPECT_TRUE(inside(wb, p.point + 0.5 * p.depth * m.normal, 1e-7)) << "point " << i << " depth " << p.depth;
    }
}

TEST(ContactRandom, BoxPairsMatchABruteForceSeparatingAxisTest) {
    std::mt19937 rng(20240611);
    std::uniform_real_distribution<Real> size(0.5, 10), offset(-1, 1);
    int overlapping = 0;
    for (int k = 0; k < 3000; ++k) {
        const Vec3 ha(size(rng), size(rng), size(rng)), hb(size(rng), size(rng), size(rng));
        const Real reach = (ha + hb).norm();
        const Vec3 d = Vec3(offset(rng), offset(rng), offset(rng)) * (0.6 * reach);
        expectMatchesBruteForce(box(ha), pose(d, randomRotation(rng)), box(hb), pose(Vec3::Zero(), randomRotation(rng)),
                                1, overlapping);
        if (HasFatalFailure()) {
            return;
        }
    }
    EXPECT_GT(overlapping, 1000);
}

TEST(ContactRandom, MixedShapePairsMatchABruteForceSeparatingAxisTest) {
    const std::vector<Polytope> shapes = {
        makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6)),
        makeOctahedron(Vec3(-1, -2, -3), Vec3(3, 4, 5)),
        makeDodecahedron(Vec3(-1, 0, 2), Vec3(3, 2, 7)),
        makeCylinder(Vec3(1, -2, -1), Vec3(5, 4, 3), 3),
        makeCylinder(Vec3(-3, -3, -6), Vec3(3, 3, 6), 10),
        makeCone(Vec3(-4, -2, -8), Vec3(4, 2, 0), 5),
        makeCone(Vec3(-3, -3, -5), Vec3(3, 3, 0), 15),
        makeBone(12, 3),
    };
    std::mt19937 rng(99);
    std::uniform_real_distribution<Real> offset(-6, 6);
    std::uniform_int_distribution<size_t> pick(0, shapes.size() - 1);
    int overlapping = 0;
    for (int k = 0; k < 3000; ++k) {
        const Polytope& a = shapes[pick(rng)];
        const Polytope& b = shapes[pick(rng)];
        expectMatchesBruteForce(a, pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng)), b,
                                pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng)), 2,
                                overlapping);
        if (HasFatalFailure()) {
            return;
        }
    }
    EXPECT_GT(overlapping, 500);
}

// A flat shape against a solid one: their Minkowski difference is solid, so its faces (and the
// exact depth) still come from face normals and edge pairs, the flat edges' half-circle cones
// included.
TEST(ContactRandom, FlatShapesAgainstSolidsMatchABruteForceSeparatingAxisTest) {
    const std::vector<Polytope> flats = {
        flatCone(),
        makeBox(Vec3(-4, -3, 0), Vec3(4, 3, 0)),
        makeCylinder(Vec3(-3, -2, 1), Vec3(3, 2, 1), 6),
    };
    const std::vector<Polytope> solids = {
        box(Vec3(2, 3, 4)),
        makeCylinder(Vec3(-3, -3, -6), Vec3(3, 3, 6), 7),
        makeBone(12, 3),
    };
    std::mt19937 rng(23);
    std::uniform_real_distribution<Real> offset(-5, 5);
    int overlapping = 0;
    for (int k = 0; k < 2000; ++k) {
        const Polytope& flat = flats[k % flats.size()];
        const Polytope& solid = solids[(k / 3) % solids.size()];
        const RigidPose pf = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        const RigidPose ps = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        if (k % 2 == 0) {
            expectMatchesBruteForce(flat, pf, solid, ps, 1, overlapping);
        } else {
            expectMatchesBruteForce(solid, ps, flat, pf, 1, overlapping);
        }
        if (HasFatalFailure()) {
            return;
        }
    }
    EXPECT_GT(overlapping, 300);
}

TEST(ContactRandom, PreparedShapesGiveTheSameManifolds) {
    const std::vector<Polytope> shapes = {
        box(Vec3(2, 3, 4)), makeDodecahedron(Vec3(-1, 0, 2), Vec3(3, 2, 7)),
        makeCylinder(Vec3(-3, -3, -6), Vec3(3, 3, 6), 7), makeBone(12, 3), flatCone(),
    };
    std::vector<ConvexShape> prepared;
    for (const Polytope& p : shapes) {
        prepared.emplace_back(p);
    }
    std::mt19937 rng(17);
    std::uniform_real_distribution<Real> offset(-5, 5);
    std::uniform_int_distribution<size_t> pick(0, shapes.size() - 1);
    int nonEmpty = 0;
    for (int k = 0; k < 1000; ++k) {
        const size_t i = pick(rng), j = pick(rng);
        const RigidPose pa = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        const RigidPose pb = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        const Manifold m = collide(shapes[i], pa, shapes[j], pb, 1);
        const Manifold p = collide(prepared[i], pa, prepared[j], pb, 1);
        ASSERT_EQ(m.count, p.count);
        nonEmpty += m.count > 0;
        if (m.count > 0) {
            EXPECT_EQ(m.normal, p.normal);
        }
        for (int n = 0; n < m.count; ++n) {
            EXPECT_EQ(m.points[n].point, p.points[n].point);
            EXPECT_EQ(m.points[n].depth, p.points[n].depth);
            EXPECT_EQ(m.points[n].id, p.points[n].id);
        }
    }
    EXPECT_GT(nonEmpty, 200);
}

TEST(ContactRandom, DegenerateShapesNeverGiveNaN) {
    const std::vector<Polytope> shapes = {
        flatCone(),
        makeBox(Vec3(-4, -3, 0), Vec3(4, 3, 0)),   // zero height
        makeBox(Vec3(-4, 0, 0), Vec3(4, 0, 0)),    // a segment
        makeBone(10, 0),                           // a segment with a point in its middle
        makeCylinder(Vec3(-2, -2, 1), Vec3(2, 2, 1), 6),  // a flat hexagon
        box(Vec3(2, 3, 4)),
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> offset(-6, 6);
    for (const Polytope& a : shapes) {
        for (const Polytope& b : shapes) {
            for (int k = 0; k < 200; ++k) {
                const RigidPose pa = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
                const RigidPose pb = pose(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
                const Manifold m = collide(a, pa, b, pb, 1);
                ASSERT_TRUE(wellFormed(m, 1));
                const Manifold p = collideWithPlane(a, pa, Plane{Vec3(0, 0.6, 0.8), 0.5}, 1);
                ASSERT_TRUE(wellFormed(p, 1));
            }
        }
    }
}

}  // namespace
}  // namespace af
