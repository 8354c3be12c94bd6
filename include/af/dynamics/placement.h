#pragma once
// Where a figure may start: clear of the static world. Doom tests a spawned figure against the
// world (af_testSolid) and only warns; a figure that starts with a body inside a brush has that
// body pushed out by the first steps, its joints pulled open to do it. So a spawn is lifted
// clear, or refused, before the world sees it.

#include "af/figure/figure.h"
#include "af/geometry/polytope.h"

#include <optional>
#include <span>

namespace af {

// How deep the figure, placed at `placement`, reaches into `statics` (world-space brushes):
// the deepest contact the narrowphase finds between any body and any brush; 0 when clear.
Real staticOverlap(const Figure& figure, const RigidPose& placement, std::span<const Polytope> statics);

// `placement` raised along +z until no body of the figure reaches into `statics`: each try
// lifts the whole figure (so its joints stay as built) by the deepest overlap plus `clearance`.
// None when `tries` lifts do not clear it (a ceiling above, a shaft).
std::optional<RigidPose> liftedClear(const Figure& figure, RigidPose placement, std::span<const Polytope> statics,
                                     Real clearance = 1, int tries = 16);

}  // namespace af
