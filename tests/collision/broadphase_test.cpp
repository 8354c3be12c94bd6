#include "af/collision/broadphase.h"

#include <gtest/gtest.h>

#include <random>

namespace af {
namespace {

std::vector<std::pair<int, int>> bruteForcePairs(const std::vector<Aabb>& boxes) {
    std::vector<std::pair<int, int>> pairs;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
        for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
            if (boxes[static_cast<std::size_t>(i)].overlaps(boxes[static_cast<std::size_t>(j)])) pairs.emplace_back(i, j);
    return pairs;
}

std::vector<Aabb> randomBoxes(std::mt19937& rng, int count, Real spread) {
    std::uniform_real_distribution<Real> position(-spread, spread), size(1, 40);
    std::vector<Aabb> boxes;
    for (int i = 0; i < count; ++i) {
        const Vec3 c(position(rng), position(rng), position(rng) / 4);
        const Vec3 h(size(rng), size(rng), size(rng));
        boxes.push_back({c - h, c + h});
    }
    return boxes;
}

TEST(Broadphase, FindsExactlyTheOverlappingPairsOfRandomScenes) {
    std::mt19937 rng(7);
    SweepAndPrune sap;
    std::vector<std::pair<int, int>> pairs;
    for (int scene = 0; scene < 200; ++scene) {
        const std::vector<Aabb> boxes = randomBoxes(rng, 1 + scene % 60, 50 + scene * 3);
        sap.findPairs(boxes, pairs);
        EXPECT_EQ(pairs, bruteForcePairs(boxes)) << "scene " << scene;
    }
}

TEST(Broadphase, StaysExactWhileBoxesMoveBetweenCalls) {
    std::mt19937 rng(11);
    std::normal_distribution<Real> jitter(0, 8);
    std::vector<Aabb> boxes = randomBoxes(rng, 300, 400);
    SweepAndPrune sap;
    std::vector<std::pair<int, int>> pairs;
    for (int step = 0; step < 50; ++step) {
        for (Aabb& b : boxes) {
            const Vec3 move(jitter(rng), jitter(rng), jitter(rng));
            b.min += move;
            b.max += move;
        }
        sap.findPairs(boxes, pairs);
        ASSERT_EQ(pairs, bruteForcePairs(boxes)) << "step " << step;
    }
}

TEST(Broadphase, TouchingBoxesCountAsOverlapping) {
    const std::vector<Aabb> boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 1)},
                                     {Vec3(2.5, 0, 0), Vec3(3, 1, 1)}};
    SweepAndPrune sap;
    std::vector<std::pair<int, int>> pairs;
    sap.findPairs(boxes, pairs);
    EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 1}}));
}

TEST(Broadphase, BoundsOfARotatedBoxHoldEveryCornerAndTheMargin) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 2 : -2, i & 2 ? 1 : -1, i & 4 ? 3 : -3);
    Polytope box;
    box.vertices = corners;
    const RigidPose pose{Vec3(10, -5, 7), Eigen::AngleAxis<Real>(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix()};
    const Aabb bounds = boundsOf(box, pose, 0.5);
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (const Vec3& c : corners) {
        lo = lo.cwiseMin(pose.apply(c));
        hi = hi.cwiseMax(pose.apply(c));
    }
    EXPECT_LT((bounds.min - (lo - Vec3::Constant(0.5))).norm(), 1e-12);
    EXPECT_LT((bounds.max - (hi + Vec3::Constant(0.5))).norm(), 1e-12);
}

}  // namespace
}  // namespace af
