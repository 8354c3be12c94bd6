#pragma once
// The collision stage's world: every body's convex shape with its filter, the static world
// (planes and convex brushes), and one query per step that returns the contact manifolds of
// every pair that may collide.
//
// Which pairs collide (docs/doom-physics.md §4.8), in order:
//  * a body with clipMask 0 collides with nothing; otherwise A and B collide when A's clipMask
//    meets B's contents or B's clipMask meets A's contents (the static world: its contents);
//  * two bodies joined by a constraint other than a spring never collide (excludePair), and a
//    body joined to the world that way ignores the static world;
//  * two bodies of the same figure collide only when both have selfCollision (the figure's and
//    the body's flag together);
//  * bodies of different figures collide, unlike Doom, where a ragdoll's clip models are disabled
//    between steps so that two ragdolls pass through each other. A pile of ragdolls must pile up;
//    CollisionSettings::figuresCollide = false restores Doom's behaviour.
//
// Frames and units: shapes in their body frame (centre of mass at the origin), poses body →
// world, static shapes in world space; file units.

#include "af/collision/broadphase.h"
#include "af/collision/manifold.h"
#include "af/collision/narrowphase.h"
#include "af/text/decl_af.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace af {

inline constexpr int kStaticWorld = -1;  // BodyContact::bodyB of a contact with the static world

struct CollisionFilter {
    int figure = 0;             // bodies of one figure share this number
    bool selfCollision = true;  // the figure's and the body's selfCollision, both
    ContentsMask contents = 0;
    ContentsMask clipMask = 0;
    bool collidesWithStatic = true;  // false for a body joined to the world by a non-spring constraint
};

struct CollisionSettings {
    bool figuresCollide = true;  // false: Doom's behaviour, different figures pass through each other
    bool skipSelfCollision = false;  // Doom's af_skipSelfCollision: a figure's bodies pass through each other
};

struct BodyContact {
    int bodyA = 0;               // always a body
    int bodyB = kStaticWorld;    // a body (> bodyA), or kStaticWorld
    int staticShape = -1;        // the static plane or brush, when bodyB is kStaticWorld
    Manifold manifold;           // normal from B towards A
};

class CollisionWorld {
public:
    explicit CollisionWorld(const CollisionSettings& settings = {}) : settings_(settings) {}

    // Returns the body's index; bodies are numbered in the order they are added, as the caller's
    // rigid bodies are.
    int addBody(const Polytope& shape, const CollisionFilter& filter);
    // Removes bodies first … first + count − 1; the bodies after them move down by count, as the
    // caller's rigid bodies do.
    void removeBodies(int first, int count);
    // Bodies joined by a (non-spring) constraint.
    void excludePair(int a, int b);
    // Static shapes; both kinds share one numbering (BodyContact::staticShape).
    int addPlane(const Plane& plane, ContentsMask contents = contents::Solid);
    int addStatic(const Polytope& worldShape, ContentsMask contents = contents::Solid);
    // A removed static shape keeps its number (so contacts and callers' indices stay valid) and
    // collides with nothing.
    void removeStatic(int staticShape);

    std::size_t bodyCount() const { return bodies_.size(); }
    // Changes with every call that changes what findContacts can find (adding bodies or statics,
    // excluding pairs, removing statics), so that a caller may keep an answer while it holds.
    std::uint64_t version() const { return version_; }
    std::size_t staticCount() const { return statics_.size(); }
    const Polytope& bodyShape(int body) const { return bodies_[static_cast<std::size_t>(body)].shape.polytope(); }
    const CollisionFilter& filter(int body) const { return bodies_[static_cast<std::size_t>(body)].filter; }
    const CollisionSettings& settings() const { return settings_; }
    // New rules for which pairs may touch; changes version().
    void setSettings(const CollisionSettings& settings) {
        settings_ = settings;
        ++version_;
    }

    // Whether a and b may touch at all (the rules above), and a body and the static world.
    bool mayCollide(int a, int b) const;
    bool mayCollideWithStatic(int body, int staticShape) const;

    // The manifolds of every pair closer than their margin, at the given poses (one per body).
    // The margin is how far apart two shapes may be and still get contact points, so that the
    // solver can stop a gap closing within the step: `margin`, plus each body's `reach` (how far
    // its turning can carry its surface in the step), plus how far the two close in on each other
    // by their `moves` (each body's displacement over the step; a static shape does not move).
    // Bodies falling side by side therefore get no contacts from their common speed. Pairs whose
    // bodies are all asleep (awake[i] == 0) are skipped; an empty `awake` means all are awake.
    // Output order: body pairs (a, b) sorted, then each body against the statics in body order —
    // deterministic.
    void findContacts(std::span<const RigidPose> poses, std::span<const Vec3> moves, std::span<const Real> reach,
                      Real margin,
                      std::span<const std::uint8_t> awake, std::vector<BodyContact>& out);
    // The pairs of `contacts` (a findContacts answer) queried again at `poses` within `margin`, none
    // of them moving; those no longer within it are dropped, the order kept. This is findContacts'
    // answer for those poses and margin (no moves or reach) whenever no other pair can have come
    // within the margin since `contacts` were found: the caller's to know, e.g. when every awake
    // body moved less than half the margin the contacts were found with (asleep ones not at all).
    void findContactsAgain(std::span<const RigidPose> poses, Real margin, std::vector<BodyContact>& contacts) const;

private:
    // Shapes are prepared once for the narrowphase (ConvexShape), which halves a query's cost.
    // The bounding sphere (body frame) lets a pair farther apart than its margin skip the query.
    struct Body {
        ConvexShape shape;
        CollisionFilter filter;
        Vec3 centre = Vec3::Zero();
        Real radius = 0;
        std::vector<int> excludedWith;  // bodies joined to this one (excludePair), a handful at most
    };
    struct Static {
        ConvexShape shape;  // world space; empty for a plane
        Plane plane;
        bool isPlane = false;
        Aabb bounds;
        ContentsMask contents = 0;
        bool removed = false;
    };

    // Each query writes the manifold it finds into `out` and returns whether it has points; `out`
    // is left unspecified when not.
    bool queryPair(int a, int b, const RigidPose& poseA, const RigidPose& poseB, const Vec3& centreA,
                   const Vec3& centreB, Real pairMargin, Manifold& out) const;
    bool queryPlane(int a, const Plane& plane, const RigidPose& pose, Real staticMargin, Manifold& out) const;
    // bounds: the body's box grown by the margin.
    bool queryBrush(int a, int s, const RigidPose& pose, const Aabb& bounds, Real staticMargin, Manifold& out) const;

    CollisionSettings settings_;
    std::vector<Body> bodies_;
    std::vector<Static> statics_;
    SweepAndPrune broadphase_;
    std::vector<Aabb> boxes_;
    std::vector<Vec3> centres_;  // world centres of the bounding spheres, per findContacts call
    std::vector<Real> staticMargins_;  // each body's margin against the static world, likewise
    std::vector<std::pair<int, int>> pairs_;
    std::uint64_t version_ = 0;
};

}  // namespace af
