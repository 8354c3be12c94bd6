// CollisionWorld::findContacts skips queries that cannot find anything (bounding boxes, bounding
// spheres) and takes boxes on planes by its own path: its output must be what querying every allowed
// pair directly gives, on many random scenes. findContactsAgain, which queries only the pairs an
// earlier search found, must give the whole search's answer after moves too small to bring other
// pairs within the margin.

#include "af/collision/collision_world.h"

#include "af/geometry/shapes.h"
#include "narrowphase_test_util.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>

namespace af {
namespace {

using test::randomRotation;
using test::randomVector;

using test::kCorpse;
using test::kHits;

bool sameContact(const BodyContact& x, const BodyContact& y) {
    if (x.bodyA != y.bodyA || x.bodyB != y.bodyB || x.staticShape != y.staticShape ||
        x.manifold.count != y.manifold.count || x.manifold.normal != y.manifold.normal) {
        return false;
    }
    for (int i = 0; i < x.manifold.count; ++i) {
        const ManifoldPoint &p = x.manifold.points[i], &q = y.manifold.points[i];
        if (p.point != q.point || p.depth != q.depth || p.id != q.id) {
            return false;
        }
    }
    return true;
}

TEST(CollisionWorldCulling, ContactsAreThoseOfEveryAllowedPairQueriedDirectly) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<Real> unit(0, 1);
    int contacts = 0, culledPairs = 0;
    for (int scene = 0; scene < 300; ++scene) {
        CollisionWorld world;
        std::vector<Polytope> shapes;
        constexpr int kBodies = 12;
        for (int i = 0; i < kBodies; ++i) {
            // Boxes square to their body frame, boxes turned in it, and one shape that is not a box.
            const Polytope made = makeBox(-randomVector(rng, 0.1, 1), randomVector(rng, 0.1, 1));
            const Polytope shape = i == kBodies - 1 ? makeOctahedron(Vec3(-1, -1, -1), Vec3(1, 1, 1))
                                   : i % 2 == 0     ? made
                                                    : transformed(made, randomRotation(rng), randomVector(rng, -0.3, 0.3));
            shapes.push_back(shape);
            world.addBody(shape, {i % 2, true, kCorpse, kHits, true});
        }
        world.excludePair(0, 1);
        const int floor = world.addPlane(Plane{Vec3(0.1, 0, 1).normalized(), 0.2});
        const int brush = world.addStatic(makeBox(Vec3(2, -4, -1), Vec3(4, 4, 0.5)));

        std::vector<RigidPose> poses;
        std::vector<Vec3> moves;
        std::vector<Real> reach;
        std::vector<std::uint8_t> awake;
        for (int i = 0; i < kBodies; ++i) {
            poses.push_back({randomVector(rng, -3, 3) + Vec3(0, 0, 2), randomRotation(rng)});
            moves.push_back(randomVector(rng, -0.3, 0.3));
            reach.push_back(0.2 * unit(rng));
            awake.push_back(unit(rng) < 0.8);
        }
        const Real margin = 0.1;
        std::vector<BodyContact> found;
        world.findContacts(poses, moves, reach, margin, awake, found);

        std::vector<BodyContact> expected;
        BodyContact c;
        for (int a = 0; a < kBodies; ++a) {
            for (int b = a + 1; b < kBodies; ++b) {
                if ((!awake[a] && !awake[b]) || !world.mayCollide(a, b)) {
                    continue;
                }
                const Real pairMargin = margin + reach[a] + reach[b] + (moves[a] - moves[b]).norm();
                c = {a, b, -1, collide(shapes[a], poses[a], shapes[b], poses[b], pairMargin)};
                if (!c.manifold.empty()) {
                    expected.push_back(c);
                }
            }
        }
        for (int a = 0; a < kBodies; ++a) {
            if (!awake[a]) {
                continue;
            }
            const Real staticMargin = margin + reach[a] + moves[a].norm();
            c = {a, kStaticWorld, floor,
                 collideWithPlane(shapes[a], poses[a], Plane{Vec3(0.1, 0, 1).normalized(), 0.2}, staticMargin)};
            if (!c.manifold.empty()) {
                expected.push_back(c);
            }
            c = {a, kStaticWorld, brush,
                 collide(shapes[a], poses[a], makeBox(Vec3(2, -4, -1), Vec3(4, 4, 0.5)), RigidPose{}, staticMargin)};
            if (!c.manifold.empty()) {
                expected.push_back(c);
            }
        }
        ASSERT_EQ(found.size(), expected.size()) << "scene " << scene;
        for (size_t k = 0; k < found.size(); ++k) {
            EXPECT_TRUE(sameContact(found[k], expected[k])) << "scene " << scene << " contact " << k;
        }
        contacts += int(found.size());
        culledPairs += kBodies * (kBodies - 1) / 2 - int(found.size());
    }
    EXPECT_GT(contacts, 1000);  // the scenes are crowded enough to test something
    EXPECT_GT(culledPairs, 1000);
}

// Bodies moved by less than a quarter of the margin of a search (centre plus turn of the farthest
// vertex): querying again only the pairs it found, at margin 0, gives the whole search's answer.
TEST(CollisionWorldCulling, QueryingFoundPairsAgainAfterSmallMovesEqualsAWholeSearch) {
    std::mt19937 rng(29);
    std::uniform_real_distribution<Real> unit(0, 1);
    int kept = 0, dropped = 0;
    for (int scene = 0; scene < 300; ++scene) {
        CollisionWorld world;
        constexpr int kBodies = 12;
        std::vector<Real> radius;
        for (int i = 0; i < kBodies; ++i) {
            const Polytope made = makeBox(-randomVector(rng, 0.1, 1), randomVector(rng, 0.1, 1));
            const Polytope shape = i == kBodies - 1 ? makeOctahedron(Vec3(-1, -1, -1), Vec3(1, 1, 1))
                                   : i % 2 == 0     ? made
                                                    : transformed(made, randomRotation(rng), randomVector(rng, -0.3, 0.3));
            Real r = 0;
            for (const Vec3& v : shape.vertices) r = std::max(r, v.norm());
            radius.push_back(r);
            world.addBody(shape, {i % 2, true, kCorpse, kHits, true});
        }
        world.excludePair(0, 1);
        world.addPlane(Plane{Vec3(0.1, 0, 1).normalized(), 0.2});
        world.addStatic(makeBox(Vec3(2, -4, -1), Vec3(4, 4, 0.5)));

        std::vector<RigidPose> poses, moved;
        std::vector<std::uint8_t> awake;
        // No moves or reach, so that the pairs just beyond the margin are those a larger move would bring in.
        const std::vector<Vec3> still(kBodies, Vec3::Zero());
        const std::vector<Real> none(kBodies, 0);
        const Real margin = 0.1;
        for (int i = 0; i < kBodies; ++i) {
            poses.push_back({randomVector(rng, -2.5, 2.5) + Vec3(0, 0, 2), randomRotation(rng)});
            awake.push_back(unit(rng) < 0.8);
            // A move and a turn sharing a quarter of the margin (the turn by angle · radius).
            const Real share = unit(rng) * 0.24 * margin;
            const Real angle = (0.24 * margin - share) / radius.back() * unit(rng);
            const Mat3 turn = Eigen::AngleAxis<Real>(angle, randomVector(rng, -1, 1).normalized()).toRotationMatrix();
            moved.push_back(awake.back() ? RigidPose{poses.back().position + share * randomVector(rng, -1, 1).normalized(),
                                                     turn * poses.back().rotation}
                                         : poses.back());
        }
        std::vector<BodyContact> again;
        world.findContacts(poses, still, none, margin, awake, again);
        const std::size_t before = again.size();
        world.findContactsAgain(moved, 0, again);

        std::vector<BodyContact> whole;
        world.findContacts(moved, still, none, 0, awake, whole);
        ASSERT_EQ(again.size(), whole.size()) << "scene " << scene;
        for (size_t k = 0; k < whole.size(); ++k) {
            EXPECT_TRUE(sameContact(again[k], whole[k])) << "scene " << scene << " contact " << k;
        }
        kept += int(whole.size());
        dropped += int(before - whole.size());
    }
    EXPECT_GT(kept, 500);  // pairs that touch after the move, and pairs that came apart
    EXPECT_GT(dropped, 200);
}

}  // namespace
}  // namespace af
