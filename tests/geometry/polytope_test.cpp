// Topology and planes of every shape (closed, consistently oriented, convex, outward normals),
// the support mapping against brute force, and rigid transforms.

#include "geometry_test_util.h"

#include <limits>
#include <map>
#include <random>
#include <utility>

namespace af {
namespace {

using test::nearRelM;

// Every directed edge used exactly once and its reverse exactly once: a closed, consistently
// oriented 2-manifold. Also Euler's V − E + F = 2 and edges matching the faces.
void expectClosedOrientedSurface(const std::string& name, const Polytope& p) {
    std::map<std::pair<int, int>, int> directed;
    for (const Face& f : p.faces) {
        for (size_t i = 0; i < f.loop.size(); ++i) {
            ++directed[{f.loop[i], f.loop[(i + 1) % f.loop.size()]}];
        }
    }
    for (const auto& [edge, count] : directed) {
        EXPECT_EQ(count, 1) << name << " edge " << edge.first << "→" << edge.second;
        const auto reverse = directed.find({edge.second, edge.first});
        EXPECT_TRUE(reverse != directed.end() && reverse->second == 1)
            << name << " edge " << edge.first << "→" << edge.second << " has no twin";
    }
    EXPECT_EQ(p.edges.size() * 2, directed.size()) << name;
    EXPECT_EQ(int(p.vertices.size()) - int(p.edges.size()) + int(p.faces.size()), 2) << name;
}

// Unit outward normals: every face's vertices lie on its plane and every vertex lies behind
// every plane; the face loop turns counter-clockwise about its normal.
void expectConvexWithOutwardPlanes(const std::string& name, const Polytope& p) {
    Real size = 0;
    for (const Vec3& v : p.vertices) {
        size = std::max(size, v.cwiseAbs().maxCoeff());
    }
    const Real eps = 1e-13 * std::max(size, Real(1));
    for (size_t fi = 0; fi < p.faces.size(); ++fi) {
        const Face& f = p.faces[fi];
        EXPECT_NEAR(f.normal.norm(), 1, 1e-14) << name << " face " << fi;
        for (int i : f.loop) {
            EXPECT_NEAR(f.normal.dot(p.vertices[i]), f.offset, eps) << name << " face " << fi;
        }
        for (const Vec3& v : p.vertices) {
            EXPECT_LE(f.normal.dot(v), f.offset + eps) << name << " face " << fi;
        }
        const Vec3 a = p.vertices[f.loop[0]], b = p.vertices[f.loop[1]], c = p.vertices[f.loop[2]];
        EXPECT_GT((b - a).cross(c - a).dot(f.normal), 0) << name << " face " << fi;
    }
}

TEST(Polytope, EveryShapeIsAClosedOrientedSurface) {
    for (const test::NamedShape& s : test::sampleShapes()) {
        expectClosedOrientedSurface(s.name, s.polytope);
    }
}

TEST(Polytope, EveryShapeIsConvexWithOutwardUnitNormals) {
    for (const test::NamedShape& s : test::sampleShapes()) {
        expectConvexWithOutwardPlanes(s.name, s.polytope);
    }
}

TEST(Polytope, FaceAndEdgeCountsMatchEachFamily) {
    const Vec3 lo(-1, -2, -3), hi(2, 3, 4);
    struct Count { Polytope p; size_t v, e, f; };
    const Count counts[] = {
        {makeBox(lo, hi), 8, 12, 6},
        {makeOctahedron(lo, hi), 6, 12, 8},
        {makeDodecahedron(lo, hi), 20, 30, 12},
        {makeCylinder(lo, hi, 7), 14, 21, 9},
        {makeCone(lo, hi, 9), 10, 18, 10},
        {makeBone(5, 1), 5, 9, 6},
    };
    for (const Count& c : counts) {
        EXPECT_EQ(c.p.vertices.size(), c.v);
        EXPECT_EQ(c.p.edges.size(), c.e);
        EXPECT_EQ(c.p.faces.size(), c.f);
    }
}

TEST(Polytope, DodecahedronFacesArePentagonsWithEqualEdges) {
    const Polytope p = makeDodecahedron(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    const Real edge = (p.vertices[p.edges[0][0]] - p.vertices[p.edges[0][1]]).norm();
    for (const Face& f : p.faces) {
        EXPECT_EQ(f.loop.size(), 5u);
    }
    for (const auto& e : p.edges) {
        EXPECT_NEAR((p.vertices[e[0]] - p.vertices[e[1]]).norm(), edge, 1e-14);
    }
}

TEST(Polytope, BoxPlanesAreTheBoundsPlanes) {
    const Polytope p = makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6));
    std::vector<std::pair<Vec3, Real>> expected = {
        {{1, 0, 0}, 4}, {{-1, 0, 0}, 1}, {{0, 1, 0}, 5}, {{0, -1, 0}, 2}, {{0, 0, 1}, 6}, {{0, 0, -1}, 3}};
    for (const auto& [n, d] : expected) {
        int matches = 0;
        for (const Face& f : p.faces) {
            if ((f.normal - n).norm() < 1e-15 && std::abs(f.offset - d) < 1e-15) {
                ++matches;
            }
        }
        EXPECT_EQ(matches, 1) << n.transpose();
    }
}

TEST(Polytope, SupportMatchesBruteForceOverRandomDirections) {
    std::mt19937 rng(20240611);
    std::normal_distribution<Real> gauss(0, 1);
    for (const test::NamedShape& s : test::sampleShapes()) {
        for (int k = 0; k < 200; ++k) {
            const Vec3 dir(gauss(rng), gauss(rng), gauss(rng));
            Real best = -std::numeric_limits<Real>::infinity();
            int bestIndex = -1;
            for (int i = 0; i < int(s.polytope.vertices.size()); ++i) {
                const Real d = s.polytope.vertices[i].dot(dir);
                if (d > best) {
                    best = d;
                    bestIndex = i;
                }
            }
            EXPECT_EQ(support(s.polytope, dir).dot(dir), best) << s.name;
            EXPECT_EQ(supportIndex(s.polytope, dir), bestIndex) << s.name;
        }
    }
}

TEST(Polytope, SupportAlongAxesOfABoxGivesTheCornerInThatOctant) {
    const Polytope p = makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6));
    EXPECT_TRUE(nearRelM(support(p, Vec3(1, 1, 1)), Vec3(4, 5, 6), 0));
    EXPECT_TRUE(nearRelM(support(p, Vec3(-1, 2, -0.1)), Vec3(-1, 5, -3), 0));
    EXPECT_TRUE(nearRelM(support(p, Vec3(-3, -2, 1)), Vec3(-1, -2, 6), 0));
}

TEST(Polytope, SupportTiesGoToTheLowestIndex) {
    const Polytope p = makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    const int i = supportIndex(p, Vec3(0, 0, 1));  // four corners tie
    for (int j = 0; j < i; ++j) {
        EXPECT_LT(p.vertices[j].z(), p.vertices[i].z());
    }
    EXPECT_EQ(supportIndex(p, Vec3::Zero()), 0);
}

TEST(Polytope, RigidTransformMovesVerticesNormalsAndPlanes) {
    const Mat3 r = test::rotationAbout(Vec3(1, -2, 0.5), 1.1);
    const Vec3 t(7, -3, 12);
    for (const test::NamedShape& s : test::sampleShapes()) {
        const Polytope q = transformed(s.polytope, r, t);
        for (size_t i = 0; i < q.vertices.size(); ++i) {
            EXPECT_TRUE(nearRelM(q.vertices[i], Vec3(r * s.polytope.vertices[i] + t), 1e-15, 10));
        }
        expectConvexWithOutwardPlanes(s.name + " moved", q);
        const Vec3 dir(0.3, -0.9, 0.2);
        EXPECT_TRUE(nearRelM(support(q, dir), Vec3(r * support(s.polytope, r.transpose() * dir) + t), 1e-14, 10))
            << s.name;
    }
}

TEST(Polytope, TranslationKeepsNormalsAndShiftsOffsets) {
    const Polytope p = makeOctahedron(Vec3(-1, -2, -3), Vec3(3, 4, 5));
    const Vec3 t(100, -50, 25);
    const Polytope q = translated(p, t);
    for (size_t f = 0; f < p.faces.size(); ++f) {
        EXPECT_TRUE(nearRelM(q.faces[f].normal, p.faces[f].normal, 0));
        EXPECT_NEAR(q.faces[f].offset, p.faces[f].offset + p.faces[f].normal.dot(t), 1e-12);
    }
}

// The ground under a point: the highest top of the shapes whose x–y extent covers it.
TEST(Polytope, HighestTopAtIsTheHighestShapeCoveringThePoint) {
    const std::vector<Polytope> shapes = {makeBox(Vec3(-100, -100, -16), Vec3(100, 100, 0)),
                                          makeBox(Vec3(0, 0, 0), Vec3(20, 20, 8)),
                                          makeBox(Vec3(50, 50, 30), Vec3(60, 60, 40))};
    EXPECT_EQ(highestTopAt(shapes, -5, -5), Real(0));
    EXPECT_EQ(highestTopAt(shapes, 10, 10), Real(8));
    EXPECT_EQ(highestTopAt(shapes, 20, 20), Real(8)) << "an edge covers";
    EXPECT_EQ(highestTopAt(shapes, 55, 55), Real(40));
    EXPECT_FALSE(highestTopAt(shapes, 150, 0).has_value());
    EXPECT_FALSE(highestTopAt({}, 0, 0).has_value());
}

}  // namespace
}  // namespace af
