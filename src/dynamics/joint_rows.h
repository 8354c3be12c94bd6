#pragma once
// The rows a joint writes for the solver (the dispatch is in joint_rows.cpp, each type's rows in
// its joint_<type>.cpp). Each step the joint appends, at its bodies' current poses and
// velocities: first the equality rows (unbounded), then the limit rows (one-sided, only near or
// past a limit), then the joint friction rows (boxed by the joint's impulse of the previous
// step).
//
// Conventions shared by every row (see constraint_row.h):
//  * Cdot = J·[vA; ωA; vB; ωB] and `error` = C with dC/dt = Cdot exactly (the Jacobians are
//    the true derivatives of the written errors, so the position pass may use them as Newton
//    steps). C = 0 on a satisfied equality row; C ≥ 0 is the allowed side of a limit row.
//  * `target` is 0: no Baumgarte term; errors are corrected by the step's position pass.
//  * A row against the world has zero B blocks and bodyB = kWorldBody.

#include "af/dynamics/joints.h"
#include "constraint_row.h"

#include <span>

namespace af {

// Where a joint's rows went: rows [first, first + equalityRows) are the equality rows, then
// limitRows limit rows, then frictionRows friction rows.
struct JointRowRange {
    int first = 0;
    int equalityRows = 0;
    int limitRows = 0;
    int frictionRows = 0;

    int total() const { return equalityRows + limitRows + frictionRows; }
};

// Appends the joint's rows at the bodies' current poses and velocities.
JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies,
                             const JointRowSettings& settings, ConstraintRows& out);
// The same, with each body's world inverse inertia given (RigidBody::inverseInertiaWorld of
// bodies[i], indexed alike): a caller writing many rows at one pose computes it once per body.
JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies,
                             std::span<const Mat3> inverseInertiaWorld, const JointRowSettings& settings,
                             ConstraintRows& out);
// The same with each body's rotation() given too, indexed as bodies: a caller that has them
// spares the joints computing them for every side.
JointRowRange writeJointRows(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
                             std::span<const Mat3> inverseInertiaWorld, const JointRowSettings& settings,
                             ConstraintRows& out);

}  // namespace af
