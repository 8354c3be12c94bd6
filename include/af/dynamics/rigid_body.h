#pragma once
// Rigid bodies: the state the solver moves. World space throughout; a body's reference point is
// its centre of mass (as in Doom 3), so forces at the centre of mass cause no torque.
//
// Units: lengths in file units (Doom: ~1 inch), mass in the file's mass units, time in seconds,
// angular velocity in rad/s (right-handed, world axes). Rotations follow af/types.h: the
// orientation maps body-local vectors to world vectors.

#include "af/geometry/math.h"

#include <Eigen/Geometry>

namespace af {

using Quat = Eigen::Quaternion<Real>;

// The body index that names the immovable world (a joint or a contact against nothing).
inline constexpr int kWorldBody = -1;

struct RigidBody {
    Vec3 position = Vec3::Zero();          // centre of mass
    Quat orientation = Quat::Identity();   // body → world, unit length
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    Vec3 force = Vec3::Zero();             // external, for the next step (cleared by the step)
    Vec3 torque = Vec3::Zero();            // external, about the centre of mass

    Real inverseMass = 0;                  // 0: never moves (static)
    Mat3 inertia = Mat3::Identity();       // body frame, about the centre of mass
    Mat3 inverseInertia = Mat3::Zero();    // body frame; zero for a static body

    // Doom's air friction (docs/doom-physics.md §4.7): the fraction of velocity removed per 1/60 s step.
    Real linearFriction = 0;
    Real angularFriction = 0;

    // A body with the given mass and body-frame inertia (inertiaScale may make it unsymmetric;
    // the symmetric part is used), at rest, orientation normalised.
    // Throws std::invalid_argument if mass is not finite and > 0, or the inertia has a non-finite
    // entry: both are bugs upstream (the figure stage already replaces bad masses, docs/figures.md §3.4).
    // A symmetric part that is not positive definite (inertiaScale can do that) is repaired, not
    // refused: eigenvalues below 1e-6·λmax are raised to 1e-6·λmax (the nearest matrix in the
    // Frobenius norm with that floor), and one with no positive eigenvalue becomes the identity,
    // Doom's inertia for degenerate shapes. `inertia` stores the repaired matrix, so inertia and
    // inverseInertia are always exact inverses and energy and momentum use what the integrator uses.
    // A symmetric input above the floor is kept bit for bit; a diagonal one is inverted entry by
    // entry, so a spin about a principal axis stays exactly on it.
    static RigidBody dynamic(Real mass, const Mat3& inertia, const Vec3& position, const Quat& orientation);

    Mat3 rotation() const { return orientation.toRotationMatrix(); }
    Mat3 inverseInertiaWorld() const;
    // The same with rotation() given, for a caller that needs both.
    Mat3 inverseInertiaWorld(const Mat3& rotation) const;
    Mat3 inertiaWorld() const;
    Real mass() const { return inverseMass > 0 ? 1 / inverseMass : 0; }
    Vec3 velocityAt(const Vec3& worldPoint) const { return linearVelocity + angularVelocity.cross(worldPoint - position); }
    Vec3 linearMomentum() const { return mass() * linearVelocity; }
    // About the world origin: m x × v + I_w ω. Zero for a static body (its mass is not finite).
    Vec3 angularMomentum() const;
    // ½ m |v|² + ½ ω·I_w ω; zero for a static body.
    Real kineticEnergy() const;
};

// Limits and switches of integration: plain data, cvars later.
struct IntegrationSettings {
    // Doom's per-step caps (128 units and 1.57 rad per 1/60 s step), as rates, so that they mean
    // the same at any step. (Doom's real step is 16 ms, where its caps are 8000 units/s and
    // 98.1 rad/s; these are the values of an exact 60 Hz step.) A cap that is NaN or +∞ does
    // nothing; a negative cap acts as 0 (a World refuses both NaN and negative caps).
    Real maxLinearSpeed = 128 * 60;   // units/s
    Real maxAngularSpeed = 1.57 * 60; // rad/s
    // Keep the gyroscopic term (ω × Iω) and integrate it implicitly, so a free spinning body
    // keeps its angular momentum and gains no energy (it loses the tumble; see integrateVelocity).
    bool gyroscopic = true;
};

// v += dt·(gravity + F/m); ω += dt·I⁻¹(τ − ω × Iω), the gyroscopic part implicit; then the caps.
// Reads force and torque but does not clear them (the step does, once per frame, so substeps
// all see them). Static bodies (inverseMass 0) are left untouched.
//
// With `gyroscopic`, the angular update solves, in the body frame at the start of the step,
//     I ω' = exp(−dt [ω']×) (I ω + dt Rᵀτ),
// that is: the new angular momentum is the old one plus the torque impulse, seen from the body
// after it has turned by exactly the rotation integratePosition will apply (angle dt·|ω'| about
// ω'). So a torque-free body followed by integratePosition with the same dt keeps its world
// angular momentum exactly (up to rounding: Newton's method is run to convergence), and its
// kinetic energy never increases (the scheme is backward Euler on the rotation group; it loses
// ½ ΔL·I⁻¹ΔL per step, ΔL the change of body-frame momentum, which tends to move a tumbling
// body towards its major axis). Its first-order form is the familiar implicit gyroscopic step
// I(ω' − ω) = −dt ω' × Iω'. If the constraint solve changes ω before integratePosition, the
// predicted turn is off by that change and L is kept to first order in it only. Without
// `gyroscopic`, ω' = ω + dt I_w⁻¹τ (world ω kept: Doom's behaviour, which neither keeps L nor
// bounds the energy of an asymmetric body).
void integrateVelocity(RigidBody& body, const Vec3& gravity, Real dt, const IntegrationSettings& settings);

// Only the caps of integrateVelocity: |v| and |ω| clamped, directions kept. For a step that
// changes velocities again after integrateVelocity (constraint impulses), as Doom caps after.
void clampVelocity(RigidBody& body, const IntegrationSettings& settings);

// x += dt·v; the orientation turns by dt·|ω| about ω (exact quaternion exponential, so exact for
// constant ω), renormalised. Static bodies are left untouched.
void integratePosition(RigidBody& body, Real dt);

// Doom's air friction, made independent of the step: v ← v·(1 − f)^(dt·60), which is Doom's
// v −= f·v at 60 Hz and the same decay per second at any other rate. f is clamped to [0, 1]
// (NaN counts as 0): a negative f would accelerate, f ≥ 1 stops the body, as Doom's v −= f·v
// does at f = 1. dt ≤ 0 does nothing; static bodies are left untouched.
void applyAirFriction(RigidBody& body, Real dt);

}  // namespace af
