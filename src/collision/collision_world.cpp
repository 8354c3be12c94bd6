#include "af/collision/collision_world.h"

#include "af/collision/narrowphase.h"

#include "shape_features.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

using collision_detail::BoxFeatures;

// The box around a body's shape at `pose`, grown by `margin`: for a box from its centre and
// extents (|R| · half), which is what the corners give, without placing eight of them.
Aabb worldBounds(const ConvexShape& shape, const RigidPose& pose, Real margin) {
    const BoxFeatures& box = shape.features().box;
    if (!box.valid) {
        return boundsOf(shape.polytope(), pose, margin);
    }
    const Vec3 centre = pose.apply(box.centre);
    const Mat3 axes = box.aligned ? pose.rotation : Mat3(pose.rotation * box.axes);
    const Vec3 extent = axes.cwiseAbs() * box.half + Vec3::Constant(margin);
    return {centre - extent, centre + extent};
}

// A lower bound of the height of the shape's lowest vertex above the plane (normal · vertex −
// offset): for a box from its centre and extents, less the rounding by which that can differ from
// the corners' own heights; for other shapes from the bounding sphere.
Real heightAbove(const ConvexShape& shape, const RigidPose& pose, const Vec3& sphereCentre, Real radius,
                 const Plane& plane) {
    const BoxFeatures& box = shape.features().box;
    if (!box.valid) {
        return plane.normal.dot(sphereCentre) - radius - plane.offset;
    }
    const Vec3 centre = pose.apply(box.centre);
    const Vec3 along = box.aligned ? Vec3(pose.rotation.transpose() * plane.normal)
                                   : Vec3((pose.rotation * box.axes).transpose() * plane.normal);
    const Real rounding = 1e-12 * (1 + std::abs(plane.offset) + centre.cwiseAbs().sum() + box.half.sum());
    return plane.normal.dot(centre) - along.cwiseAbs().dot(box.half) - plane.offset - rounding;
}

}  // namespace

int CollisionWorld::addBody(const Polytope& shape, const CollisionFilter& filter) {
    Body body{ConvexShape(shape), filter};
    const BoxFeatures& box = body.shape.features().box;
    body.centre = box.valid ? box.centre : body.shape.features().centre;
    for (const Vec3& v : shape.vertices) {
        body.radius = std::max(body.radius, (v - body.centre).norm());
    }
    bodies_.push_back(std::move(body));
    return static_cast<int>(bodies_.size()) - 1;
}

void CollisionWorld::excludePair(int a, int b) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    const auto at = std::lower_bound(excluded_.begin(), excluded_.end(), key);
    if (at == excluded_.end() || *at != key) excluded_.insert(at, key);
}

int CollisionWorld::addPlane(const Plane& plane, ContentsMask contents) {
    Static s;
    s.plane = plane;
    s.isPlane = true;
    s.contents = contents;
    statics_.push_back(std::move(s));
    return static_cast<int>(statics_.size()) - 1;
}

int CollisionWorld::addStatic(const Polytope& worldShape, ContentsMask contents) {
    Static s;
    s.shape = ConvexShape(worldShape);
    s.bounds = boundsOf(worldShape, RigidPose{}, 0);
    s.contents = contents;
    statics_.push_back(std::move(s));
    return static_cast<int>(statics_.size()) - 1;
}

void CollisionWorld::removeStatic(int staticShape) { statics_[static_cast<std::size_t>(staticShape)].removed = true; }

bool CollisionWorld::mayCollide(int a, int b) const {
    if (a == b) return false;
    const CollisionFilter& fa = bodies_[static_cast<std::size_t>(a)].filter;
    const CollisionFilter& fb = bodies_[static_cast<std::size_t>(b)].filter;
    if (!(fa.clipMask & fb.contents) && !(fb.clipMask & fa.contents)) return false;
    if (std::binary_search(excluded_.begin(), excluded_.end(), std::pair{std::min(a, b), std::max(a, b)}))
        return false;
    if (fa.figure == fb.figure) return fa.selfCollision && fb.selfCollision && !settings_.skipSelfCollision;
    return settings_.figuresCollide;
}

bool CollisionWorld::mayCollideWithStatic(int body, int staticShape) const {
    const CollisionFilter& f = bodies_[static_cast<std::size_t>(body)].filter;
    const Static& s = statics_[static_cast<std::size_t>(staticShape)];
    return f.collidesWithStatic && !s.removed && (f.clipMask & s.contents) != 0;
}

Manifold CollisionWorld::queryPair(int a, int b, const RigidPose& poseA, const RigidPose& poseB, const Vec3& centreA,
                                   const Vec3& centreB, Real pairMargin) const {
    const Body& bodyA = bodies_[static_cast<std::size_t>(a)];
    const Body& bodyB = bodies_[static_cast<std::size_t>(b)];
    // Bounding spheres farther apart than the margin: the query would find nothing.
    const Real reachBoth = (bodyA.radius + bodyB.radius + pairMargin) * (1 + 1e-12);
    if ((centreA - centreB).squaredNorm() > reachBoth * reachBoth) return {};
    return collide(bodyA.shape, poseA, bodyB.shape, poseB, pairMargin);
}

Manifold CollisionWorld::queryStatic(int a, int s, const RigidPose& pose, const Vec3& centre, const Aabb& bounds,
                                     Real staticMargin) const {
    const Static& shape = statics_[static_cast<std::size_t>(s)];
    const Body& body = bodies_[static_cast<std::size_t>(a)];
    if (shape.isPlane) {
        if (heightAbove(body.shape, pose, centre, body.radius, shape.plane) > staticMargin) return {};
        return collideWithPlane(body.shape.polytope(), pose, shape.plane, staticMargin);
    }
    if (!bounds.overlaps(shape.bounds)) return {};
    return collide(body.shape, pose, shape.shape, RigidPose{}, staticMargin);
}

void CollisionWorld::findContacts(std::span<const RigidPose> poses, std::span<const Vec3> moves,
                                  std::span<const Real> reach, Real margin, std::span<const std::uint8_t> awake,
                                  std::vector<BodyContact>& out) {
    out.clear();
    auto isAwake = [&](int i) { return awake.empty() || awake[static_cast<std::size_t>(i)] != 0; };
    auto at = [](const auto& items, int i) -> decltype(auto) { return items[static_cast<std::size_t>(i)]; };

    // Each box holds everything the body can reach in the step, so a pair's boxes overlap
    // whenever the pair can get within its margin.
    boxes_.resize(bodies_.size());
    centres_.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        boxes_[i] = worldBounds(bodies_[i].shape, poses[i], margin + reach[i] + moves[i].norm());
        centres_[i] = poses[i].apply(bodies_[i].centre);
    }
    broadphase_.findPairs(boxes_, pairs_);

    BodyContact contact;
    for (const auto& [a, b] : pairs_) {
        if (!isAwake(a) && !isAwake(b)) continue;
        if (!mayCollide(a, b)) continue;
        const Real pairMargin = margin + at(reach, a) + at(reach, b) + (at(moves, a) - at(moves, b)).norm();
        contact.manifold = queryPair(a, b, at(poses, a), at(poses, b), at(centres_, a), at(centres_, b), pairMargin);
        if (contact.manifold.empty()) continue;
        contact.bodyA = a;
        contact.bodyB = b;
        contact.staticShape = -1;
        out.push_back(contact);
    }
    for (int a = 0; a < static_cast<int>(bodies_.size()); ++a) {
        if (!isAwake(a)) continue;
        for (int s = 0; s < static_cast<int>(statics_.size()); ++s) {
            if (!mayCollideWithStatic(a, s)) continue;
            const Real staticMargin = margin + at(reach, a) + at(moves, a).norm();
            contact.manifold = queryStatic(a, s, at(poses, a), at(centres_, a), at(boxes_, a), staticMargin);
            if (contact.manifold.empty()) continue;
            contact.bodyA = a;
            contact.bodyB = kStaticWorld;
            contact.staticShape = s;
            out.push_back(contact);
        }
    }
}

void CollisionWorld::findContactsAgain(std::span<const RigidPose> poses, Real margin,
                                       std::vector<BodyContact>& contacts) const {
    auto placed = [&](int i) {
        const Body& body = bodies_[static_cast<std::size_t>(i)];
        const RigidPose& pose = poses[static_cast<std::size_t>(i)];
        return std::pair{pose.apply(body.centre), worldBounds(body.shape, pose, margin)};
    };
    std::size_t kept = 0;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        BodyContact& c = contacts[k];
        const auto [centreA, boundsA] = placed(c.bodyA);
        const RigidPose& poseA = poses[static_cast<std::size_t>(c.bodyA)];
        if (c.bodyB == kStaticWorld) {
            c.manifold = queryStatic(c.bodyA, c.staticShape, poseA, centreA, boundsA, margin);
        } else {
            const RigidPose& poseB = poses[static_cast<std::size_t>(c.bodyB)];
            c.manifold = queryPair(c.bodyA, c.bodyB, poseA, poseB, centreA, poseB.apply(bodies_[static_cast<std::size_t>(c.bodyB)].centre),
                                   margin);
        }
        if (!c.manifold.empty()) contacts[kept++] = c;
    }
    contacts.resize(kept);
}

}  // namespace af
