#pragma once
// Broadphase: the pairs of bodies whose axis-aligned bounding boxes overlap, so that the
// narrowphase runs only where shapes can touch.
//
// Sweep and prune on one axis, chosen per call as the axis along which the boxes' centres are
// most spread (a pile of ragdolls spreads on the floor, not up). The sorted order persists between
// calls, so with coherent motion the insertion sort costs O(n + swaps) and the sweep
// O(n + overlapping pairs on that axis). Results do not depend on that internal order: pairs come
// out as (i < j), sorted, so every run with the same boxes produces the same list.
//
// Frames and units: world space, file units.

#include "af/geometry/polytope.h"

#include <span>
#include <utility>
#include <vector>

namespace af {

struct Aabb {
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();

    bool overlaps(const Aabb& other) const {
        return min.x() <= other.max.x() && other.min.x() <= max.x() && min.y() <= other.max.y() &&
               other.min.y() <= max.y() && min.z() <= other.max.z() && other.min.z() <= max.z();
    }
};

// The box around `shape` placed by `pose`, grown by `margin` on every side.
Aabb boundsOf(const Polytope& shape, const RigidPose& pose, Real margin);

class SweepAndPrune {
public:
    // Every (i, j), i < j, with boxes[i] and boxes[j] overlapping, sorted by i then j.
    void findPairs(std::span<const Aabb> boxes, std::vector<std::pair<int, int>>& pairs);

private:
    std::vector<int> order_;  // box indices by min along axis_ (kept between calls)
    int axis_ = 0;
    std::vector<std::pair<int, int>> partners_;  // per call: the pairs as found
    std::vector<int> firstPartner_;              // per call: where each body's pairs go in the output
};

}  // namespace af
