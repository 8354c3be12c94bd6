// Islands of many figures solved figure by figure (figure_blocks.h): each figure's rows exactly,
// the contacts between figures by Gauss–Seidel through each figure's articulated response.

#include "af/geometry/shapes.h"
#include "dynamics/figure_blocks.h"
#include "dynamics/world_access.h"
#include "row_scene_util.h"
#include "scene_test_util.h"

#include <algorithm>
#include <numeric>

namespace af {
namespace {

using test::humanoidAt;
using test::Scene;

// Two free chains of eight links, the second lying on the first, shifted by half a link so each
// of its links rests on two of the first's; the first on the floor. Every link is pushed down and
// spun, so contacts push, and (with `friction`) stick or slide.
Scene stackedChains(Real friction) {
    Scene scene(test::horizontalChain(8, 1, true));
    const Scene upper(test::horizontalChain(8, 3, true));
    const int offset = static_cast<int>(scene.bodies.size());
    for (RigidBody b : upper.bodies) {
        b.position.x() += 5;
        scene.bodies.push_back(b);
    }
    for (Joint j : upper.joints) {
        j.bodyA += offset;
        if (j.bodyB != kWorldBody) j.bodyB += offset;
        j.anchorB.x() += j.bodyB == kWorldBody ? 5 : 0;
        scene.joints.push_back(j);
    }
    test::spin(scene, 5, 2);
    for (std::size_t k = 0; k < 8; ++k) {
        Contact floor;
        floor.bodyA = static_cast<int>(k);
        floor.point = scene.bodies[k].position - Vec3(0, 0, 1);
        floor.depth = 0.01 * static_cast<Real>(k % 3);
        floor.friction = friction;
        scene.contacts.push_back(floor);
        scene.bodies[k].linearVelocity.z() -= 20;
        for (std::size_t below : {k, k + 1}) {
            if (below >= 8) continue;
            Contact between;  // normal from the lower link (B) up to the upper one (A)
            between.bodyA = offset + static_cast<int>(k);
            between.bodyB = static_cast<int>(below);
            between.point = Vec3(scene.bodies[below].position.x() + (below == k ? 2.5 : -2.5), 0, 2);
            between.depth = 0.02 * static_cast<Real>((k + below) % 4);
            between.friction = friction;
            scene.contacts.push_back(between);
        }
        scene.bodies[static_cast<std::size_t>(offset) + k].linearVelocity.z() -= 40;
    }
    scene.write();
    return scene;
}

// The velocity change M⁻¹Jᵀλ (or the move) of impulses λ on the scene's rows.
std::vector<Vec3> changeOf(const Scene& scene, const RowSystem& system, std::span<const Real> lambda) {
    std::vector<Vec3> linear(scene.bodies.size(), Vec3::Zero()), angular(scene.bodies.size(), Vec3::Zero());
    accumulateResponses(scene.rows.all(), system.responses(), lambda, linear, angular);
    for (std::size_t b = 0; b < angular.size(); ++b) linear.push_back(angular[b]);
    return linear;
}

// The blocks' answer to the scene's velocity or position problem, sweeping to `stopChange`.
struct BlockAnswer {
    RowSystem system;
    BlockSolveResult result;
};
void solveByBlocks(Scene& scene, bool position, Real stopChange, BlockAnswer& out) {
    if (position) holdFrictionAtZero(scene.rows, scene.ranges);
    out.system.buildResponses(scene.rows, scene.bodies);
    position ? out.system.setPositionRhs(scene.rows) : out.system.setVelocityRhs(scene.rows, scene.bodies);
    std::fill(out.system.solution().begin(), out.system.solution().end(), Real(0));
    std::fill(out.system.states().begin(), out.system.states().end(), LcpRowState::Unknown);
    std::vector<std::uint64_t> keys(scene.rows.size());
    std::iota(keys.begin(), keys.end(), std::uint64_t(1));
    FigureBlockSolver blocks;
    blocks.setStructure(scene.bodies, scene.joints);
    ASSERT_EQ(blocks.figureCount(), 2u);
    SolverTuning tuning;
    tuning.blocks.maxSweeps = 10000;
    out.result = blocks.solve(position ? BlockProblem::Position : BlockProblem::Velocity, scene.rows, scene.ranges, keys,
                              out.system, scene.bodies, tuning, stopChange);
}

Real largestDifference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    Real worst = 0;
    for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, (a[k] - b[k]).norm());
    return worst;
}
Real largestNorm(const std::vector<Vec3>& a) {
    Real worst = 0;
    for (const Vec3& v : a) worst = std::max(worst, v.norm());
    return worst;
}

TEST(FigureBlocks, FrictionlessContactsBetweenFiguresConvergeToTheExactAnswer) {
    // Frictionless, the problem (with its CFM) has one answer; the blocks reach the dense
    // pivoting solve's velocity change and move as they sweep closer.
    for (const bool position : {false, true}) {
        Scene scene = stackedChains(0);
        test::Dense dense;
        test::solveDense(scene, position, dense);
        ASSERT_EQ(dense.result.status, LcpStatus::Solved);
        const std::vector<Vec3> exact = changeOf(scene, dense.system, dense.lambda);
        BlockAnswer blocks;
        solveByBlocks(scene, position, position ? 1e-12 : 1e-6, blocks);  // velocities about 40
        EXPECT_EQ(blocks.result.status, LcpStatus::Solved);
        EXPECT_GT(blocks.result.sweeps, 2) << "the figures' contacts were not iterated";
        EXPECT_LT(blocks.result.sweeps, 10000);
        const std::vector<Vec3> answer = changeOf(scene, blocks.system, blocks.system.solution());
        // Measured: velocities 7.9e-8 of the largest after 1052 sweeps (the stack is statically
        // indeterminate: its impulses drift slowly along redundant contacts), moves 2.6e-9 after 6.
        EXPECT_LT(largestDifference(answer, exact), (position ? 1e-8 : 2e-7) * largestNorm(exact))
            << (position ? "position" : "velocity");
    }
}

TEST(FigureBlocks, FrictionBetweenFiguresIsCoupledToItsNormalAsTheLcpSays) {
    // With friction the answer need not be unique; it must solve the coupled LCP: every row
    // complementary, each friction row within μ of its own normal's impulse.
    Scene scene = stackedChains(0.6);
    test::Dense dense;
    test::solveDense(scene, false, dense);  // A, b and bounds to check against
    BlockAnswer blocks;
    solveByBlocks(scene, false, 1e-6, blocks);
    EXPECT_EQ(blocks.result.status, LcpStatus::Solved);
    const LcpProblem p = dense.system.problem();
    const std::span<const Real> x = blocks.system.solution();
    const std::size_t n = static_cast<std::size_t>(p.size);
    Real residual = 0, largestImpulse = 0;
    int sliding = 0;
    for (std::size_t i = 0; i < n; ++i) {
        Real w = -p.b[i] + p.cfm[i] * x[i];
        for (std::size_t j = 0; j < n; ++j) w += p.a[i * n + j] * x[j];
        Real lo = p.lo[i], hi = p.hi[i];
        if (p.findex[i] >= 0) {
            hi = p.mu[i] * std::abs(x[static_cast<std::size_t>(p.findex[i])]);
            lo = -hi;
            sliding += hi > 0 && std::abs(std::abs(x[i]) - hi) < 1e-9 * hi ? 1 : 0;
        }
        residual = std::max(residual, std::abs(x[i] - std::clamp(x[i] - w, lo, hi)));
        largestImpulse = std::max(largestImpulse, std::abs(x[i]));
    }
    EXPECT_GT(sliding, 0) << "no contact slid: the coupling was not tried";
    // Measured: 5.7e-10 of the largest impulse after 744 sweeps, 8 friction rows sliding.
    EXPECT_LT(residual, 1.5e-9 * largestImpulse);
}

TEST(FigureBlocks, PileOfEightHumanoidsRestsWithItsJointsClosed) {
    World world;
    for (int i = 0; i < 8; ++i) world.addFigure(humanoidAt(Vec3(0, 0, 20 + 30 * i), 37 * i, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    int blockedSteps = 0, failedSteps = 0;
    Real worstJoint = 0;
    while (world.time() < 20 && !world.atRest()) {
        world.step();
        blockedSteps += detail::WorldAccess::counters(world).largeIslands > 0 ? 1 : 0;
        worstJoint = std::max(worstJoint, world.maxJointError());
        failedSteps += world.lastStep().failures > 0 ? 1 : 0;
    }
    // Measured: no failed solve, at rest after 1.97 s, joints at most 1.0e-10 apart, contacts at
    // the slop (0.05).
    EXPECT_EQ(failedSteps, 0);
    ASSERT_TRUE(world.atRest()) << "the pile never came to rest";
    EXPECT_GT(blockedSteps, 0) << "the pile never made an island of blocks";
    EXPECT_LT(world.maxJointError(), 1e-6);
    EXPECT_LT(worstJoint, 1e-6);
    EXPECT_LT(world.maxPenetration(), 0.05 * 1.02);
}

// A block past its pivot budget is relaxed: its tree's auxiliary rows by sweeps of their Schur
// complement. A budget of 0 relaxes every block from the start; the pile must still land and
// rest with its joints exact (the tree holds them whatever the contacts do), and the world must
// say that the solves fell back.
TEST(FigureBlocks, BlocksPastTheirPivotBudgetAreRelaxedWithTheirJointsHeld) {
    World world;
    SolverTuning tuning;
    tuning.blocks.pivotsPerRow = 0;
    detail::WorldAccess::setTuning(world, tuning);
    for (int i = 0; i < 4; ++i) world.addFigure(humanoidAt(Vec3(0, 0, 20 + 30 * i), 37 * i, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    int blockedSteps = 0, failedSteps = 0;
    Real worstJoint = 0, worstPenetration = 0;
    while (world.time() < 20 && !world.atRest()) {
        world.step();
        const bool blocked = detail::WorldAccess::counters(world).largeIslands > 0;
        blockedSteps += blocked ? 1 : 0;
        if (blocked) failedSteps += world.lastStep().failures > 0 ? 1 : 0;
        worstJoint = std::max(worstJoint, world.maxJointError());
        worstPenetration = std::max(worstPenetration, world.maxPenetration());
    }
    ASSERT_GT(blockedSteps, 0) << "the pile never made an island of blocks";
    EXPECT_EQ(failedSteps, blockedSteps) << "a relaxed block was not reported as a fallback";
    // Measured: at rest after 1.25 s (52 steps with blocks), joints at most 1.4e-10 apart,
    // contacts at most 0.0504 deep (the slop is 0.05).
    ASSERT_TRUE(world.atRest()) << "the pile never came to rest";
    EXPECT_LT(world.time(), 2.0);
    EXPECT_LT(worstJoint, 1e-9);
    EXPECT_LT(worstPenetration, 0.05 * 1.02);
}

}  // namespace
}  // namespace af
