#pragma once
// Narrowphase: the contact manifold of two convex polytopes, or of a polytope and a plane.
//
// Frames and units: shapes are Polytopes in their body frames, placed in the world by RigidPoses
// (world = position + rotation·local); the manifold is in world space (see manifold.h for its
// sign conventions: normal from B towards A, depth > 0 penetrating). Lengths in file units.
//
// `margin` (≥ 0, file units; negative values count as 0) is the speculative distance: shapes
// farther apart than it get an empty manifold, closer ones get points with depth ≥ −margin, so
// that the solver can stop a gap from closing within one step.
//
// The normal and depth (choice made here): the best separating axis among the polytopes' face
// normals and edge×edge directions, each scored by the shapes' actual separation along it. For
// overlapping polytopes that is exact (the minimum translation is always along one of them): a
// box resting on a box gets its face normal to the last bit and the depth is exact. Edge pairs
// are pruned on the Gauss map, so this costs O(faces × vertices + edge groups × edges).
// libccd answers what the axes cannot: whether shapes that no axis separates by more than the
// margin are really within it (the axes only bound the distance from below: two corners), and,
// for two flat shapes (whose axes can miss a gap within their common plane), a direction. It
// runs MPR on A grown by the margin, then GJK+EPA if MPR's direction is unusable, then the line
// between the centres: never NaN. Its approximate direction is used only where it separates the
// shapes more than every feature axis does. Overlapping solid shapes never reach libccd, so its
// face-to-face (libccd#25) and large-box (libccd#17) failures cannot show.
//
// Points: a face axis clips the incident face (on the other shape, around its deepest vertex, the
// face most opposed to the normal) against the side planes of the reference face, keeps the
// points within the margin and reduces them to four (deepest first, then the largest area). An
// edge-pair axis gives the edges' closest points, unless both shapes have a face within 25° of
// the axis (a box tilted over a ledge): then those faces are clipped as for a face axis, with
// separations measured along the axis. Each point sits midway between the two surfaces; its id
// names the features that made it (contact_ids in src/collision), stable while they stay in touch.
//
// Cost and allocation: per-thread buffers grow to the largest shapes seen and are reused, so once
// warmed up a query allocates nothing. Preparing a ConvexShape once saves the pose-independent half
// of the work. Polytopes without vertices give an empty manifold.

#include "af/collision/manifold.h"
#include "af/geometry/polytope.h"

#include <memory>
#include <span>

namespace af {

namespace collision_detail {
struct ShapeFeatures;
}

/// A polytope prepared for the narrowphase: what collide() needs of it that does not depend on the
/// pose (the faces at each edge, each edge's normal cone, the edges grouped by direction), worked
/// out once here instead of in every query. Building one allocates; copies share the prepared part.
class ConvexShape {
public:
    ConvexShape();
    explicit ConvexShape(Polytope polytope);

    const Polytope& polytope() const { return polytope_; }
    const collision_detail::ShapeFeatures& features() const { return *features_; }

private:
    Polytope polytope_;
    std::shared_ptr<const collision_detail::ShapeFeatures> features_;
};

/// Contact manifold of A and B. Normal from B towards A; empty when farther apart than `margin`.
Manifold collide(const ConvexShape& a, const RigidPose& poseA, const ConvexShape& b, const RigidPose& poseB,
                 Real margin);

/// The same for polytopes not prepared: each query prepares both first (roughly doubling the cost
/// of a box–box query).
Manifold collide(const Polytope& a, const RigidPose& poseA, const Polytope& b, const RigidPose& poseB,
                 Real margin);

/// Contact manifold of A against a plane (B is the plane, its solid side below): the normal is the
/// plane's normal, the points are A's vertices closer to the plane than `margin` (at most four),
/// and each point's id is its vertex index.
Manifold collideWithPlane(const Polytope& a, const RigidPose& poseA, const Plane& plane, Real margin);

/// How deep any of `shapes` (body frames, placed at `poses`) reaches into any of `statics` (world
/// space, e.g. a map's brushes): the largest penetration of their contact manifolds, 0 when none
/// overlaps. What a spawn asks before it lets a figure go (Doom's af_testSolid asks it of a
/// ragdoll started from an animated pose).
Real deepestOverlap(std::span<const Polytope> shapes, std::span<const RigidPose> poses, std::span<const Polytope> statics);

}  // namespace af
