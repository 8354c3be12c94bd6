#pragma once
// Joints: the runtime form of a figure's constraints.
//
// A Joint is plain data, made once from a Figure (makeJoints): every world-space spawn vector
// is stored in the frame of the body that carries it, so the joint follows its bodies. Each
// step the world writes the joint's rows for its solver (src/dynamics/joint_rows.h): first the
// equality rows, then the limit rows (only near or past a limit), then the joint friction rows.
// Springs write no equality rows; their force is explicit (applySpringForces). What a caller
// reads here are the measures: how far a joint is open (jointError, jointAngularError), past
// its limit (limitViolationDegrees), and its angles.
//
// Conventions:
//  * A = body1 of the .af constraint, B = body2 (kWorldBody for the world).
//  * Angles are radians, right-handed, unless a name says degrees.

#include "af/dynamics/rigid_body.h"
#include "af/figure/figure.h"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace af {

// Cone limit (docs/figures.md §3.8): the limited shaft (body A) may deviate up to halfAngle from the cone
// axis (body B). Doom's decl angle is the full apex angle, so halfAngle = angle/2.
struct ConeLimit {
    Vec3 axis = Vec3::UnitZ();  // body B frame (world if B is the world), unit
    Real halfAngle = 0;
    Real cosHalfAngle = 1;
    Real sinHalfAngle = 0;
};

// Pyramid limit (docs/figures.md §3.8): basis in body B's frame, columns e0 = base, e1 = e0 × e2, e2 = axis.
// The shaft's projection onto the (e0, e2) plane may deviate up to halfAngles[0] (= a1/2) from
// e2, its projection onto the (e1, e2) plane up to halfAngles[1] (= a2/2).
struct PyramidLimit {
    Mat3 basis = Mat3::Identity();
    Real halfAngles[2] = {0, 0};
};

// Hinge V limit (docs/figures.md §3.8) as an interval of the hinge angle: the right-handed rotation of body A
// relative to body B about the hinge axis, 0 at spawn (see hingeAngle). Allowed:
// |wrap(angle − center)| ≤ halfWidth. With Doom's a1 (V centre), a2 (V width), a3 (shaft
// orientation) in degrees, center = a3 − a1 and halfWidth = a2/2: Doom's clockwise angle
// θ = −angle lies in [a1 − a3 − a2/2, a1 − a3 + a2/2], that section's formula.
struct HingeLimit {
    Real center = 0;
    Real halfWidth = 0;
};

// Cardan (Hooke) universal joint, our extension (joint_cardan.cpp). The arms are the Joint's
// axisA (A's, in A's frame) and axisB (B's, in B's frame), kept ⟂. Its angles θ0 (about B's arm)
// and θ1 (about A's arm), right-handed and 0 at spawn, are those of the relative rotation
// q = R(armB, θ0)·R(armA, θ1) of A against B: each side's spawn copies of the other arm
// (referenceA: B's arm in A's frame, referenceB: A's arm in B's frame) and of armB × armA
// (crossA, crossB) read them off. θk stays within [lower[k], upper[k]] where lower < upper.
struct CardanJoint {
    bool enabled = false;
    Vec3 crossA = Vec3::UnitZ();
    Vec3 crossB = Vec3::UnitZ();
    Real lower[2] = {0, 0};
    Real upper[2] = {0, 0};
};

struct SpringParameters {
    Real stretch = 0;     // force per squared unit of extension (Doom's law is quadratic)
    Real compress = 0;    // force per squared unit of compression
    Real damping = 0;
    Real restLength = 0;
    Real minLength = 0;   // limit rows: L ≥ minLength when minLength > 0
    Real maxLength = 0;   // L ≤ maxLength when maxLength > 0
};

struct Joint {
    ConstraintType type = ConstraintType::Fixed;
    std::string name;
    int bodyA = 0;            // body1
    int bodyB = kWorldBody;   // body2, or kWorldBody

    // Anchors: anchorA in A's frame, anchorB in B's (world for the world). Ball, universal,
    // hinge: both copies of the one anchor. Spring: anchor1 and anchor2. Fixed and slider: A's
    // centre of mass (anchorA = 0) and where B holds it at spawn.
    Vec3 anchorA = Vec3::Zero();
    Vec3 anchorB = Vec3::Zero();

    // Hinge: the axis in each frame. Slider: axisB is the slide axis. Universal: axisA = shaft1
    // (A's frame), axisB = shaft2 (B's frame), as in the decl.
    Vec3 axisA = Vec3::UnitZ();
    Vec3 axisB = Vec3::UnitZ();
    // Hinge: a vector ⟂ the axis, the same world vector at spawn, in each frame (hinge angle
    // reference). Slider: referenceB ⟂ axisB, the first off-axis row direction.
    Vec3 referenceA = Vec3::UnitX();
    Vec3 referenceB = Vec3::UnitX();
    // Fixed, slider: A's orientation in B's frame at spawn. Universal: the constant middle
    // factor of the relative rotation, see joint_universal.cpp.
    Quat relative = Quat::Identity();

    LimitType limit = LimitType::None;  // ball and universal: cone or pyramid; hinge: cone = V
    Vec3 limitShaft = Vec3::UnitZ();    // A's frame: the limited vector (ball: shaft, universal: shaft1)
    ConeLimit cone;
    PyramidLimit pyramid;
    HingeLimit hinge;

    // Ball and socket, our extension (Doom's decl has none): A's twist about its shaft relative
    // to B, swing taken out (joint_twist_limit.cpp), stays within ±twistHalfAngle of its spawn
    // twist; 0 (or ≥ π): no limit. twistAxisB is B's axis (the cone axis, or B's copy of the
    // shaft at spawn); the references, ⟂ the shaft in A's frame and ⟂ twistAxisB in B's, agree
    // at spawn.
    Real twistHalfAngle = 0;
    Vec3 twistAxisB = Vec3::UnitZ();
    Vec3 twistReferenceA = Vec3::UnitX();
    Vec3 twistReferenceB = Vec3::UnitX();

    CardanJoint cardan;
    SpringParameters spring;

    Real friction = 0;     // joint friction coefficient (ball, universal, hinge)
    Real lastImpulse = 0;  // norm of the equality-row impulses of the previous step (set by the step)
};

// One joint per figure constraint, in the figure's order, from the spawn poses of the bodies.
// Body indices are the figure's (and must match the RigidBody span given to the measures).
std::vector<Joint> makeJoints(const Figure& figure);

// Softness of the rows, relative: a row's cfm is this times its own diagonal J M⁻¹ Jᵀ, so it is
// free of units and masses. Margins: a limit row is written once the joint is within this of
// its limit (so it engages before penetration and stays engaged while resting on the limit).
inline constexpr Real kJointRelativeCfm = 1e-9;
inline constexpr Real kLimitRelativeCfm = 1e-6;
inline constexpr Real kFrictionRelativeCfm = 1e-6;
inline constexpr Real kLimitMarginRadians = 0.01;  // about 0.57°
inline constexpr Real kSpringLimitMargin = 0.05;   // length units

struct JointRowSettings {
    Real jointCfm = kJointRelativeCfm;
    Real limitCfm = kLimitRelativeCfm;
    Real frictionCfm = kFrictionRelativeCfm;
    Real limitMargin = kLimitMarginRadians;
    Real springLimitMargin = kSpringLimitMargin;
    // Doom's af_skipLimits, af_skipFriction and af_forceFriction (docs/doom-physics.md §4.13), for
    // judging a figure: without limits a joint moves freely within its kind; without friction a
    // joint writes no friction rows; a forced friction (> 0) replaces every joint's own coefficient.
    bool limits = true;
    bool friction = true;
    Real forcedFriction = 0;
    friend bool operator==(const JointRowSettings&, const JointRowSettings&) = default;
};

// Doom's spring force (docs/doom-physics.md §4.3), quadratic in the displacement, added to the bodies'
// external force and torque. Does nothing for other joint types.
void applySpringForces(const Joint& joint, std::span<RigidBody> bodies);
// The same, capped at m·x/dt² (x the displacement, m the mass the spring moves along its line):
// the most a step of dt integrates stably (docs/doom-physics.md §4.3). The world's step uses this one.
void applySpringForces(const Joint& joint, std::span<RigidBody> bodies, Real dt);
// The energy stored in a spring by Doom's law (the integral of its force without damping:
// stretch·x³/3 stretched by x, compress·x³/3 compressed by x); 0 for other joint types.
Real springPotentialEnergy(const Joint& joint, std::span<const RigidBody> bodies);
// The energy of the capped law the step applies (applySpringForces with dt), at the current poses.
Real springPotentialEnergy(const Joint& joint, std::span<const RigidBody> bodies, Real dt);

// Distance between the two bodies' copies of the anchor; slider: the off-axis distance; fixed:
// the distance of A's centre of mass from where B holds it; spring: how far the length is
// outside [minLength, maxLength]. Length units.
Real jointError(const Joint& joint, std::span<const RigidBody> bodies);
// The rotational part, radians: fixed and slider: the angle of the relative rotation away from
// spawn; hinge: the angle between the two copies of the axis; universal: the relative twist
// (Cardan: how far the arms are from ⟂). 0 for ball and spring.
Real jointAngularError(const Joint& joint, std::span<const RigidBody> bodies);
// How far past its limit the joint is, in degrees; 0 inside the limit or without one.
Real limitViolationDegrees(const Joint& joint, std::span<const RigidBody> bodies);

// The hinge angle: right-handed rotation of A relative to B about B's copy of the axis,
// radians in (−π, π], 0 at spawn.
Real hingeAngle(const Joint& joint, std::span<const RigidBody> bodies);
// Ball and socket: the twist angle of A about its shaft relative to B, swing taken out,
// radians in (−π, π], 0 at spawn (defined whether or not the twist is limited).
Real twistAngle(const Joint& joint, std::span<const RigidBody> bodies);
// A Cardan universal joint's angles θ0 (about B's arm) and θ1 (about A's arm), radians in
// (−π, π] (see CardanJoint).
std::array<Real, 2> cardanAngles(const Joint& joint, std::span<const RigidBody> bodies);
// Spring length |anchor2 − anchor1|.
Real springLength(const Joint& joint, std::span<const RigidBody> bodies);

}  // namespace af
