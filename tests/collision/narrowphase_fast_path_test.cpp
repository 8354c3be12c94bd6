// The narrowphase's shortcuts against the paths they stand in for, on many random poses: the
// closed-form box–box axis search against the polytope search, and the skipping of libccd where
// the axis's features show its separation is the distance, against a brute-force distance and
// against what libccd would have answered.

#include "collision/ccd_query.h"
#include "collision/collide_placed.h"

#include "narrowphase_test_util.h"

#include <random>

namespace af {
namespace {

using namespace collision_detail;
using test::box;
using test::pose;
using test::randomRotation;
using test::randomVector;

// A box whose body frame is not its own: shifted and turned, as a body's shape is around its
// centre of mass.
Polytope offsetBox(std::mt19937& rng) {
    const Polytope b = box(randomVector(rng, 0.2, 3));
    return transformed(b, randomRotation(rng), randomVector(rng, -1, 1));
}

// The pair placed in A's body frame, as collide() places it.
std::pair<PlacedShape, PlacedShape> place(const Polytope& a, const ShapeFeatures& fa, const RigidPose& poseA,
                                          const Polytope& b, const ShapeFeatures& fb, const RigidPose& poseB) {
    const Mat3 toA = poseA.rotation.transpose();
    return {PlacedShape{&a, &fa, Mat3::Identity(), Vec3::Zero()},
            PlacedShape{&b, &fb, toA * poseB.rotation, toA * (poseB.position - poseA.position)}};
}

ShapeFeatures featuresOf(const Polytope& p) {
    ShapeFeatures f;
    prepare(p, f);
    return f;
}

ShapeFeatures withoutBox(ShapeFeatures f) {
    f.box.valid = false;
    return f;
}

TEST(BoxFeatures, BoxesAreRecognisedWhereverTheirFrameIsAndOtherShapesAreNot) {
    std::mt19937 rng(7);
    EXPECT_TRUE(featuresOf(box(Vec3(1, 2, 3))).box.valid);
    EXPECT_TRUE(featuresOf(box(Vec3(1, 2, 3))).box.aligned);
    EXPECT_TRUE(featuresOf(makeBox(Vec3(0, 1, 2), Vec3(3, 3, 3))).box.aligned);
    for (int k = 0; k < 50; ++k) {
        const Polytope p = offsetBox(rng);
        const ShapeFeatures f = featuresOf(p);
        ASSERT_TRUE(f.box.valid);
        EXPECT_NEAR(f.box.axes.determinant(), 1, 1e-12);
        // Every vertex sits on a corner: centre ± half along each axis.
        for (const Vec3& v : p.vertices) {
            const Vec3 local = f.box.axes.transpose() * (v - f.box.centre);
            EXPECT_LT((local.cwiseAbs() - f.box.half).cwiseAbs().maxCoeff(), 1e-12);
        }
    }
    EXPECT_FALSE(featuresOf(makeOctahedron(Vec3(-1, -1, -1), Vec3(1, 1, 1))).box.valid);
    EXPECT_FALSE(featuresOf(makeCylinder(Vec3(-1, -1, -1), Vec3(1, 1, 1), 6)).box.valid);
    // Eight corners and six four-sided faces, but sheared: not a box.
    Polytope sheared = box(Vec3(1, 1, 1));
    for (Vec3& v : sheared.vertices) {
        v.x() += 0.3 * v.z();
    }
    sheared = makePolytope(sheared.vertices, {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {3, 2, 1, 0},
                                              {4, 5, 6, 7}});
    EXPECT_FALSE(featuresOf(sheared).box.valid);
}

// Random box pairs from deep overlap to beyond the margin, their centres up to 6 apart.
struct BoxPair {
    Polytope a, b;
    RigidPose poseA, poseB;
};

// Each box made around the origin (square to its frame) or turned and shifted in it, at random.
Polytope someBox(std::mt19937& rng) {
    return std::uniform_int_distribution<int>(0, 1)(rng) == 1 ? box(randomVector(rng, 0.2, 3)) : offsetBox(rng);
}

BoxPair randomBoxPair(std::mt19937& rng) {
    BoxPair p{someBox(rng), someBox(rng), pose(randomVector(rng, -50, 50), randomRotation(rng)), {}};
    p.poseB = pose(p.poseA.position + randomVector(rng, -3.5, 3.5), randomRotation(rng));
    return p;
}

TEST(BoxAxis, MatchesThePolytopeSearchOnRandomPoses) {
    std::mt19937 rng(11);
    constexpr Real kMargin = 0.5;
    int found = 0, edgeAxes = 0;
    for (int k = 0; k < 20000; ++k) {
        const BoxPair pair = randomBoxPair(rng);
        const ShapeFeatures fa = featuresOf(pair.a), fb = featuresOf(pair.b);
        const auto [a, b] = place(pair.a, fa, pair.poseA, pair.b, fb, pair.poseB);
        const std::optional<SeparatingAxis> fast = findBestBoxAxis(a, b, kMargin);
        const std::optional<SeparatingAxis> slow = findBestPolytopeAxis(a, b, kMargin);
        ASSERT_EQ(fast.has_value(), slow.has_value()) << "pair " << k;
        if (!fast) {
            continue;
        }
        ++found;
        edgeAxes += slow->kind == AxisKind::edges;
        ASSERT_EQ(fast->kind, slow->kind) << "pair " << k;
        EXPECT_EQ(fast->featureA, slow->featureA) << "pair " << k;
        EXPECT_EQ(fast->featureB, slow->featureB) << "pair " << k;
        EXPECT_LT((fast->normal - slow->normal).norm(), 1e-12) << "pair " << k;
        EXPECT_NEAR(fast->separation, slow->separation, 1e-12) << "pair " << k;
    }
    // The poses cover both outcomes and both kinds of axis.
    EXPECT_GT(found, 4000);
    EXPECT_LT(found, 16000);
    EXPECT_GT(edgeAxes, 500);
}

TEST(BoxAxis, BoxesSquareToEachOtherMatchThePolytopeSearch) {
    // Exact zeros in the rotation between the boxes make edge axes degenerate (parallel to a face
    // normal): they must not outrank the faces.
    std::mt19937 rng(12);
    const std::array<Mat3, 3> turns{Mat3::Identity(), test::rotation(Vec3::UnitZ(), 90),
                                    test::rotation(Vec3::UnitX(), 90) * test::rotation(Vec3::UnitZ(), 90)};
    for (int k = 0; k < 3000; ++k) {
        const Polytope pa = box(randomVector(rng, 0.2, 3)), pb = box(randomVector(rng, 0.2, 3));
        const ShapeFeatures fa = featuresOf(pa), fb = featuresOf(pb);
        const Mat3 turnB = k % 2 ? test::rotation(Vec3::UnitZ(), 30) * turns[k % 3] : turns[k % 3];
        const auto [a, b] = place(pa, fa, pose(Vec3::Zero()), pb, fb, pose(randomVector(rng, -3.5, 3.5), turnB));
        const std::optional<SeparatingAxis> fast = findBestBoxAxis(a, b, 0.5);
        const std::optional<SeparatingAxis> slow = findBestPolytopeAxis(a, b, 0.5);
        ASSERT_EQ(fast.has_value(), slow.has_value()) << "pair " << k;
        if (fast) {
            ASSERT_EQ(fast->kind, slow->kind) << "pair " << k;
            EXPECT_LT((fast->normal - slow->normal).norm(), 1e-12) << "pair " << k;
            EXPECT_NEAR(fast->separation, slow->separation, 1e-12) << "pair " << k;
        }
    }
}

::testing::AssertionResult sameManifold(const Manifold& x, const Manifold& y, Real tolerance) {
    if (x.count != y.count) {
        return ::testing::AssertionFailure() << "counts " << x.count << " and " << y.count;
    }
    if (x.count > 0 && (x.normal - y.normal).norm() > tolerance) {
        return ::testing::AssertionFailure() << "normals " << x.normal.transpose() << " and " << y.normal.transpose();
    }
    for (int i = 0; i < x.count; ++i) {
        const ManifoldPoint &p = x.points[i], &q = y.points[i];
        if (p.id != q.id || (p.point - q.point).norm() > tolerance * (1 + q.point.norm()) ||
            std::abs(p.depth - q.depth) > tolerance) {
            return ::testing::AssertionFailure() << "point " << i << ": " << p.point.transpose() << " depth " << p.depth
                                                 << " id " << p.id << " and " << q.point.transpose() << " depth "
                                                 << q.depth << " id " << q.id;
        }
    }
    return ::testing::AssertionSuccess();
}

TEST(BoxAxis, BoxManifoldsMatchThePolytopePathOnRandomPoses) {
    std::mt19937 rng(13);
    int touching = 0;
    for (int k = 0; k < 20000; ++k) {
        const BoxPair pair = randomBoxPair(rng);
        const ShapeFeatures fa = featuresOf(pair.a), fb = featuresOf(pair.b);
        const ShapeFeatures ga = withoutBox(fa), gb = withoutBox(fb);
        const auto [a, b] = place(pair.a, fa, pair.poseA, pair.b, fb, pair.poseB);
        const auto [a0, b0] = place(pair.a, ga, pair.poseA, pair.b, gb, pair.poseB);
        const Manifold fast = collidePlaced(a, b, pair.poseA, pair.poseB, 0.5);
        const Manifold slow = collidePlaced(a0, b0, pair.poseA, pair.poseB, 0.5);
        ASSERT_TRUE(sameManifold(fast, slow, 1e-9)) << "pair " << k;
        touching += !slow.empty();
    }
    EXPECT_GT(touching, 4000);
}

// The distance of two disjoint convex polytopes in the world, by brute force: the least over
// vertex–face and edge–edge pairs.
Real pointSegment(const Vec3& p, const Vec3& s0, const Vec3& s1) {
    const Vec3 d = s1 - s0;
    const Real t = std::clamp((p - s0).dot(d) / d.squaredNorm(), Real(0), Real(1));
    return (s0 + t * d - p).norm();
}

Real segmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    // Ternary search along one segment of the exact point–segment distance, which is convex
    // along it.
    Real lo = 0, hi = 1;
    auto at = [&](Real s) { return pointSegment(p0 + s * (p1 - p0), q0, q1); };
    for (int it = 0; it < 100; ++it) {
        const Real m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (at(m1) < at(m2)) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    return at((lo + hi) / 2);
}

Real pointPolytope(const Vec3& p, const Polytope& shape) {
    Real best = std::numeric_limits<Real>::infinity();
    for (const Face& f : shape.faces) {
        bool over = true;
        for (size_t i = 0; i < f.loop.size(); ++i) {
            const Vec3& r0 = shape.vertices[f.loop[i]];
            const Vec3& r1 = shape.vertices[f.loop[(i + 1) % f.loop.size()]];
            over = over && (r1 - r0).cross(f.normal).dot(p - r0) <= 0;
        }
        if (over) {
            best = std::min(best, std::abs(f.normal.dot(p) - f.offset));
        }
    }
    for (const auto& e : shape.edges) {
        best = std::min(best, pointSegment(p, shape.vertices[e[0]], shape.vertices[e[1]]));
    }
    return best;
}

Real bruteForceDistance(const Polytope& a, const Polytope& b) {
    Real best = std::numeric_limits<Real>::infinity();
    for (const Vec3& v : a.vertices) {
        best = std::min(best, pointPolytope(v, b));
    }
    for (const Vec3& v : b.vertices) {
        best = std::min(best, pointPolytope(v, a));
    }
    for (const auto& ea : a.edges) {
        for (const auto& eb : b.edges) {
            best = std::min(best, segmentSegment(a.vertices[ea[0]], a.vertices[ea[1]], b.vertices[eb[0]],
                                                 b.vertices[eb[1]]));
        }
    }
    return best;
}

TEST(LibccdSkip, WhereTheAxisIsTheDistanceLibccdHasNothingToAdd) {
    std::mt19937 rng(17);
    const std::array<Polytope, 3> others{box(Vec3(1, 0.5, 2)), makeOctahedron(Vec3(-1, -1, -1), Vec3(1, 1, 1)),
                                         makeCylinder(Vec3(-0.5, -0.5, -1), Vec3(0.5, 0.5, 1), 8)};
    constexpr Real kMargin = 1;
    int skipped = 0, asked = 0;
    for (int k = 0; k < 6000; ++k) {
        const Polytope pa = offsetBox(rng);
        const Polytope& pb = others[k % 3];
        const ShapeFeatures fa = featuresOf(pa), fb = featuresOf(pb);
        const RigidPose poseA = pose(randomVector(rng, -20, 20), randomRotation(rng));
        const RigidPose poseB = pose(poseA.position + randomVector(rng, -4, 4), randomRotation(rng));
        const auto [a, b] = place(pa, fa, poseA, pb, fb, poseB);
        const std::optional<SeparatingAxis> axis = findBestAxis(a, b, kMargin);
        if (!axis || axis->separation <= 0) {
            continue;
        }
        ++asked;
        if (!separationIsDistance(a, b, *axis)) {
            continue;
        }
        ++skipped;
        const Real distance = bruteForceDistance(test::placed(pa, poseA), test::placed(pb, poseB));
        EXPECT_NEAR(distance, axis->separation, 1e-9) << "pair " << k;
        // What libccd would have said: within the margin, along no better direction.
        const CcdResult ccd = ccdPenetration(a, b, kMargin + 1e-6);
        EXPECT_TRUE(ccd.intersecting) << "pair " << k;
        EXPECT_LE(separationAlong(a, b, ccd.normal), axis->separation + kLengthTolerance) << "pair " << k;
    }
    EXPECT_GT(skipped, 300);
    EXPECT_LT(skipped, asked);  // vertex–edge and vertex–vertex closest pairs still go to libccd
}

}  // namespace
}  // namespace af
