// The shortcuts of the plane contact against the paths they stand in for, on many random cases:
// smallPlaneContact, which the collision world uses for boxes on planes, against collideWithPlane;
// reduceToFour's shortcut for four clearly distinct points or fewer against reduceByArea.

#include "collision/manifold_reduction.h"
#include "collision/plane_contact.h"

#include "narrowphase_test_util.h"

#include <Eigen/Geometry>

#include <random>

namespace af {
namespace {

using namespace collision_detail;
using test::box;
using test::randomRotation;
using test::randomVector;

// Every field, bit for bit, the points past `count` included.
::testing::AssertionResult identical(const Manifold& x, const Manifold& y) {
    if (x.count != y.count || x.normal != y.normal) {
        return ::testing::AssertionFailure() << "count " << x.count << " vs " << y.count << ", normal "
                                             << x.normal.transpose() << " vs " << y.normal.transpose();
    }
    for (int i = 0; i < Manifold::kMaxPoints; ++i) {
        const ManifoldPoint &p = x.points[i], &q = y.points[i];
        if (p.point != q.point || p.depth != q.depth || p.id != q.id) {
            return ::testing::AssertionFailure() << "point " << i << ": " << p.point.transpose() << " depth "
                                                 << p.depth << " id " << p.id << " vs " << q.point.transpose()
                                                 << " depth " << q.depth << " id " << q.id;
        }
    }
    return ::testing::AssertionSuccess();
}

// Boxes, some turned and shifted in their body frame, some so thin that their corners nearly meet
// across a plane they lie on; and smaller shapes that are not boxes.
Polytope smallShape(std::mt19937& rng, int k) {
    const Vec3 half = randomVector(rng, 0.02, 2);
    switch (k % 5) {
    case 4:
        return box(Vec3(half.x(), half.y(), k % 3 == 0 ? 1e-7 : k % 3 == 1 ? 4e-6 : 1e-3));
    case 0:
        return box(half);
    case 1:
        return transformed(box(half), randomRotation(rng), randomVector(rng, -1, 1));
    case 2:
        return makeOctahedron(-half, half);
    default:
        return makePolytope({Vec3(0, 0, 0), Vec3(half.x(), 0, 0), Vec3(0, half.y(), 0), Vec3(0, 0, half.z())},
                            {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
    }
}

TEST(SmallPlaneContact, EqualsCollideWithPlaneBitForBitOnRandomPoses) {
    std::mt19937 rng(41);
    std::uniform_real_distribution<Real> unit(0, 1);
    int withPoints = 0, fourPoints = 0;
    Manifold out;
    for (int k = 0; k < 20000; ++k) {
        const Polytope shape = smallShape(rng, k);
        ASSERT_LE(int(shape.vertices.size()), kSmallPolytope);
        const ConvexShape prepared(shape);
        const Plane plane{k % 3 == 0 ? Vec3::UnitZ() : randomVector(rng, -1, 1).normalized(), 4 * unit(rng) - 2};
        // Half the poses lie nearly flat on the plane, as a resting body does: a face's corners
        // then tie for deepest or nearly so.
        Mat3 rotation = randomRotation(rng);
        if (k % 2 == 0) {
            const Mat3 onFace = Eigen::Quaternion<Real>::FromTwoVectors(Vec3::UnitZ(), -plane.normal).toRotationMatrix();
            const Mat3 tilt = Eigen::AngleAxis<Real>(1e-3 * unit(rng) * (k % 4 == 0 ? 0 : 1),
                                                     randomVector(rng, -1, 1).normalized())
                                  .toRotationMatrix();
            rotation = tilt * onFace;
        }
        const Vec3 along = plane.offset * plane.normal;
        const RigidPose pose{along + randomVector(rng, -3, 3) - randomVector(rng, -3, 3).dot(plane.normal) * plane.normal +
                                 (4 * unit(rng) - 2) * plane.normal,
                             rotation};
        const Real margin = k % 5 == 0 ? 0 : k % 7 == 0 ? -0.1 : 2 * unit(rng);
        const Manifold expected = collideWithPlane(shape, pose, plane, margin);
        out.count = 3;  // what a query before left: all of it must be overwritten
        out.points[3].id = 99;
        EXPECT_EQ(smallPlaneContact(prepared, pose, plane, margin, out), !expected.empty()) << "case " << k;
        EXPECT_TRUE(identical(out, expected)) << "case " << k;
        withPoints += !expected.empty();
        fourPoints += expected.count == 4;
    }
    EXPECT_GT(withPoints, 5000);  // enough contacts, and enough faces flat on the plane
    EXPECT_GT(fourPoints, 2000);
}

// Up to eight candidates; some pairs of them closer across the plane than the reduction's 1e-6
// (one the other moved along the normal, or across it by less than 1e-6, or by just more), some
// far from the origin; depths often tied.
std::vector<Candidate> randomCandidates(std::mt19937& rng, const Vec3& normal, int k) {
    std::uniform_real_distribution<Real> unit(0, 1);
    const int n = 1 + k % 8;
    const Real scale = k % 11 == 0 ? 1e5 : 1;
    const Vec3 origin = k % 13 == 0 ? randomVector(rng, -1e7, 1e7) : Vec3::Zero();
    std::vector<Candidate> c;
    for (int i = 0; i < n; ++i) {
        Vec3 p = origin + scale * randomVector(rng, -1, 1);
        if (i > 0 && unit(rng) < 0.4) {
            const Vec3 across = randomVector(rng, -1, 1).cross(normal).normalized();
            p = c[std::size_t(rng() % i)].point + (unit(rng) - 0.5) * normal + 3e-6 * unit(rng) * across;
        }
        const Real depth = unit(rng) < 0.3 ? 0.25 : unit(rng);
        c.push_back({p, depth, std::uint32_t(i)});
    }
    return c;
}

TEST(ReduceToFour, ShortcutPicksWhatTheAreaReductionPicks) {
    std::mt19937 rng(43);
    int shortcutCases = 0, mergedCases = 0;
    for (int k = 0; k < 100000; ++k) {
        const Vec3 normal = randomVector(rng, -1, 1).normalized();
        const std::vector<Candidate> c = randomCandidates(rng, normal, k);
        std::array<int, 4> fast{}, general{};
        const int n = reduceToFour(c, normal, fast);
        ASSERT_EQ(n, reduceByArea(c, normal, general)) << "case " << k;
        for (int i = 0; i < n; ++i) {
            EXPECT_EQ(fast[i], general[i]) << "case " << k << " pick " << i;
        }
        shortcutCases += c.size() <= 4 && n == int(c.size());
        mergedCases += c.size() <= 4 && n < int(c.size());
    }
    EXPECT_GT(shortcutCases, 10000);  // both outcomes of four points or fewer are well represented
    EXPECT_GT(mergedCases, 5000);
}

}  // namespace
}  // namespace af
