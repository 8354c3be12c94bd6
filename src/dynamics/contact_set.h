#pragma once
// The contact points of one step, attached to their bodies.
//
// The collision world reports manifolds at the start-of-step poses. Each point is kept as the two
// surface points it joins, pA on A and pB on B, in their body frames (world frame for the static
// world), and the manifold normal n (world, B → A), fixed for the step. Wherever the bodies have
// moved since, the separation is n·(pA − pB), and each body is pushed at its own point. The
// position projection and the penetration report read contacts this way, without another
// collision query.

#include "af/collision/collision_world.h"
#include "af/dynamics/rigid_body.h"
#include "contact_rows.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace af {

// What a body's surface is made of (Doom: contactFriction, bounciness, frictionDirection).
struct BodyMaterial {
    Real friction = 0;
    Real bounciness = 0;
    std::optional<Vec3> frictionDirection;  // body frame
};

struct ContactPoint {
    int bodyA = 0;
    int bodyB = kWorldBody;
    Vec3 normal = Vec3::UnitZ();
    Vec3 localA = Vec3::Zero();
    Vec3 localB = Vec3::Zero();
    Real friction = 0;
    Real restitution = 0;
    std::optional<Vec3> frictionDirection;  // A's, body frame
    std::uint64_t key = 0;                  // the same point in the next step has the same key
    Real approachVelocity = 0;              // n·(v_A − v_B) at the point when gathered
    // pA and pB in the world where ContactSet::keep took the approach velocity (placed), which a
    // step's start reads again before the bodies move (resting bench ragdoll, every point a step).
    bool placed = false;
    Vec3 onA = Vec3::Zero();
    Vec3 onB = Vec3::Zero();
};

namespace contact_detail {

inline const RigidBody* bodyOrNull(std::span<const RigidBody> bodies, int index) {
    return index == kWorldBody ? nullptr : &bodies[static_cast<std::size_t>(index)];
}

// Where a point fixed to a body (body frame), or to the world (body null, world frame), is now.
inline Vec3 toWorld(const RigidBody* body, const Vec3& local) {
    return body ? Vec3(body->position + body->orientation * local) : local;
}

}  // namespace contact_detail

// The key of a manifold's point: the same for the same pair and feature step after step
// (ContactPoint::key; its rows are keyed key + 0 for the normal, + 1 and + 2 for friction).
std::uint64_t contactPairKey(const BodyContact& manifold);
std::uint64_t contactPointKey(std::uint64_t pairKey, const ManifoldPoint& point);

// The point's depth at the bodies' current poses: −n·(pA − pB).
Real currentDepth(const ContactPoint& point, std::span<const RigidBody> bodies);
// Appends every point's rows at the bodies' current poses, and one key per row (the point's key
// and the row's place). The rows push A at pA and B at pB, so that J is exactly the derivative of
// the normal row's C = n·(pA − pB) for the step's n (contact_rows.cpp). inverseInertiaWorld: each
// body's RigidBody::inverseInertiaWorld, indexed as bodies. placedHold: the bodies are where the
// points were placed (ContactPoint::placed), whose pA and pB then serve as they are.
void writeContactRows(std::span<const ContactPoint> points, std::span<const RigidBody> bodies,
                      std::span<const Mat3> inverseInertiaWorld, const ContactSettings& settings, ConstraintRows& rows,
                      std::vector<std::uint64_t>& keys, bool placedHold = false);
// The deepest penetration of the points at the bodies' current poses (0 when none touches).
Real maxPenetration(std::span<const ContactPoint> points, std::span<const RigidBody> bodies);

class ContactSet {
public:
    // Call before the step changes velocities: each point's approach velocity, which decides
    // whether it bounces, is taken from the bodies as they are now.
    void gather(const std::vector<BodyContact>& manifolds, std::span<const RigidBody> bodies,
                std::span<const BodyMaterial> materials);
    // gather in parts: clear, then each manifold's points appended by add (as gather makes
    // them) or by keep: points an earlier gather made, kept (body-fixed, so valid at the bodies'
    // current poses) but for their approach velocities, taken anew from the bodies as they are
    // now at the midpoint of each point's pA and pB.
    void clear() { points_.clear(); }
    void add(const BodyContact& manifold, std::span<const RigidBody> bodies, std::span<const BodyMaterial> materials);
    void keep(std::span<const ContactPoint> points, std::span<const RigidBody> bodies);
    // keep without taking the approach velocities anew (they stay as they were made): for points
    // that only positions read (penetration, the position projection), never a velocity solve.
    void keepForPositions(std::span<const ContactPoint> points) {
        points_.insert(points_.end(), points.begin(), points.end());
    }
    std::span<const ContactPoint> points() const { return points_; }
    std::size_t size() const { return points_.size(); }

private:
    std::vector<ContactPoint> points_;
};

}  // namespace af
