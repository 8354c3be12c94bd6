// The libccd adapter on the cases libccd is known to get wrong (danfis/libccd#25, #17) and on
// touching shapes: it must answer "within the inflation or not" correctly and always give a
// finite direction from B towards A.

#include "collision/ccd_query.h"

#include "narrowphase_test_util.h"

namespace af::collision_detail {
namespace {

using test::box;

// A at `offset` from B, both unrotated; A's frame is the working frame.
struct Pair {
    Pair(const Polytope& pa, const Polytope& pb, const Vec3& offset) {
        prepare(pa, fa);
        prepare(pb, fb);
        a = {&pa, &fa, Mat3::Identity(), Vec3::Zero()};
        b = {&pb, &fb, Mat3::Identity(), -offset};
    }
    Pair(const Pair&) = delete;
    ShapeFeatures fa, fb;
    PlacedShape a, b;
};

TEST(CcdQuery, FaceToFaceBoxesGetAFiniteDirectionOutOfTheOverlap) {
    const Polytope cube = box(Vec3(5, 5, 5));
    for (const Real overlap : {0.0, 1e-9, 0.01, 1.0}) {
        const Pair p(cube, cube, Vec3(0, 0, 10 - overlap));
        const CcdResult r = ccdPenetration(p.a, p.b, 0);
        ASSERT_TRUE(r.intersecting || overlap == 0) << overlap;
        if (r.intersecting) {
            EXPECT_TRUE(r.normal.allFinite()) << overlap;
            EXPECT_NEAR(r.normal.norm(), 1, 1e-12);
            EXPECT_GT(r.normal.z(), 0.7) << overlap << ": A is above B";
        }
    }
}

TEST(CcdQuery, InflationDecidesWhetherSeparatedShapesCount) {
    const Polytope cube = box(Vec3(1, 1, 1));
    const Polytope huge = box(Vec3(500, 500, 10));
    // 0.5 above the huge box's top (libccd#17's sizes): within 0.6, not within 0.4.
    const Pair p(cube, huge, Vec3(123, -77, 11.5));
    EXPECT_TRUE(ccdPenetration(p.a, p.b, 0.6).intersecting);
    EXPECT_FALSE(ccdPenetration(p.a, p.b, 0.4).intersecting);
    const CcdResult r = ccdPenetration(p.a, p.b, 0.6);
    EXPECT_GT(r.normal.z(), 0.7);
    // Corner to corner along the diagonal, √3 apart.
    const Pair q(cube, cube, Vec3(3, 3, 3));
    EXPECT_TRUE(ccdPenetration(q.a, q.b, 1.8).intersecting);
    EXPECT_FALSE(ccdPenetration(q.a, q.b, 1.6).intersecting);
}

}  // namespace
}  // namespace af::collision_detail
