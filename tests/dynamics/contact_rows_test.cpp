// Contact rows of the step's ContactPoints against their definitions: each row's J u is the
// measured rate of change of the separation of the point's two surface points along its
// direction; and every row's softness is relativeCfm times its J M⁻¹ Jᵀ computed with the full
// 12×12 inverse mass matrix.

#include "dynamics/contact_set.h"
#include "dynamics/row_system.h"

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

// The bodies moved for time h with their velocities (orientation by the exact rotation of ω h).
std::vector<RigidBody> advanced(std::vector<RigidBody> bodies, Real h) {
    for (RigidBody& b : bodies) {
        b.position += h * b.linearVelocity;
        const Real angle = b.angularVelocity.norm() * h;
        if (angle != 0) b.orientation = (Quat(Eigen::AngleAxis<Real>(angle, b.angularVelocity.normalized())) * b.orientation).normalized();
    }
    return bodies;
}

// The relative velocity along d of the two surface points, as a central difference in time.
Real measuredRate(const std::vector<RigidBody>& bodies, const ContactPoint& p, const Vec3& d) {
    using contact_detail::bodyOrNull;
    using contact_detail::toWorld;
    const Real h = 1e-4;  // truncation ~h²|ω|³|r| ≈ 1e-6, rounding ~1e-10
    const std::vector<RigidBody> later = advanced(bodies, h), earlier = advanced(bodies, -h);
    const auto gap = [&](const std::vector<RigidBody>& at) {
        return d.dot(toWorld(bodyOrNull(at, p.bodyA), p.localA) - toWorld(bodyOrNull(at, p.bodyB), p.localB));
    };
    return (gap(later) - gap(earlier)) / (2 * h);
}

// Each row's J u is the rate at which the separation of the point's two surface points changes
// along the row's direction, so that the position projection's linearisation is exact to first
// order; the normal row's C is the separation itself (beyond the slop), its friction rows are
// bounded by it with the point's coefficient, and the keys follow the rows.
TEST(ContactRows, PointRowsAreTheRatesOfTheSeparationOfTheirTwoSurfacePoints) {
    Random random;
    const std::vector<RigidBody> bodies = randomBodies(random, 4);
    const std::vector<Mat3> inverses = inversesOf(bodies);
    const std::vector<ContactPoint> points = randomPoints(random, 4, 200);
    ContactSettings settings;
    settings.restitutionThreshold = 3;  // some points bounce, some do not

    ConstraintRows rows;
    std::vector<std::uint64_t> keys;
    writeContactRows(points, bodies, inverses, settings, rows, keys);
    ASSERT_EQ(keys.size(), rows.size());

    std::size_t r = 0;
    int bounced = 0;
    for (const ContactPoint& p : points) {
        SCOPED_TRACE(r);
        ASSERT_LT(r, rows.size());
        const ConstraintRow& normal = rows[r];
        EXPECT_EQ(normal.bodyA, p.bodyA);
        EXPECT_EQ(normal.bodyB, p.bodyB);
        EXPECT_EQ(normal.linearA, p.normal);
        EXPECT_NEAR(normal.error, settings.slop - currentDepth(p, bodies), 1e-12);
        EXPECT_NEAR(rowVelocity(normal, bodies), measuredRate(bodies, p, p.normal), 1e-5);
        EXPECT_EQ(normal.lo, 0);
        EXPECT_EQ(normal.hi, kInfinity);
        const bool bounces = p.approachVelocity < -settings.restitutionThreshold;
        EXPECT_EQ(normal.target, bounces ? -p.restitution * p.approachVelocity : 0);
        bounced += bounces ? 1 : 0;
        EXPECT_EQ(keys[r], p.key);
        const int normalIndex = static_cast<int>(r++);
        const int frictionRows = p.friction <= 0 ? 0 : p.frictionDirection ? 1 : 2;
        for (int k = 0; k < frictionRows; ++k, ++r) {
            ASSERT_LT(r, rows.size());
            const ConstraintRow& f = rows[r];
            const Vec3 t = f.linearA;  // the points' body A is never the world
            EXPECT_NEAR(t.dot(p.normal), 0, 1e-12);
            EXPECT_NEAR(t.norm(), 1, 1e-12);
            EXPECT_NEAR(rowVelocity(f, bodies), measuredRate(bodies, p, t), 1e-5);
            EXPECT_EQ(f.frictionSource, normalIndex);
            EXPECT_EQ(f.frictionCoefficient, p.friction);
            EXPECT_EQ(keys[r], p.key + static_cast<std::uint64_t>(k + 1));
        }
    }
    EXPECT_EQ(r, rows.size());
    EXPECT_GT(bounced, 0);
    EXPECT_LT(bounced, static_cast<int>(points.size()));
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

// A resting box's manifold lists its equally deep corners deepest first, in whatever order
// rounding puts them; the points, and so the rows and the warm-start keys, come in one order.
TEST(ContactRows, GatheredPointsKeepOneOrderWhateverOrderTheManifoldListsThem) {
    Random random;
    const std::vector<RigidBody> bodies = randomBodies(random, 2);
    const std::vector<BodyMaterial> materials(2, BodyMaterial{0.5, 0, std::nullopt});
    BodyContact contact;
    contact.bodyA = 0;
    contact.bodyB = 1;
    contact.manifold.normal = random.unit();
    contact.manifold.count = 4;
    for (std::uint32_t k = 0; k < 4; ++k) contact.manifold.points[k] = {random.vector(10), 0.01, 40 - 7 * k};
    ContactSet first, second;
    first.gather({contact}, bodies, materials);
    std::swap(contact.manifold.points[0], contact.manifold.points[2]);
    std::swap(contact.manifold.points[1], contact.manifold.points[3]);
    second.gather({contact}, bodies, materials);
    ASSERT_EQ(first.size(), 4u);
    ASSERT_EQ(second.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(first.points()[i].key, second.points()[i].key);
        EXPECT_EQ(first.points()[i].localA, second.points()[i].localA);
    }
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
