#pragma once
// Contact rows: a point where body A touches body B (or the world), with Coulomb friction.
// The step writes them for its ContactPoints (contact_set.h); a hand-made Contact writes them
// the same way (tests, and sources of extra rows).
//
// Rows (docs/doom-physics.md §4.3, §4.7): one normal row  [n │ rA×n] − [n │ rB×n],  lo = 0, hi = +∞, so it
// only pushes; its target is the restitution velocity when the bodies approach faster than
// restitutionThreshold, else 0; its error is the separation (negative when penetrating) plus a
// small slop, which the position projection removes. Friction: two rows along tangents t1, t2
// (or one along the body's frictionDirection projected into the contact plane), bounded by
// ±friction·λ_normal through frictionSource: a Coulomb friction pyramid.

#include "af/dynamics/contact.h"
#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"

#include <optional>
#include <span>

namespace af {

struct Contact {
    int bodyA = kWorldBody;
    int bodyB = kWorldBody;
    Vec3 point = Vec3::Zero();         // world, on the surface between the bodies
    Vec3 normal = Vec3::UnitZ();       // world, unit, pointing from B towards A
    Real depth = 0;                    // penetration along the normal (≥ 0 when touching)
    Real friction = 0;                 // Coulomb coefficient μ
    Real restitution = 0;              // Doom: 0.4 for every body
    std::optional<Vec3> frictionDirection;  // world; one friction row along it when given
    // The normal velocity (B towards A, negative when approaching) the bounce is judged from.
    // A world step takes it from before gravity acted in the step, as Doom does: otherwise a
    // body resting on the ground, whose predicted velocity is g·dt (17.8 units/s at 60 Hz) into
    // it, would bounce every step. Empty: the bodies' current velocities.
    std::optional<Real> approachVelocity;
};

// The directions of a contact's friction rows: its friction direction (world, or null) projected
// into the plane of the normal n, unless that leaves nothing of it; else two unit tangents
// completing n to a right-handed basis. Returns how many (1 or 2).
int frictionDirections(const Vec3& n, const Vec3* frictionDirection, Vec3 (&out)[2]);

// Appends the rows of one contact; returns the index of its normal row.
int writeContactRows(const Contact& contact, std::span<const RigidBody> bodies, const ContactSettings& settings,
                     ConstraintRows& out);
// The same, with each body's world inverse inertia given (RigidBody::inverseInertiaWorld of
// bodies[i], indexed alike): a caller writing many rows at one pose computes it once per body.
int writeContactRows(const Contact& contact, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld,
                     const ContactSettings& settings, ConstraintRows& out);

}  // namespace af
