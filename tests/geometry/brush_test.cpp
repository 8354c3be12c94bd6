// Brush solids from half-spaces: hand-computed corners of boxes and a wedge, rotated boxes with
// exact and float-rounded planes, redundant planes dropped, open/empty/bad brushes reported,
// and every worldspawn brush of maps/default.map closed and valid.

#include "af/geometry/brush.h"
#include "af/geometry/mass_properties.h"
#include "geometry_test_util.h"

#include <map>
#include <random>
#include <utility>

namespace af {
namespace {

using test::sameVertexSet;

// Planes of the axis-aligned box [lo, hi], in the order bottom, top, −y, +x, +y, −x.
std::vector<BrushPlane> boxPlanes(const Vec3& lo, const Vec3& hi) {
    return {{-Vec3::UnitZ(), lo.z()}, {Vec3::UnitZ(), -hi.z()}, {-Vec3::UnitY(), lo.y()},
            {Vec3::UnitX(), -hi.x()}, {Vec3::UnitY(), -hi.y()}, {-Vec3::UnitX(), lo.x()}};
}

std::vector<Vec3> boxCorners(const Vec3& lo, const Vec3& hi) {
    std::vector<Vec3> out;
    for (int i = 0; i < 8; ++i)
        out.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    return out;
}

// A closed, consistently oriented surface (every directed edge once, with its twin; Euler
// V − E + F = 2), every vertex within `tol` behind every face plane, and each face normal within
// `normalTol` of the plane it came from (float-rounded planes tilt the faces a little).
void expectValidSolid(const BrushPolytope& b, const std::vector<BrushPlane>& planes, Real tol,
                      Real normalTol = 1e-9) {
    ASSERT_TRUE(b.ok()) << b.message;
    const Polytope& p = *b.polytope;
    std::map<std::pair<int, int>, int> directed;
    for (const Face& f : p.faces)
        for (std::size_t i = 0; i < f.loop.size(); ++i) ++directed[{f.loop[i], f.loop[(i + 1) % f.loop.size()]}];
    for (const auto& [edge, count] : directed) {
        EXPECT_EQ(count, 1);
        EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << edge.first << "→" << edge.second;
    }
    EXPECT_EQ(int(p.vertices.size()) - int(p.edges.size()) + int(p.faces.size()), 2);
    ASSERT_EQ(b.faceSides.size(), p.faces.size());
    for (std::size_t fi = 0; fi < p.faces.size(); ++fi) {
        const BrushPlane& plane = planes[b.faceSides[fi]];
        EXPECT_TRUE(test::nearRelM(p.faces[fi].normal, plane.normal.normalized(), normalTol)) << "face " << fi;
        for (const Vec3& v : p.vertices) EXPECT_LE(p.faces[fi].normal.dot(v), p.faces[fi].offset + tol);
    }
    EXPECT_GT(volumeProperties(p).volume, 0);
}

TEST(Brush, AxisAlignedBoxHasItsEightCornersAndSixFaces) {
    const Vec3 lo(64, -64, 0), hi(192, 64, 32);
    const std::vector<BrushPlane> planes = boxPlanes(lo, hi);
    const BrushPolytope b = polytopeFromPlanes(planes);
    expectValidSolid(b, planes, 1e-9);
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices, boxCorners(lo, hi), 1e-12));
    EXPECT_EQ(b.faceSides, (std::vector<int>{0, 1, 2, 3, 4, 5}));
    EXPECT_TRUE(b.droppedSides.empty());
    EXPECT_NEAR(volumeProperties(*b.polytope).volume, 128.0 * 128 * 32, 1e-6);
    for (const Face& f : b.polytope->faces) EXPECT_EQ(f.loop.size(), 4u);
}

// A ramp: the slope rises from z = 0 at x = 64 to z = 32 at x = 192, over y ∈ [128, 192].
// Its plane through (64, y, 0) and (192, y, 32) is −x + 4z + 64 = 0, written unnormalised.
TEST(Brush, WedgeHasSixCornersTwoTrianglesAndASlope) {
    const std::vector<BrushPlane> planes = {{-Vec3::UnitZ(), 0},
                                            {Vec3::UnitX(), -192},
                                            {-Vec3::UnitY(), 128},
                                            {Vec3::UnitY(), -192},
                                            {Vec3(-1, 0, 4), 64}};
    const BrushPolytope b = polytopeFromPlanes(planes);
    expectValidSolid(b, planes, 1e-9);
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices,
                              {Vec3(64, 128, 0), Vec3(64, 192, 0), Vec3(192, 128, 0), Vec3(192, 192, 0),
                               Vec3(192, 128, 32), Vec3(192, 192, 32)},
                              1e-12));
    std::vector<std::size_t> loopSizes;
    for (const Face& f : b.polytope->faces) loopSizes.push_back(f.loop.size());
    EXPECT_EQ(loopSizes, (std::vector<std::size_t>{4, 4, 3, 3, 4}));  // in side order
    EXPECT_NEAR(volumeProperties(*b.polytope).volume, 0.5 * 128 * 32 * 64, 1e-6);
    EXPECT_TRUE(test::nearRelM(b.polytope->faces[4].normal, Vec3(-1, 0, 4) / std::sqrt(17.0), 1e-15));
}

struct RotatedBox {
    Vec3 centre, half;
    Mat3 rotation;
    std::vector<BrushPlane> planes;
    std::vector<Vec3> corners;
};

RotatedBox rotatedBox() {
    RotatedBox box{Vec3(300, -40, 75), Vec3(48, 16, 24), test::rotationAbout(Vec3(1, 2, 3), 0.7), {}, {}};
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign : {-1, 1}) {
            const Vec3 n = sign * box.rotation.col(axis);
            box.planes.push_back({n, -n.dot(box.centre) - box.half[axis]});
        }
    }
    for (int i = 0; i < 8; ++i) {
        const Vec3 local((i & 1 ? 1 : -1) * box.half.x(), (i & 2 ? 1 : -1) * box.half.y(), (i & 4 ? 1 : -1) * box.half.z());
        box.corners.push_back(box.centre + box.rotation * local);
    }
    return box;
}

TEST(Brush, RotatedBoxHasTheRotatedCorners) {
    const RotatedBox box = rotatedBox();
    const BrushPolytope b = polytopeFromPlanes(box.planes);
    expectValidSolid(b, box.planes, 1e-9);
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices, box.corners, 1e-10));
    EXPECT_NEAR(volumeProperties(*b.polytope).volume, 8 * box.half.prod(), 1e-6);
}

// Planes read from a file are float-rounded: the corners move by about 1e-5 and still merge.
TEST(Brush, RotatedBoxFromFloatRoundedPlanesStillCloses) {
    const RotatedBox box = rotatedBox();
    std::vector<BrushPlane> rounded;
    for (const BrushPlane& p : box.planes)
        rounded.push_back({p.normal.cast<float>().cast<Real>(), Real(float(p.d))});
    const BrushPolytope b = polytopeFromPlanes(rounded);
    expectValidSolid(b, rounded, 1e-3, 1e-5);
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices, box.corners, 1e-3));
    EXPECT_TRUE(b.droppedSides.empty());
}

// Four float-rounded side planes far from the origin meet at the apex only up to rounding; the
// corners they give merge into one.
TEST(Brush, FloatRoundedPyramidFarFromTheOriginHasOneApex) {
    const Vec3 c(20000.5, -15000.25, 3000), apex = c + Vec3(0, 0, 64);
    std::vector<BrushPlane> planes = {{-Vec3::UnitZ(), c.z()}};
    const Vec3 base[4] = {c + Vec3(-32, -32, 0), c + Vec3(32, -32, 0), c + Vec3(32, 32, 0), c + Vec3(-32, 32, 0)};
    for (int i = 0; i < 4; ++i) {
        const Vec3 n = (base[(i + 1) % 4] - base[i]).cross(apex - base[i]).normalized();
        planes.push_back({n.cast<float>().cast<Real>(), Real(float(-n.dot(apex)))});
    }
    planes[0].d = Real(float(planes[0].d));
    const BrushPolytope b = polytopeFromPlanes(planes);
    expectValidSolid(b, planes, 0.05, 1e-4);  // d rounded by ~1e-3 over 64-unit faces
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices, {base[0], base[1], base[2], base[3], apex}, 0.05));
    EXPECT_EQ(b.polytope->faces.size(), 5u);
}

// Boxes of 1 to 100 units, rotated at random, cut by a random slanted plane and float-rounded,
// up to 100000 units from the origin: every one builds (slivers smaller than the default
// tolerance are built with a tighter one).
TEST(Brush, RandomCutBoxesFarFromTheOriginAllBuild) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-1, 1);
    for (Real far : {0.0, 1e3, 1e5}) {
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 centre = far * Vec3(u(rng), u(rng), u(rng));
            const Vec3 half = Vec3::Constant(1) + 50 * (Vec3(u(rng), u(rng), u(rng)) + Vec3::Ones());
            const Mat3 r = test::rotationAbout(Vec3(u(rng), u(rng), u(rng)), 3 * u(rng));
            std::vector<BrushPlane> planes;
            auto add = [&](const Vec3& n, Real d) { planes.push_back({n.cast<float>().cast<Real>(), Real(float(d))}); };
            for (int axis = 0; axis < 3; ++axis)
                for (int sign : {-1, 1}) add(sign * r.col(axis), -sign * r.col(axis).dot(centre) - half[axis]);
            const Vec3 cut = (r.col(0) + u(rng) * r.col(1) + u(rng) * r.col(2)).normalized();
            add(cut, -cut.dot(centre) - 0.5 * half.x());
            const BrushPolytope b = polytopeFromPlanes(planes);
            ASSERT_TRUE(b.ok()) << "far " << far << " trial " << trial << ": " << b.message;
            EXPECT_GT(volumeProperties(*b.polytope).volume, 0);
            EXPECT_LT(volumeProperties(*b.polytope).volume, 8 * half.prod() * (1 + 1e-4));
        }
    }
}

TEST(Brush, RedundantPlanesAreDropped) {
    const Vec3 lo(64, -64, 0), hi(192, 64, 32);
    std::vector<BrushPlane> planes = boxPlanes(lo, hi);
    planes.insert(planes.begin() + 2, {Vec3::UnitZ(), -100});                    // 2: outside, z ≤ 100
    planes.push_back({Vec3(1, 0, 1), -(192 + 32)});                              // 7: touches the edge x = 192, z = 32
    planes.push_back({Vec3(1, 1, 1), -(192 + 64 + 32)});                         // 8: touches the corner (192, 64, 32)
    planes.push_back({Vec3(0, 0, 2), -64});                                      // 9: the top again, scaled
    const BrushPolytope b = polytopeFromPlanes(planes);
    expectValidSolid(b, planes, 1e-9);
    EXPECT_TRUE(sameVertexSet(b.polytope->vertices, boxCorners(lo, hi), 1e-12));
    EXPECT_EQ(b.droppedSides, (std::vector<int>{2, 7, 8, 9}));
    EXPECT_EQ(b.faceSides, (std::vector<int>{0, 1, 3, 4, 5, 6}));
}

TEST(Brush, OpenBrushIsAnErrorNamingTheOpenDirection) {
    std::vector<BrushPlane> planes = boxPlanes(Vec3(0, 0, 0), Vec3(10, 10, 10));
    planes.erase(planes.begin() + 1);  // no top
    const BrushPolytope b = polytopeFromPlanes(planes);
    EXPECT_EQ(b.problem, BrushProblem::open);
    EXPECT_FALSE(b.polytope.has_value());
    EXPECT_NE(b.message.find("(0 0 1)"), std::string::npos) << b.message;

    // A slab between two parallel planes and a single half-space are open too.
    EXPECT_EQ(polytopeFromPlanes({{Vec3::UnitZ(), -1}, {-Vec3::UnitZ(), -1}}).problem, BrushProblem::open);
    EXPECT_EQ(polytopeFromPlanes({{Vec3::UnitZ(), 0}}).problem, BrushProblem::open);
    EXPECT_EQ(polytopeFromPlanes({}).problem, BrushProblem::open);
    // A prism: every normal horizontal, so the solid goes on along z.
    EXPECT_EQ(polytopeFromPlanes({{Vec3(1, 0, 0), -1}, {Vec3(-1, 1, 0), -1}, {Vec3(-1, -1, 0), -1}}).problem,
              BrushProblem::open);
}

TEST(Brush, EmptyAndFlatBrushesAreErrors) {
    // Top below bottom: the half-spaces miss each other.
    EXPECT_EQ(polytopeFromPlanes(boxPlanes(Vec3(0, 0, 10), Vec3(10, 10, 0))).problem, BrushProblem::empty);
    // Zero height: a square with no volume.
    const BrushPolytope flat = polytopeFromPlanes(boxPlanes(Vec3(0, 0, 5), Vec3(10, 10, 5)));
    EXPECT_EQ(flat.problem, BrushProblem::empty);
    EXPECT_FALSE(flat.polytope.has_value());
    EXPECT_FALSE(flat.message.empty());
}

TEST(Brush, ZeroOrNonFiniteNormalIsABadPlane) {
    std::vector<BrushPlane> planes = boxPlanes(Vec3(0, 0, 0), Vec3(1, 1, 1));
    planes[3].normal = Vec3::Zero();
    const BrushPolytope b = polytopeFromPlanes(planes);
    EXPECT_EQ(b.problem, BrushProblem::badPlane);
    EXPECT_NE(b.message.find("side 3"), std::string::npos) << b.message;
    planes[3] = {Vec3(std::nan(""), 0, 0), 0};
    EXPECT_EQ(polytopeFromPlanes(planes).problem, BrushProblem::badPlane);
}

TEST(Brush, BrushDef3SidesGiveThePlanes) {
    BrushDef3 brush;
    brush.sides.push_back({{0, 0, 1, -8}, {}, "m", {}});
    const std::vector<BrushPlane> planes = brushPlanes(brush);
    ASSERT_EQ(planes.size(), 1u);
    EXPECT_EQ(planes[0].normal, Vec3(0, 0, 1));
    EXPECT_EQ(planes[0].d, -8);
}

// Every worldspawn brush of our default map is a valid closed solid using all its sides; the
// floor's top is at z = 0 and spans 1024 × 1024.
TEST(Brush, DefaultMapBrushesAreClosedSolids) {
    const MapParseResult r = loadMapFile(std::string(AF_SOURCE_DIR) + "/maps/default.map");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    const MapEntity* world = r.map.worldspawn();
    ASSERT_NE(world, nullptr);
    int brushes = 0;
    for (const MapPrimitive& primitive : world->primitives) {
        const BrushDef3* brush = primitive.brush();
        if (!brush) continue;
        ++brushes;
        const BrushPolytope b = polytopeFromBrush(*brush);
        expectValidSolid(b, brushPlanes(*brush), 1e-3);
        EXPECT_TRUE(b.droppedSides.empty()) << "primitive at line " << primitive.where.line;
        EXPECT_EQ(b.faceSides.size(), brush->sides.size());
    }
    EXPECT_GE(brushes, 3);
    const BrushPolytope floor = polytopeFromBrush(*world->primitives.at(0).brush());
    ASSERT_TRUE(floor.ok());
    EXPECT_TRUE(sameVertexSet(floor.polytope->vertices, boxCorners(Vec3(-512, -512, -16), Vec3(512, 512, 0)), 1e-9));
}

}  // namespace
}  // namespace af
