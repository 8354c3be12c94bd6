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
    const std::size_t n = boxes.size();
    if (order_.size() != n) {
        order_.resize(n);
        std::iota(order_.begin(), order_.end(), 0);
    }
    axis_ = axisOfLargestSpread(boxes);
    const int axis = axis_;
    auto before = [&](int a, int b) {
        const Real ka = boxes[static_cast<std::size_t>(a)].min[axis], kb = boxes[static_cast<std::size_t>(b)].min[axis];
        return ka < kb || (ka == kb && a < b);
    };
    // Insertion sort: nearly sorted from the previous call when bodies move coherently.
    for (std::size_t i = 1; i < n; ++i) {
        const int key = order_[i];
        std::size_t j = i;
        for (; j > 0 && before(key, order_[j - 1]); --j) order_[j] = order_[j - 1];
        order_[j] = key;
    }
    // Each pair goes to the list of its lower body (a counting sort by it), so that the lists read
    // in body order give the pairs sorted once each list is, and the lists are short.
    partners_.clear();
    firstPartner_.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const Aabb& a = boxes[static_cast<std::size_t>(order_[i])];
        for (std::size_t j = i + 1; j < n; ++j) {
            const Aabb& b = boxes[static_cast<std::size_t>(order_[j])];
            if (b.min[axis] > a.max[axis]) break;
            if (a.overlaps(b)) {
                const auto [low, high] = std::minmax(order_[i], order_[j]);
                partners_.emplace_back(low, high);
                ++firstPartner_[static_cast<std::size_t>(low) + 1];
            }
        }
    }
    for (std::size_t i = 0; i < n; ++i) firstPartner_[i + 1] += firstPartner_[i];
    pairs.resize(partners_.size());
    for (const auto& pair : partners_) {
        pairs[static_cast<std::size_t>(firstPartner_[static_cast<std::size_t>(pair.first)]++)] = pair;
    }
    // firstPartner_[a] is now where a's list ends and a + 1's begins: sort each by its higher body.
    auto byHigher = [](const std::pair<int, int>& x, const std::pair<int, int>& y) { return x.second < y.second; };
    for (std::size_t a = 0, begin = 0; a < n; ++a) {
        const std::size_t end = static_cast<std::size_t>(firstPartner_[a]);
        if (end - begin > 1) {
            std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(begin), pairs.begin() + static_cast<std::ptrdiff_t>(end),
                      byHigher);
        }
        begin = end;
    }
}

}  // namespace af
