#pragma once
// Extra rows for a World's step, written by the caller on the world's bodies: the drag's
// (world_figures.cpp), and hand-made contacts in tests (detail::WorldAccess::setContactSource).

#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"

#include <functional>
#include <span>

namespace af {

// Appends rows for the current step; body indices are the world's.
using RowSource = std::function<void(std::span<const RigidBody>, ConstraintRows&)>;

}  // namespace af
