#pragma once
// libccd on the narrowphase's shapes: does A, grown by `inflation` in every direction, overlap B,
// and roughly along which direction. Growing A by the margin turns "within the margin" into
// "overlapping", which is all libccd answers.
//
// MPR first: it does not allocate, and it handles the face-to-face boxes where GJK+EPA returns
// depth 0 and a NaN direction (libccd#25). Should MPR give a direction that is not finite or is
// zero, GJK+EPA is asked, and after it the line between the shapes' centres: the result is never
// NaN. The direction is only approximate (MPR does not minimise the depth); callers score it
// against the polytopes' own features.

#include "placed_shape.h"

namespace af::collision_detail {

struct CcdResult {
    bool intersecting = false;
    Vec3 normal = Vec3::UnitZ();  // working frame, unit, finite, from B towards A
};

CcdResult ccdPenetration(const PlacedShape& a, const PlacedShape& b, Real inflation);

}  // namespace af::collision_detail
