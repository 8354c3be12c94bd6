// RowSystem's responses and displacements: the world inverse inertias it computes once per body
// are RigidBody's, and the displacements of a solve can be applied after the caller's rows have
// been rewritten (with other rows, or none).

#include "dynamics/contact_rows.h"
#include "dynamics/row_system.h"
#include "scene_test_util.h"

#include <gtest/gtest.h>

#include <random>

namespace af {
namespace {

struct Humanoid {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    std::vector<Contact> contacts;
    ConstraintRows rows;

    Humanoid() : joints(makeJoints(test::hungHumanoid())) {
        for (const FigureBody& b : test::hungHumanoid().bodies)
            bodies.push_back(RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation)));
        std::mt19937 rng(5);
        std::uniform_real_distribution<Real> u(-1, 1);
        for (RigidBody& b : bodies) {
            b.orientation = Quat(Eigen::AngleAxis<Real>(0.3, Vec3(u(rng), u(rng), u(rng)).normalized())) * b.orientation;
            b.linearVelocity = Vec3(u(rng), u(rng), u(rng)) * 20;
        }
        for (const Joint& j : joints) writeJointRows(j, bodies, JointRowSettings{}, rows);
        for (std::size_t k = 0; k < bodies.size(); k += 3) {
            Contact c;
            c.bodyA = static_cast<int>(k);
            c.bodyB = k + 1 < bodies.size() ? static_cast<int>(k + 1) : kWorldBody;
            c.point = bodies[k].position + Vec3(0.5, -0.5, -1);
            c.normal = Vec3(0.1, 0.2, 1).normalized();
            c.friction = 0.5;
            contacts.push_back(c);
        }
        for (const Contact& c : contacts) writeContactRows(c, bodies, ContactSettings{}, rows);
    }
};

TEST(RowSystem, InverseInertiasAreThoseOfTheBodies) {
    const Humanoid h;
    RowSystem system;
    const std::span<const Mat3> inertia = system.inverseInertiasWorld(h.bodies);
    ASSERT_EQ(inertia.size(), h.bodies.size());
    for (std::size_t k = 0; k < h.bodies.size(); ++k) EXPECT_EQ(inertia[k], h.bodies[k].inverseInertiaWorld()) << k;
}

// The rows written with the per-body inertias are those written body by body, up to the
// symmetrisation of I⁻¹ (joints' softness was computed from R I⁻¹ Rᵀ as it comes): 1e-12 relative.
TEST(RowSystem, RowsWithGivenInertiasAreTheSame) {
    const Humanoid h;
    RowSystem system;
    const std::span<const Mat3> inertia = system.inverseInertiasWorld(h.bodies);
    ConstraintRows given;
    for (const Joint& j : h.joints) writeJointRows(j, h.bodies, inertia, JointRowSettings{}, given);
    for (const Contact& c : h.contacts) writeContactRows(c, h.bodies, inertia, ContactSettings{}, given);
    ASSERT_EQ(given.size(), h.rows.size());
    for (std::size_t r = 0; r < given.size(); ++r) {
        EXPECT_EQ(given[r].angularA, h.rows[r].angularA) << r;
        EXPECT_EQ(given[r].angularB, h.rows[r].angularB) << r;
        EXPECT_EQ(given[r].error, h.rows[r].error) << r;
        EXPECT_EQ(given[r].frictionSource, h.rows[r].frictionSource) << r;
        EXPECT_NEAR(given[r].cfm, h.rows[r].cfm, 1e-12 * h.rows[r].cfm) << r;
    }
}

TEST(RowSystem, DisplacementsNeedNotKeepTheSolvedRows) {
    Humanoid h;
    RowSystem system;
    system.buildResponses(h.rows, h.bodies);
    std::mt19937 rng(3);
    std::uniform_real_distribution<Real> u(-0.05, 0.05);
    for (Real& x : system.solution()) x = u(rng);
    // What the solved rows say: each body moved by the sum of its rows' moves.
    std::vector<RigidBody> withRows = h.bodies;
    std::vector<Vec3> linear(withRows.size()), angular(withRows.size());
    accumulateResponses(h.rows.all(), system.responses(), system.solution(), linear, angular);
    for (std::size_t k = 0; k < withRows.size(); ++k) displaceBody(withRows[k], linear[k], angular[k]);
    h.rows.clear();
    std::vector<RigidBody> without = h.bodies;
    system.applyDisplacements(without);
    Real moved = 0;
    for (std::size_t k = 0; k < without.size(); ++k) {
        EXPECT_EQ(without[k].position, withRows[k].position) << k;
        EXPECT_EQ(without[k].orientation.coeffs(), withRows[k].orientation.coeffs()) << k;
        moved = std::max(moved, (without[k].position - h.bodies[k].position).norm());
    }
    EXPECT_GT(moved, 1e-3);
}

}  // namespace
}  // namespace af
