#include "contact_set.h"

#include <algorithm>
#include <array>

namespace af {

namespace {

// splitmix64's finaliser: spreads the identifying numbers over the whole key.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

Vec3 toLocal(const RigidBody* body, const Vec3& world) {
    return body ? Vec3(body->orientation.conjugate() * (world - body->position)) : world;
}

using contact_detail::bodyOrNull;
using contact_detail::toWorld;

}  // namespace

std::uint64_t contactPairKey(const BodyContact& c) {
    return mix(mix(static_cast<std::uint64_t>(c.bodyA)) ^
               static_cast<std::uint64_t>(c.bodyB == kStaticWorld ? (1ull << 32) + static_cast<std::uint64_t>(c.staticShape)
                                                                  : static_cast<std::uint64_t>(c.bodyB)));
}

std::uint64_t contactPointKey(std::uint64_t pairKey, const ManifoldPoint& point) { return mix(pairKey ^ point.id); }

void ContactSet::gather(const std::vector<BodyContact>& manifolds, std::span<const RigidBody> bodies,
                        std::span<const BodyMaterial> materials) {
    points_.clear();
    for (const BodyContact& c : manifolds) add(c, bodies, materials);
}

void ContactSet::add(const BodyContact& c, std::span<const RigidBody> bodies, std::span<const BodyMaterial> materials) {
    const int bodyB = c.bodyB == kStaticWorld ? kWorldBody : c.bodyB;
    const BodyMaterial& material = materials[static_cast<std::size_t>(c.bodyA)];
    // Doom: μ is body A's, lowered to B's when B's is lower.
    Real friction = material.friction;
    if (bodyB != kWorldBody) friction = std::min(friction, materials[static_cast<std::size_t>(bodyB)].friction);
    const std::uint64_t pairKey = contactPairKey(c);
    const RigidBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
    const RigidBody* b = bodyOrNull(bodies, bodyB);
    const Vec3& n = c.manifold.normal;
    // By feature id, not as the manifold lists them (deepest first, which swaps between
    // equally deep corners of a resting box): rows in the same order step after step.
    // (Insertion by hand: std::sort on a four-element array trips GCC's -Warray-bounds.)
    std::array<int, Manifold::kMaxPoints> order{};
    const auto idOf = [&](int i) { return c.manifold.points[static_cast<std::size_t>(i)].id; };
    for (int i = 0; i < c.manifold.count; ++i) {
        int at = i;
        for (; at > 0 && idOf(order[static_cast<std::size_t>(at - 1)]) > idOf(i); --at)
            order[static_cast<std::size_t>(at)] = order[static_cast<std::size_t>(at - 1)];
        order[static_cast<std::size_t>(at)] = i;
    }
    for (int k = 0; k < c.manifold.count; ++k) {
        const ManifoldPoint& m = c.manifold.points[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
        ContactPoint& p = points_.emplace_back();
        p.bodyA = c.bodyA;
        p.bodyB = bodyB;
        p.normal = n;
        // Separation n·(pA − pB) = −depth, split evenly about the reported midpoint.
        p.localA = toLocal(&a, m.point - n * (m.depth / 2));
        p.localB = toLocal(b, m.point + n * (m.depth / 2));
        p.friction = friction;
        p.restitution = material.bounciness;
        p.frictionDirection = material.frictionDirection;
        p.key = contactPointKey(pairKey, m);
        // v_A − 0 is v_A bit for bit, so the world's side is left out.
        p.approachVelocity = b ? n.dot(a.velocityAt(m.point) - b->velocityAt(m.point)) : n.dot(a.velocityAt(m.point));
    }
}

void ContactSet::keep(std::span<const ContactPoint> points, std::span<const RigidBody> bodies) {
    for (const ContactPoint& kept : points) {
        ContactPoint& p = points_.emplace_back(kept);
        const RigidBody& a = bodies[static_cast<std::size_t>(p.bodyA)];
        const RigidBody* b = bodyOrNull(bodies, p.bodyB);
        p.placed = true;
        p.onA = toWorld(&a, p.localA);
        p.onB = toWorld(b, p.localB);
        const Vec3 at = (p.onA + p.onB) / 2;
        p.approachVelocity = b ? p.normal.dot(a.velocityAt(at) - b->velocityAt(at)) : p.normal.dot(a.velocityAt(at));
    }
}

Real currentDepth(const ContactPoint& p, std::span<const RigidBody> bodies) {
    const Vec3 onA = toWorld(bodyOrNull(bodies, p.bodyA), p.localA);
    const Vec3 onB = toWorld(bodyOrNull(bodies, p.bodyB), p.localB);
    return -p.normal.dot(onA - onB);
}

Real maxPenetration(std::span<const ContactPoint> points, std::span<const RigidBody> bodies) {
    Real worst = 0;
    for (const ContactPoint& p : points) worst = std::max(worst, currentDepth(p, bodies));
    return worst;
}

}  // namespace af
