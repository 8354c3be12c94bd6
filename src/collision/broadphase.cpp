#include "af/collision/broadphase.h"

#include <algorithm>
#include <numeric>

namespace af {

Aabb boundsOf(const Polytope& shape, const RigidPose& pose, Real margin) {
    // A shape without vertices (a body that collides with nothing) gets a point box.
    Aabb box{pose.position, pose.position};
    if (!shape.vertices.empty()) box.min = box.max = pose.apply(shape.vertices[0]);
    for (const Vec3& v : shape.vertices) {
        const Vec3 p = pose.apply(v);
        box.min = box.min.cwiseMin(p);
        box.max = box.max.cwiseMax(p);
    }
    box.min.array() -= margin;
    box.max.array() += margin;
    return box;
}

namespace {

int axisOfLargestSpread(std::span<const Aabb> boxes) {
    Vec3 sum = Vec3::Zero(), sumSquares = Vec3::Zero();
    for (const Aabb& b : boxes) {
        const Vec3 c = (b.min + b.max) / 2;
        sum += c;
        sumSquares += c.cwiseProduct(c);
    }
    const Real n = static_cast<Real>(boxes.size());
    const Vec3 variance = sumSquares / n - (sum / n).cwiseProduct(sum / n);
    int axis = 0;
    variance.maxCoeff(&axis);
    return axis;
}

}  // namespace

void SweepAndPrune::findPairs(std::span<const Aabb> boxes, std::vector<std::pair<int, int>>& pairs) {
    pairs.clear();
    if (boxes.empty()) return;
    if (order_.size() != boxes.size()) {
        order_.resize(boxes.size());
        std::iota(order_.begin(), order_.end(), 0);
    }
    axis_ = axisOfLargestSpread(boxes);
    const int axis = axis_;
    auto before = [&](int a, int b) {
        const Real ka = boxes[static_cast<std::size_t>(a)].min[axis], kb = boxes[static_cast<std::size_t>(b)].min[axis];
        return ka < kb || (ka == kb && a < b);
    };
    // Insertion sort: nearly sorted from the previous call when bodies move coherently.
    for (std::size_t i = 1; i < order_.size(); ++i) {
        const int key = order_[i];
        std::size_t j = i;
        for (; j > 0 && before(key, order_[j - 1]); --j) order_[j] = order_[j - 1];
        order_[j] = key;
    }
    for (std::size_t i = 0; i < order_.size(); ++i) {
        const Aabb& a = boxes[static_cast<std::size_t>(order_[i])];
        for (std::size_t j = i + 1; j < order_.size(); ++j) {
            const Aabb& b = boxes[static_cast<std::size_t>(order_[j])];
            if (b.min[axis] > a.max[axis]) break;
            if (a.overlaps(b)) pairs.emplace_back(std::min(order_[i], order_[j]), std::max(order_[i], order_[j]));
        }
    }
    std::sort(pairs.begin(), pairs.end());
}

}  // namespace af
