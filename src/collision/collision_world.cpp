#include "af/collision/collision_world.h"

#include "af/collision/narrowphase.h"

#include "plane_contact.h"
#include "shape_features.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

using collision_detail::BoxFeatures;

// The box around a body's shape at `pose`, grown by `margin`: for a box from its centre and
// extents (|R| · half), which is what the corners give, without placing eight of them. `centre`
// is the box's centre placed by `pose` (for other shapes it is not used).
Aabb worldBounds(const ConvexShape& shape, const RigidPose& pose, const Vec3& centre, Real margin) {
    const BoxFeatures& box = shape.features().box;
    if (!box.valid) {
        return boundsOf(shape.polytope(), pose, margin);
    }
    const Vec3 extent = (box.aligned ? pose.rotation.cwiseAbs() * box.half
                                     : Mat3(pose.rotation * box.axes).cwiseAbs() * box.half) +
                        Vec3::Constant(margin);
    return {centre - extent, centre + extent};
}

// A lower bound of the height of the shape's lowest vertex above the plane (normal · vertex −
// offset), from its bounding sphere: for shapes too large for smallPlaneContact, which a far plane
// then spares looking at every vertex.
Real heightAbove(const Vec3& sphereCentre, Real radius, const Plane& plane) {
    return plane.normal.dot(sphereCentre) - radius - plane.offset;
}

}  // namespace

int CollisionWorld::addBody(const Polytope& shape, const CollisionFilter& filter) {
    Body body;
    body.shape = ConvexShape(shape);
    body.filter = filter;
    const BoxFeatures& box = body.shape.features().box;
    body.centre = box.valid ? box.centre : body.shape.features().centre;
    for (const Vec3& v : shape.vertices) {
        body.radius = std::max(body.radius, (v - body.centre).norm());
    }
    bodies_.push_back(std::move(body));
    ++version_;
    return static_cast<int>(bodies_.size()) - 1;
}

void CollisionWorld::removeBodies(int first, int count) {
    const auto at = bodies_.begin() + first;
    bodies_.erase(at, at + count);
    for (Body& body : bodies_) {
        std::vector<int>& with = body.excludedWith;
        std::erase_if(with, [&](int b) { return b >= first && b < first + count; });
        for (int& b : with)
            if (b >= first + count) b -= count;
    }
    broadphase_ = SweepAndPrune{};  // its order names bodies by index
    ++version_;
}

void CollisionWorld::excludePair(int a, int b) {
    auto exclude = [&](int body, int other) {
        std::vector<int>& with = bodies_[static_cast<std::size_t>(body)].excludedWith;
        if (std::find(with.begin(), with.end(), other) == with.end()) with.push_back(other);
    };
    exclude(a, b);
    exclude(b, a);
    ++version_;
}

int CollisionWorld::addPlane(const Plane& plane, ContentsMask contents) {
    Static s;
    s.plane = plane;
    s.isPlane = true;
    s.contents = contents;
    statics_.push_back(std::move(s));
    ++version_;
    return static_cast<int>(statics_.size()) - 1;
}

int CollisionWorld::addStatic(const Polytope& worldShape, ContentsMask contents) {
    Static s;
    s.shape = ConvexShape(worldShape);
    s.bounds = boundsOf(worldShape, RigidPose{}, 0);
    s.contents = contents;
    statics_.push_back(std::move(s));
    ++version_;
    return static_cast<int>(statics_.size()) - 1;
}

void CollisionWorld::removeStatic(int staticShape) {
    statics_[static_cast<std::size_t>(staticShape)].removed = true;
    ++version_;
}

bool CollisionWorld::mayCollide(int a, int b) const {
    if (a == b) return false;
    const CollisionFilter& fa = bodies_[static_cast<std::size_t>(a)].filter;
    const CollisionFilter& fb = bodies_[static_cast<std::size_t>(b)].filter;
    if (!(fa.clipMask & fb.contents) && !(fb.clipMask & fa.contents)) return false;
    const std::vector<int>& excluded = bodies_[static_cast<std::size_t>(a)].excludedWith;
    if (std::find(excluded.begin(), excluded.end(), b) != excluded.end()) return false;
    if (fa.figure == fb.figure) return fa.selfCollision && fb.selfCollision && !settings_.skipSelfCollision;
    return settings_.figuresCollide;
}

bool CollisionWorld::mayCollideWithStatic(int body, int staticShape) const {
    const CollisionFilter& f = bodies_[static_cast<std::size_t>(body)].filter;
    const Static& s = statics_[static_cast<std::size_t>(staticShape)];
    return f.collidesWithStatic && !s.removed && (f.clipMask & s.contents) != 0;
}

bool CollisionWorld::queryPair(int a, int b, const RigidPose& poseA, const RigidPose& poseB, const Vec3& centreA,
                               const Vec3& centreB, Real pairMargin, Manifold& out) const {
    const Body& bodyA = bodies_[static_cast<std::size_t>(a)];
    const Body& bodyB = bodies_[static_cast<std::size_t>(b)];
    // Bounding spheres farther apart than the margin: the query would find nothing.
    const Real reachBoth = (bodyA.radius + bodyB.radius + pairMargin) * (1 + 1e-12);
    if ((centreA - centreB).squaredNorm() > reachBoth * reachBoth) return false;
    out = collide(bodyA.shape, poseA, bodyB.shape, poseB, pairMargin);
    return !out.empty();
}

bool CollisionWorld::queryPlane(int a, const Plane& plane, const RigidPose& pose, Real staticMargin,
                                Manifold& out) const {
    const Body& body = bodies_[static_cast<std::size_t>(a)];
    const Polytope& shape = body.shape.polytope();
    if (shape.vertices.size() <= std::size_t(collision_detail::kSmallPolytope)) {
        return collision_detail::smallPlaneContact(body.shape, pose, plane, staticMargin, out);
    }
    if (heightAbove(pose.apply(body.centre), body.radius, plane) > staticMargin) return false;
    out = collideWithPlane(shape, pose, plane, staticMargin);
    return !out.empty();
}

bool CollisionWorld::queryBrush(int a, int s, const RigidPose& pose, const Aabb& bounds, Real staticMargin,
                                Manifold& out) const {
    const Static& brush = statics_[static_cast<std::size_t>(s)];
    if (!bounds.overlaps(brush.bounds)) return false;
    out = collide(bodies_[static_cast<std::size_t>(a)].shape, pose, brush.shape, RigidPose{}, staticMargin);
    return !out.empty();
}

void CollisionWorld::findContacts(std::span<const RigidPose> poses, std::span<const Vec3> moves,
                                  std::span<const Real> reach, Real margin, std::span<const std::uint8_t> awake,
                                  std::vector<BodyContact>& out) {
    auto isAwake = [&](int i) { return awake.empty() || awake[static_cast<std::size_t>(i)] != 0; };
    auto at = [](const auto& items, int i) -> decltype(auto) { return items[static_cast<std::size_t>(i)]; };

    // Each box holds everything the body can reach in the step, so a pair's boxes overlap
    // whenever the pair can get within its margin.
    boxes_.resize(bodies_.size());
    centres_.resize(bodies_.size());
    staticMargins_.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        staticMargins_[i] = margin + reach[i] + moves[i].norm();
        centres_[i] = poses[i].apply(bodies_[i].centre);  // a box's centre (addBody)
        boxes_[i] = worldBounds(bodies_[i].shape, poses[i], centres_[i], staticMargins_[i]);
    }
    broadphase_.findPairs(boxes_, pairs_);

    // Each query writes into the next slot of `out`, which is kept only when it found points: no
    // manifold is copied, and once `out` has held as many contacts none is constructed either.
    std::size_t used = 0;
    auto slot = [&]() -> BodyContact& {
        if (out.size() == used) out.emplace_back();
        return out[used];
    };
    for (const auto& [a, b] : pairs_) {
        if (!isAwake(a) && !isAwake(b)) continue;
        if (!mayCollide(a, b)) continue;
        const Real pairMargin = margin + at(reach, a) + at(reach, b) + (at(moves, a) - at(moves, b)).norm();
        BodyContact& contact = slot();
        if (!queryPair(a, b, at(poses, a), at(poses, b), at(centres_, a), at(centres_, b), pairMargin, contact.manifold))
            continue;
        contact.bodyA = a;
        contact.bodyB = b;
        contact.staticShape = -1;
        ++used;
    }
    for (int a = 0; a < static_cast<int>(bodies_.size()); ++a) {
        if (!isAwake(a)) continue;
        for (int s = 0; s < static_cast<int>(statics_.size()); ++s) {
            if (!mayCollideWithStatic(a, s)) continue;
            const Static& shape = at(statics_, s);
            BodyContact& contact = slot();
            const bool found = shape.isPlane
                                   ? queryPlane(a, shape.plane, at(poses, a), at(staticMargins_, a), contact.manifold)
                                   : queryBrush(a, s, at(poses, a), at(boxes_, a), at(staticMargins_, a), contact.manifold);
            if (!found) continue;
            contact.bodyA = a;
            contact.bodyB = kStaticWorld;
            contact.staticShape = s;
            ++used;
        }
    }
    out.resize(used);
}

void CollisionWorld::findContactsAgain(std::span<const RigidPose> poses, Real margin,
                                       std::vector<BodyContact>& contacts) const {
    auto pose = [&](int i) -> const RigidPose& { return poses[static_cast<std::size_t>(i)]; };
    auto centre = [&](int i) { return pose(i).apply(bodies_[static_cast<std::size_t>(i)].centre); };
    std::size_t kept = 0;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        BodyContact& c = contacts[k];
        bool found = false;
        if (c.bodyB != kStaticWorld) {
            found = queryPair(c.bodyA, c.bodyB, pose(c.bodyA), pose(c.bodyB), centre(c.bodyA), centre(c.bodyB), margin,
                              c.manifold);
        } else if (const Static& shape = statics_[static_cast<std::size_t>(c.staticShape)]; shape.isPlane) {
            found = queryPlane(c.bodyA, shape.plane, pose(c.bodyA), margin, c.manifold);
        } else {
            const Aabb bounds =
                worldBounds(bodies_[static_cast<std::size_t>(c.bodyA)].shape, pose(c.bodyA), centre(c.bodyA), margin);
            found = queryBrush(c.bodyA, c.staticShape, pose(c.bodyA), bounds, margin, c.manifold);
        }
        if (found) {
            if (kept != k) contacts[kept] = c;
            ++kept;
        }
    }
    contacts.resize(kept);
}

}  // namespace af
