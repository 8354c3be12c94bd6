// The position projection with the tree solver (Island::solvePositionsWithTree) against the dense
// pivoting solve of the same rows: the tree leaves far one-sided rows out of its LCP and puts
// back those its move would violate, so its answer, and the bodies' poses after the step, must
// be the dense one's up to rounding.

#include "af/geometry/shapes.h"
#include "scene_test_util.h"

namespace af {
namespace {

WorldSettings lyingSettings(SolverKind solver) {
    WorldSettings settings;
    settings.comeToRest = false;
    settings.solver = solver;
    return settings;
}

// The humanoid lying face down on the floor, body `nudged` moved by `nudge` before one step:
// its joints open by the nudge, and the projection closes them while its contacts (many of them
// centimetres off the floor, some pushed into it by the move) keep it out of the floor.
World nudgedAndStepped(SolverKind solver, std::size_t nudged, const Vec3& nudge) {
    World world(test::humanoidAt(Vec3(0, 0, 6), 0, 90), lyingSettings(solver));
    world.collision().addPlane(Plane{Vec3::UnitZ(), 0});
    world.bodies()[nudged].position += nudge;
    world.step();
    return world;
}

TEST(Projection, TreeMovesEveryNudgedHumanoidAsTheDenseSolveDoes) {
    const std::size_t bodies = test::humanoidAt(Vec3::Zero()).bodies.size();
    int projected = 0;
    for (std::size_t nudged = 0; nudged < bodies; ++nudged)
        for (const Vec3& nudge : {Vec3(0, 0, 0.5), Vec3(0, 0, -0.5), Vec3(0.5, 0.5, 0)}) {
            SCOPED_TRACE(testing::Message() << "body " << nudged << " nudged by " << nudge.transpose());
            const World tree = nudgedAndStepped(SolverKind::Tree, nudged, nudge);
            const World dense = nudgedAndStepped(SolverKind::Exact, nudged, nudge);
            ASSERT_EQ(tree.lastStep().treeFallbacks, 0);
            projected += tree.lastStep().projectionPasses > 0;
            // Every row within positionTolerance (1e-10) after the projection's passes.
            EXPECT_LT(tree.maxJointError(), 1e-9);
            EXPECT_NEAR(tree.maxPenetration(), dense.maxPenetration(), 1e-9);
            for (std::size_t b = 0; b < bodies; ++b) {
                // units and radians: rounding of two solvers over one step (measured ≤ 1e-12)
                EXPECT_LT((tree.bodies()[b].position - dense.bodies()[b].position).norm(), 1e-9) << "body " << b;
                EXPECT_LT(tree.bodies()[b].orientation.angularDistance(dense.bodies()[b].orientation), 1e-9)
                    << "body " << b;
            }
        }
    EXPECT_EQ(projected, static_cast<int>(3 * bodies)) << "every nudge needs the projection";
}

}  // namespace
}  // namespace af
