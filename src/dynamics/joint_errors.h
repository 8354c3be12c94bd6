#pragma once
// A joint's rows measured without being written: each row's error and bounds, in the order and
// with the counts writeJointRows gives, bit for bit the errors of the rows it would write. What
// telling whether the joints drifted or are violated needs, at a fraction of writing the rows
// (no Jacobians, no softness, no inertia).

#include "joint_rows.h"

#include <span>
#include <vector>

namespace af {

struct RowError {
    Real error = 0;  // the row's C
    Real lo = -kInfinity;
    Real hi = kInfinity;
};

// Appends the errors of the rows writeJointRows would append; the range's `first` indexes `out`.
JointRowRange writeJointErrors(const Joint& joint, std::span<const RigidBody> bodies, const JointRowSettings& settings,
                               std::vector<RowError>& out);
// The same with each body's rotation() given, indexed as bodies.
JointRowRange writeJointErrors(const Joint& joint, std::span<const RigidBody> bodies, std::span<const Mat3> rotations,
                               const JointRowSettings& settings, std::vector<RowError>& out);

}  // namespace af
