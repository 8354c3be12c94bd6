#pragma once
// af-gen: an articulated figure made from an md5mesh skeleton and its mesh (issue 31,
// docs/af-gen.md). Four steps, one file each:
//   gen_bodies.cpp       joints grouped into bodies;
//   gen_shapes.cpp       each body's shape sized from the vertices weighted mostly to its
//                        joints, or from its bone when it has none, and its mass;
//   gen_constraints.cpp  a constraint per body, its kind from the bone's name and place in the
//                        tree, its limits built from the af_pose;
//   gen_figure.cpp       the .af decl those make, through the same data the parser produces.
// Everything is in the af_pose's model space (docs/formats.md §2.3): +x forward, +y left, +z up
// (docs/conventions.md §0.2), the axes a figure's natural bends are told by.

#include "af/figure/skeleton.h"
#include "af/text/decl_af.h"
#include "af/text/md5_skin.h"

#include <algorithm>
#include <string>
#include <vector>

namespace af::gen {

// The af_pose's forward and up (docs/conventions.md §0.2).
inline const Vec3 kForward = Vec3::UnitX();
inline const Vec3 kUp = Vec3::UnitZ();

// `v` as the .af text spells it: at float precision (the writer's), a component below 1e-6 as
// the zero it means.
AFVector literal(const Vec3& v);

// Whether a lower-case bone name contains any of `parts` (C strings): "l_thigh" has "thigh".
bool nameHas(const std::string& lowerName, const auto& parts) {
    return std::any_of(parts.begin(), parts.end(),
                       [&](const char* part) { return lowerName.find(part) != std::string::npos; });
}

struct GenOptions {
    std::string name;                // the decl, model and entityDef name
    std::vector<std::string> keep;   // joints that get a body of their own, whatever their size
    std::vector<std::string> merge;  // joints their parent's body contains, whatever their size
    Real totalMass = 0;              // the figure's mass; 0: from its size, as our humanoid's
};

// A vertex of the mesh placed on the af_pose, and the joint that carries most of its weight.
struct MeshPoint {
    Vec3 position = Vec3::Zero();
    int joint = -1;
};

// Every vertex of every mesh block, placed on `afPose` (the skin's skeleton) as md5_skin.h says.
std::vector<MeshPoint> meshPoints(const std::vector<Md5SkinSection>& skin, const Skeleton& afPose);

// A body's shape in model space: a frame at the joint the body drives, its z axis along the bone,
// and the shape's bounds in that frame.
struct GenShape {
    ShapeType type = ShapeType::Box;
    Mat3 rotation = Mat3::Identity();  // columns: the body's x, y, z axes
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();
    int meshVertices = 0;              // vertices that sized it; 0: sized from its bone
};

struct GenBody {
    std::string name;         // its joint's name
    int joint = -1;           // the joint it drives; the root body: the `origin` joint's child
    int parent = -1;          // the body it hangs on; -1 for the root body (body 0)
    std::vector<int> joints;  // the joints it contains, in skeleton order
    std::vector<int> children;
    Vec3 boneEnd = Vec3::Zero();  // model space; boneEnd − joint position is its bone
    GenShape shape;
    Real mass = 0;
};

// The figure's largest extent along an axis, over its joints (but `origin`) and vertices; at
// least 1. The size that "tiny", a shape's least width and the default mass are measured by.
Real figureSize(const Skeleton& afPose, const std::vector<MeshPoint>& points);

// The joint that an `origin` body drives (docs/figures.md §3.6): the first child of the joint
// named `origin`, or of joint 0 when there is none; that joint and its ancestors are the root
// body's. Throws std::invalid_argument when it has no child.
int rootJoint(const Skeleton& skeleton);

// Groups the joints into bodies: a body for every joint that carries mesh weight or has children,
// unless it is a tiny or end part (docs/af-gen.md, "Bodies"); every other joint is contained by
// its nearest ancestor's body. Body 0 is the root body; the others follow in skeleton order.
// Every joint is contained by exactly one body. Throws std::invalid_argument for a --keep or
// --merge name that is no joint, or a joint named in both.
std::vector<GenBody> groupJoints(const Skeleton& afPose, const std::vector<MeshPoint>& points,
                                 const GenOptions& options);

// Sizes every body's shape from its vertices (or its bone) and gives it a mass: the figure's
// `totalMass` shared by volume, each body then kept within kMaxMassRatio of its parent's.
void sizeBodies(std::vector<GenBody>& bodies, const Skeleton& afPose, const std::vector<MeshPoint>& points,
                Real totalMass);

// The density that gives `body` its mass with its shape (docs/figures.md §3.4).
Real densityOf(const GenBody& body);

// What a body's joint to its parent is, from its name where a name says, else from its place.
enum class JointKind { Hinge, Shoulder, Hip, Spine, Neck, Wrist, Ankle, Limb, Continuation };
const char* toString(JointKind kind);

JointKind classifyJoint(const std::vector<GenBody>& bodies, const Skeleton& afPose, int body);

// The constraint that joins body `body` (not the root) to its parent: anchored at its joint,
// its limits centred on the af_pose.
AFConstraint makeConstraint(const std::vector<GenBody>& bodies, const Skeleton& afPose, int body, JointKind kind);

// A figure's plausible mass from its size: our humanoid's 150 for its 70 units, scaled by volume.
Real defaultTotalMass(const Skeleton& afPose, const std::vector<MeshPoint>& points);

struct Generated {
    DeclAF decl;
    std::vector<GenBody> bodies;
    std::vector<JointKind> kinds;  // per body; the root's is unused
    Real totalMass = 0;
};

// The whole figure: bodies, shapes, constraints, as a decl whose settings name the model
// `options.name`. Throws std::invalid_argument for a skeleton it cannot make a figure of (a joint
// named `world`, `origin` as the only joint).
Generated generateFigure(const std::vector<Md5SkinSection>& skin, const Skeleton& afPose, const GenOptions& options);

}  // namespace af::gen
