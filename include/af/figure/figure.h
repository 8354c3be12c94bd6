#pragma once
// A figure: an .af decl made concrete against a skeleton pose (docs/figures.md).
//
// Every body has its reference point at its centre of mass (as in Doom). Poses and constraint
// vectors are in world space at spawn: the decl's model-space values (resolved against the
// af_pose skeleton) moved by the spawn placement, world = placement.position +
// placement.rotation * model. Lengths in file units, masses in the file's mass units, angles of
// limits in degrees as written. Directions (axes, shafts) are unit vectors.

#include "af/figure/skeleton.h"
#include "af/geometry/polytope.h"
#include "af/geometry/shapes.h"
#include "af/text/decl_af.h"
#include "af/text/diagnostics.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace af {

struct FigureBody {
    std::string name;
    ShapeKind shapeKind = ShapeKind::box;
    int sides = 0;                   // cylinder and cone: sides actually built
    Polytope shape;                  // body frame, centre of mass at the origin
    Real volume = 0;
    Real mass = 0;                   // after totalMass scaling
    Mat3 inertia = Mat3::Identity(); // about the centre of mass, body frame, inertiaScale applied
    RigidPose pose;                  // world pose at spawn (position = centre of mass)

    // How the body drives the skeleton (docs/figures.md §3.6): the joint, and the body's pose in that joint's
    // frame at the af_pose. The root body drives the first child of the `origin` joint.
    int joint = -1;
    JointMod mod = JointMod::Orientation;
    RigidPose bodyInJoint;
    std::vector<int> containedJoints;  // skeleton joints whose hits land on this body

    Real linearFriction = 0;
    Real angularFriction = 0;
    Real contactFriction = 0;
    Real bounciness = 0.4;  // Doom's physics default; .af files cannot set it
    ContentsMask contents = 0;
    ContentsMask clipMask = 0;
    bool selfCollision = true;
    std::optional<Vec3> frictionDirection;      // body frame, as resolved (not normalised)
    std::optional<Vec3> contactMotorDirection;  // body frame
    SourceLocation where;
};

inline constexpr int kWorld = -1;  // a constraint's body index meaning "the world"

struct FigureConstraint {
    ConstraintType type = ConstraintType::Fixed;
    std::string name;
    int body1 = 0;
    int body2 = kWorld;
    Vec3 anchor = Vec3::Zero();   // world; spring: anchor1
    Vec3 anchor2 = Vec3::Zero();  // spring only: world
    Vec3 axis = Vec3::UnitX();    // hinge, slider
    Vec3 shafts[2] = {Vec3::UnitZ(), Vec3::UnitZ()};  // universal: both; ball and socket: [0] (limit)
    LimitType limit = LimitType::None;
    Vec3 limitAxis = -Vec3::UnitZ();
    Real3 limitAngles{};
    Real friction = 0;
    // Ball and socket, our extension (not in Doom's decl, so .af files leave it 0): the shaft
    // may twist about itself up to this many degrees either way from its spawn twist.
    Real twistLimit = 0;
    // Universal joint, our extension (Doom's decl knows only its homokinetic joint): a Cardan
    // (Hooke) cross instead. shafts[0] is then the cross's arm carried by body1, shafts[1] its arm
    // carried by body2, ⟂ at spawn, and the joint keeps them ⟂. Its two angles, right-handed and
    // 0 at spawn, are body1's turn relative to body2 about body2's arm, then about its own; each
    // stays within [cardanLower[k], cardanUpper[k]] degrees (k = 0: about body2's arm, 1: about
    // body1's arm) where lower < upper. `limit` is not read for a Cardan joint.
    bool cardan = false;
    std::array<Real, 2> cardanLower{}, cardanUpper{};
    Real stretch = 0, compress = 0, damping = 0, restLength = 0, minLength = 0, maxLength = 0;
    SourceLocation where;
};

struct Figure {
    std::string name;
    AFSettings settings;
    std::vector<FigureBody> bodies;  // body 0 is the root (joint "origin")
    std::vector<FigureConstraint> constraints;
    Skeleton afPose;                 // model space
    RigidPose placement;             // model → world at spawn
    std::vector<int> jointBody;      // per skeleton joint: the body whose containedJoints hold it, or -1

    Real totalMass() const;
    int findBody(std::string_view bodyName) const;
};

struct FigureResult {
    std::optional<Figure> figure;        // empty when an error was found
    std::vector<Diagnostic> diagnostics; // errors and warnings, each with its file and position

    bool ok() const { return figure.has_value(); }
    std::string formatDiagnostics() const;
};

// Builds the figure of `decl` against the af_pose skeleton and places it. `afFile` names the .af
// file in diagnostics. Warnings flag what usually makes figures misbehave (docs/doom-quirks.md): unknown
// joints, mass ratios above 1:20 between jointed bodies, inertia tensors with principal moments
// more than 20 apart, jointed bodies overlapping at spawn, bodies in more than one tree.
FigureResult buildFigure(const DeclAF& decl, const Skeleton& afPose, const std::string& afFile,
                         const RigidPose& placement = {});

struct AFResources;
// The af_pose skeleton of resolved resources (docs/formats.md §2.3): frame 0 of the model's
// `anim af_pose`, with the model's `offset` added to the root.
Skeleton afPoseSkeleton(const AFResources& resources);
// The figure of resolved resources (ResourceIndex::resolveAFEntity or resolveFigure, which must
// be ok()) on their af_pose, in model space: the definition every instance of it shares.
FigureResult buildFigure(const AFResources& resources);

// The figure moved rigidly by `placement`, after its own: body poses, constraint vectors, and
// `placement` itself (placement * figure.placement). Building a figure at the identity and placing
// it gives the figure built at that placement, to rounding.
Figure placeFigure(const Figure& figure, const RigidPose& placement);

// The lowest and highest z of the figure's shapes moved by `placement`: how far to lift a figure so
// that it stands on a floor, and where the next of a pile goes.
struct HeightRange {
    Real lowest = 0;
    Real highest = 0;
};
HeightRange heightRange(const Figure& figure, const RigidPose& placement = {});

// The groups of bodies joined by constraints (to the world or not), each in body order; a
// well-formed figure is one tree. Groups are ordered by their first body.
std::vector<std::vector<int>> bodyTrees(const Figure& figure);

// One of the warnings buildFigure gives about a figure that tends to misbehave (mass ratio across
// a constraint, lopsided inertia, jointed bodies overlapping, separate trees), with what it is
// about, so that an editor can show it beside that body or constraint.
struct FigureWarning {
    enum class Subject : std::uint8_t { Body, Constraint, Figure };
    Subject subject = Subject::Figure;
    int index = -1;  // into Figure::bodies or Figure::constraints; -1 for the whole figure
    std::string message;
};
// The warnings of a built figure, bodies first, then constraints, then the figure; buildFigure
// reports the same ones as diagnostics at the body's or constraint's place in the file.
std::vector<FigureWarning> figureWarnings(const Figure& figure);

// The skeleton the bodies pose (docs/figures.md §3.6), in world space: driven joints follow their bodies as
// their `mod` says, every other joint follows its parent with its af_pose local transform, and
// the root joint follows body 0. `bodyPoses` holds one world pose per body.
Skeleton poseSkeleton(const Figure& figure, const std::vector<RigidPose>& bodyPoses);

// The joints of a containedJoints list (docs/formats.md §1.6): `name`, `*name` (with descendants), `-name`
// and `-*name` (removals), left to right, case-insensitive. Unknown names are returned in `unknown`.
std::vector<int> expandJointList(const Skeleton& skeleton, std::string_view list,
                                 std::vector<std::string>* unknown = nullptr);

}  // namespace af
