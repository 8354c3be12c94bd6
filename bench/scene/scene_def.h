#pragma once
// The engine-neutral ragdoll benchmark scene (docs/bench-scene.md §2–§4):
// the ragdoll's boxes and joints in the model frame (the standing T-pose), the placements of
// the four scenes, and the joint angle formulas every engine's run is measured with.
// SI units (m, kg, s, rad); Z up; +X = the character's right, +Y = its forward.
// Depends on Eigen only, so that every engine's benchmark program can link it.

#include <Eigen/Geometry>

#include <array>
#include <span>
#include <string_view>
#include <vector>

namespace benchscene {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// A box body in the T-pose: orientation identity, centre = centre of mass.
struct BoxBody {
    const char* name;
    Vec3 halfExtents;  // m
    Vec3 centre;       // m, model frame
    double mass;       // kg
};

// Diagonal (Ixx, Iyy, Izz) of a solid box about its centre, kg·m².
Vec3 boxInertia(const BoxBody&);

enum class JointKind { Fixed, Hinge, Universal, ConeTwist };

struct JointDef {
    const char* name;
    JointKind kind;
    int parent, child;  // body indices (A, B)
    Vec3 anchor;        // model frame
    Vec3 axis1;         // hinge: axis; universal: axis 1 (parent); cone+twist: cone axis c (unit)
    Vec3 axis2;         // universal: axis 2 (child); cone+twist: bone axis b; else zero
    double lo1, hi1;    // hinge: [lo1, hi1]; universal: θ1 range; cone+twist: hi1 = cone angle
    double lo2, hi2;    // universal: θ2 range; cone+twist: twist range [lo2, hi2] = [−t, t]
};

inline constexpr int kBodiesPerRagdoll = 16;
inline constexpr int kJointsPerRagdoll = 15;
inline constexpr double kGravity = 9.81;         // m/s², along −Z
inline constexpr double kTimeStep = 1.0 / 60.0;  // s
inline constexpr int kSteps = 600;
inline constexpr double kFriction = 0.5;

std::span<const BoxBody> ragdollBodies();   // the 16 rows of §2, in order
std::span<const JointDef> ragdollJoints();  // the 15 rows of §2, in order

// A ragdoll's placement: position p of the pivot h = (0, 0, 0.9), rotation R, spin ω (rad/s).
struct Placement {
    Vec3 p;
    Quat R;
    Vec3 spin;
};
inline const Vec3 kPivot(0, 0, 0.9);

// "single", "grid4", "grid16", "pile"; throws std::invalid_argument otherwise. `count` (≥ 1)
// changes the pile's number of ragdolls (32 by default, §3); 0 keeps the scene's own, and any
// other scene refuses it.
std::vector<Placement> scenePlacements(std::string_view scene, int count = 0);

// World centre, orientation, linear and angular velocity (world frame) of one body.
struct BodyState {
    Vec3 x;
    Quat q;
    Vec3 v;
    Vec3 w;
};

BodyState placeBody(const Placement&, int body);            // §3
Vec3 placePoint(const Placement&, const Vec3& modelPoint);  // §3 (anchors)

// Angles of §2 from the two bodies' world orientations (q = conj(qA)·qB), radians.
double hingeAngle(const JointDef&, const Quat& qA, const Quat& qB);            // wrapped to (−π, π]
std::array<double, 2> universalAngles(const JointDef&, const Quat& qA, const Quat& qB);  // {θ1, θ2}
std::array<double, 2> swingTwist(const JointDef&, const Quat& qA, const Quat& qB);       // {swing, twist}

// The joint frames A and B of a cone+twist joint (§2): A's x axis is c, B's x axis is b.
std::array<Quat, 2> coneTwistFrames(const JointDef&);

}  // namespace benchscene
