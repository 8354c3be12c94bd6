// The position projection with the tree solver (Island::solvePositionsWithTree) against the dense
// pivoting solve of the same rows: the tree leaves far one-sided rows out of its LCP and puts
// back those its move would violate, so its answer, and the bodies' poses after the step, must
// be the dense one's up to rounding.

#include "af/geometry/shapes.h"
#include "dynamics/island.h"
#include "dynamics/world_access.h"
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
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    detail::WorldAccess::bodies(world)[nudged].position += nudge;  // the one body, before the first step
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
            ASSERT_EQ(detail::WorldAccess::counters(tree).treeFallbacks, 0);
            projected += detail::WorldAccess::counters(tree).projectionPasses > 0;
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

// A heavy hub and a light bar 40 long along +X, joined by a hinge about Z at the bar's near end,
// the bar pitched 0.02 rad up off the hinge's axis, its far end 0.7 above a contact point with
// the world (0.75 from violating it, slop included). Closing the hinge's angular rows (0.02 rad,
// the largest violation) turns the light bar down by about 0.8 at that end: the contact, left
// out of the first LCP as far apart, must be put back, and the hub turned up instead.
struct HubAndBar {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    std::vector<ContactPoint> points;
};

HubAndBar hubAndBar() {
    const Figure figure = test::figureOfBlocks(
        {"origin", "bar"}, test::boxBodyText("hub", "origin", Vec3(1, 1, 1), Vec3(-1, 0, 10), 1000) +
                               test::boxBodyText("bar", "bar", Vec3(20, 0.5, 0.5), Vec3(20, 0, 10), 0.01) +
                               "hinge \"h\" { body1 \"bar\" body2 \"hub\" anchor ( 0, 0, 10 ) axis ( 0, 0, 1 ) friction 0 }\n");
    World world(figure);
    HubAndBar scene{world.bodies(), world.joints(), {}};
    RigidBody& bar = scene.bodies[1];
    ContactPoint point;
    point.bodyA = 1;
    point.localA = bar.orientation.conjugate() * (Vec3(40, 0, 9.5) - bar.position);  // the far end's bottom
    const Vec3 anchor(0, 0, 10);
    const Quat pitch(Eigen::AngleAxis<Real>(-0.02, Vec3::UnitY()));
    bar.position = anchor + pitch * (bar.position - anchor);
    bar.orientation = pitch * bar.orientation;
    point.localB = bar.position + bar.orientation * point.localA - Vec3(0, 0, 0.7);
    point.key = 1;
    scene.points.push_back(point);
    return scene;
}

std::vector<RigidBody> projected(HubAndBar scene, SolverKind solver) {
    WorldSettings settings;
    settings.solver = solver;
    const SolverTuning tuning;
    StepReport report;
    SolverCounters counters;
    WarmStartCache noWarmStart;
    Real springWork = 0;
    IslandContext context{settings, tuning, {}, scene.bodies, report, counters, noWarmStart, springWork};
    const std::vector<int> bodyIds{0, 1}, jointIds{0}, pointIds{0}, localOf{0, 1};
    Island island;
    island.gather(bodyIds, jointIds, pointIds, IslandWorld{scene.bodies, scene.joints, scene.points, localOf});
    island.project(context);
    EXPECT_EQ(counters.treeFallbacks, 0);
    EXPECT_GT(counters.projectionPasses, 0);
    island.scatter(scene.bodies, scene.joints);
    // The contact holds (within the slop) and the hinge is closed.
    EXPECT_GT(-currentDepth(scene.points[0], scene.bodies), -settings.contact.slop - 1e-9);
    EXPECT_LT(World(scene.bodies, scene.joints).maxJointError(), 1e-9);
    return scene.bodies;
}

TEST(Projection, TreePutsBackAFarContactItsMoveWouldPassThrough) {
    const HubAndBar scene = hubAndBar();
    ASSERT_NEAR(-currentDepth(scene.points[0], scene.bodies), 0.7, 1e-9) << "the far end's gap";
    const std::vector<RigidBody> tree = projected(scene, SolverKind::Tree);
    const std::vector<RigidBody> dense = projected(scene, SolverKind::Exact);
    // The hub turned up to spare the contact: the bar alone would have passed it by 0.05.
    EXPECT_GT(tree[0].orientation.angularDistance(scene.bodies[0].orientation), 1e-4);
    for (std::size_t b = 0; b < tree.size(); ++b) {
        EXPECT_LT((tree[b].position - dense[b].position).norm(), 1e-9) << "body " << b;
        EXPECT_LT(tree[b].orientation.angularDistance(dense[b].orientation), 1e-9) << "body " << b;
    }
}

}  // namespace
}  // namespace af
