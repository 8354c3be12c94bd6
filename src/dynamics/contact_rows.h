#pragma once
// The contact row writer behind both writeContactRows overloads: a hand-made Contact (contact.h)
// and the step's ContactPoints (contact_set.h) are written by the same arithmetic.

#include "af/dynamics/contact.h"

namespace af::contact_detail {

// A Contact as the writer reads it: its optional parts as pointers (null when absent), so a
// caller builds it on the stack without copying optionals.
struct ContactView {
    int bodyA = kWorldBody;
    int bodyB = kWorldBody;
    Vec3 point;                              // world
    Vec3 normal;                             // world, unit, B towards A
    Real depth = 0;
    Real friction = 0;
    Real restitution = 0;
    const Real* approachVelocity = nullptr;  // empty: the bodies' current velocities
    const Vec3* frictionDirection = nullptr;  // world
};

// Appends the contact's rows; returns the index of its normal row. inverseInertiaA/B: the world
// inverse inertias of A and B (not read for the world).
int writeRows(const ContactView& contact, std::span<const RigidBody> bodies, const Mat3& inverseInertiaA,
              const Mat3& inverseInertiaB, const ContactSettings& settings, ConstraintRows& out);

}  // namespace af::contact_detail
