// Contact rows of the step's ContactPoints against their definitions: the rows written straight
// from the points equal, bit for bit, the rows of the Contact each point is at; and every row's
// softness is relativeCfm times its J M⁻¹ Jᵀ computed with the full 12×12 inverse mass matrix.

#include "dynamics/contact_set.h"

#include <gtest/gtest.h>

#include <random>

namespace af {
namespace {

class Random {
public:
    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(engine_); }
    Vec3 vector(Real scale) { return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)); }
    Vec3 unit() { return vector(1).normalized(); }
    Quat rotation() { return Quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized(); }
    bool chance(Real p) { return uniform(0, 1) < p; }

private:
    std::mt19937_64 engine_{20261122};
};

std::vector<RigidBody> randomBodies(Random& random, int count) {
    std::vector<RigidBody> bodies;
    for (int i = 0; i < count; ++i) {
        const Vec3 d(random.uniform(1, 50), random.uniform(1, 50), random.uniform(1, 50));
        RigidBody b = RigidBody::dynamic(random.uniform(0.5, 20), d.asDiagonal(), random.vector(100), random.rotation());
        b.linearVelocity = random.vector(30);
        b.angularVelocity = random.vector(3);
        bodies.push_back(b);
    }
    return bodies;
}

std::vector<ContactPoint> randomPoints(Random& random, int bodyCount, int count) {
    std::vector<ContactPoint> points;
    for (int i = 0; i < count; ++i) {
        ContactPoint p;
        p.bodyA = static_cast<int>(random.uniform(0, bodyCount - 0.001));
        p.bodyB = random.chance(0.5) ? kWorldBody : (p.bodyA + 1) % bodyCount;
        p.normal = random.unit();
        p.localA = random.vector(10);
        p.localB = random.vector(p.bodyB == kWorldBody ? 100 : 10);
        p.friction = random.chance(0.2) ? 0 : random.uniform(0.1, 1);
        p.restitution = random.uniform(0, 1);
        if (random.chance(0.3)) p.frictionDirection = random.vector(2);
        p.key = static_cast<std::uint64_t>(1000 * i);
        p.approachVelocity = random.uniform(-10, 10);
        points.push_back(p);
    }
    return points;
}

std::vector<Mat3> inversesOf(const std::vector<RigidBody>& bodies) {
    std::vector<Mat3> inverses;
    for (const RigidBody& b : bodies) inverses.push_back(b.inverseInertiaWorld());
    return inverses;
}

void expectSameRow(const ConstraintRow& a, const ConstraintRow& b) {
    EXPECT_EQ(a.bodyA, b.bodyA);
    EXPECT_EQ(a.bodyB, b.bodyB);
    EXPECT_EQ(a.linearA, b.linearA);
    EXPECT_EQ(a.angularA, b.angularA);
    EXPECT_EQ(a.linearB, b.linearB);
    EXPECT_EQ(a.angularB, b.angularB);
    EXPECT_EQ(a.target, b.target);
    EXPECT_EQ(a.error, b.error);
    EXPECT_EQ(a.lo, b.lo);
    EXPECT_EQ(a.hi, b.hi);
    EXPECT_EQ(a.frictionSource, b.frictionSource);
    EXPECT_EQ(a.frictionCoefficient, b.frictionCoefficient);
    EXPECT_EQ(a.cfm, b.cfm);
}

TEST(ContactRows, PointRowsEqualTheRowsOfTheContactThePointIsAt) {
    Random random;
    const std::vector<RigidBody> bodies = randomBodies(random, 4);
    const std::vector<Mat3> inverses = inversesOf(bodies);
    const std::vector<ContactPoint> points = randomPoints(random, 4, 200);
    ContactSettings settings;
    settings.restitutionThreshold = 3;  // some points bounce, some do not

    ConstraintRows fromPoints;
    std::vector<std::uint64_t> keys;
    writeContactRows(points, bodies, inverses, settings, fromPoints, keys);

    ConstraintRows fromContacts;
    std::vector<std::uint64_t> expectedKeys;
    for (const ContactPoint& p : points) {
        const std::size_t first = fromContacts.size();
        writeContactRows(currentContact(p, bodies), bodies, settings, fromContacts);
        for (std::size_t r = first; r < fromContacts.size(); ++r) expectedKeys.push_back(p.key + (r - first));
    }
    ASSERT_EQ(fromPoints.size(), fromContacts.size());
    EXPECT_GT(fromPoints.size(), 2 * points.size()) << "most points must have friction rows";
    for (std::size_t r = 0; r < fromPoints.size(); ++r) {
        SCOPED_TRACE(r);
        expectSameRow(fromPoints[r], fromContacts[r]);
    }
    EXPECT_EQ(keys, expectedKeys);
}

TEST(ContactRows, CurrentDepthIsTheDepthOfTheCurrentContact) {
    Random random;
    const std::vector<RigidBody> bodies = randomBodies(random, 3);
    for (const ContactPoint& p : randomPoints(random, 3, 100)) EXPECT_EQ(currentDepth(p, bodies), currentContact(p, bodies).depth);
}

// J M⁻¹ Jᵀ of one row with M⁻¹ = diag(m_A⁻¹ I, I_A⁻¹, m_B⁻¹ I, I_B⁻¹) written out in full.
Real bruteForceDiagonal(const ConstraintRow& row, std::span<const RigidBody> bodies) {
    Eigen::Matrix<Real, 12, 1> j = Eigen::Matrix<Real, 12, 1>::Zero();
    Eigen::Matrix<Real, 12, 12> inverseMass = Eigen::Matrix<Real, 12, 12>::Zero();
    if (row.bodyA != kWorldBody) {
        const RigidBody& a = bodies[static_cast<std::size_t>(row.bodyA)];
        j << row.linearA, row.angularA, Vec3::Zero(), Vec3::Zero();
        inverseMass.block<3, 3>(0, 0) = a.inverseMass * Mat3::Identity();
        inverseMass.block<3, 3>(3, 3) = a.rotation() * a.inverseInertia * a.rotation().transpose();
    }
    if (row.bodyB != kWorldBody) {
        const RigidBody& b = bodies[static_cast<std::size_t>(row.bodyB)];
        j.segment<3>(6) = row.linearB;
        j.segment<3>(9) = row.angularB;
        inverseMass.block<3, 3>(6, 6) = b.inverseMass * Mat3::Identity();
        inverseMass.block<3, 3>(9, 9) = b.rotation() * b.inverseInertia * b.rotation().transpose();
    }
    return j.dot(inverseMass * j);
}

TEST(ContactRows, SoftnessIsRelativeCfmTimesTheRowsOwnEffectiveInverseMass) {
    Random random;
    const std::vector<RigidBody> bodies = randomBodies(random, 4);
    ConstraintRows rows;
    std::vector<std::uint64_t> keys;
    ContactSettings settings;
    settings.relativeCfm = 1e-3;
    writeContactRows(randomPoints(random, 4, 100), bodies, inversesOf(bodies), settings, rows, keys);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const Real expected = settings.relativeCfm * bruteForceDiagonal(rows[r], bodies);
        EXPECT_NEAR(rows[r].cfm, expected, 1e-12 * expected) << "row " << r;
    }
}

}  // namespace
}  // namespace af
