// PGS on the rows (sequential impulses through per-body accumulators) against PGS on the dense
// matrix of the same rows: the same iteration, so the same impulses up to rounding, on a chain
// with limits, joint friction and contacts with coupled friction.

#include "../figure/figure_test_util.h"
#include "dynamics/contact_rows.h"
#include "dynamics/row_pgs.h"
#include "dynamics/row_system.h"
#include "world_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace af {
namespace {

struct ChainOnTheGround {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    ConstraintRows rows;

    explicit ChainOnTheGround(unsigned seed) {
        const Figure figure = test::horizontalChain(12, 0, true);
        for (const FigureBody& b : figure.bodies)
            bodies.push_back(RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation)));
        joints = makeJoints(figure);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<Real> u(-40, 40);
        for (RigidBody& b : bodies) {
            b.linearVelocity = Vec3(u(rng), u(rng), u(rng) - 60);
            b.angularVelocity = Vec3(u(rng), u(rng), u(rng)) / 20;
        }
        for (const Joint& j : joints) writeJointRows(j, bodies, JointRowSettings{}, rows);
        for (std::size_t k = 0; k < bodies.size(); ++k) {
            Contact c;
            c.bodyA = static_cast<int>(k);
            c.point = bodies[k].position + Vec3(0, 0, -1);
            c.normal = Vec3::UnitZ();
            c.friction = 0.6;
            writeContactRows(c, bodies, ContactSettings{}, rows);
        }
    }
};

TEST(RowPgs, GivesTheImpulsesOfPgsOnTheDenseMatrix) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
        ChainOnTheGround scene(seed);
        RowSystem system;
        system.build(scene.rows, scene.bodies);
        system.setVelocityRhs(scene.rows, scene.bodies);
        const LcpPgsSettings settings{.maxIterations = 60, .tolerance = 1e-12};

        std::vector<Real> dense(scene.rows.size(), 0);
        LcpPgsSolver densePgs(settings);
        const LcpPgsResult d = densePgs.solve(system.problem(), dense);

        std::vector<Real> sparse(scene.rows.size(), 0);
        RowPgs rowPgs;
        const LcpPgsResult r = rowPgs.solve(scene.rows, system, scene.bodies.size(), sparse, settings);

        ASSERT_EQ(r.status, d.status) << seed;
        EXPECT_EQ(r.iterations, d.iterations) << seed;
        Real scale = 1, worst = 0;
        for (std::size_t i = 0; i < dense.size(); ++i) {
            scale = std::max(scale, std::abs(dense[i]));
            worst = std::max(worst, std::abs(dense[i] - sparse[i]));
        }
        EXPECT_LE(worst, 1e-9 * scale) << seed;
        EXPECT_NEAR(r.residual, d.residual, 1e-9 * scale) << seed;
    }
}

}  // namespace
}  // namespace af
