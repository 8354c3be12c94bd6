// Islands stepped on worker threads (WorldSettings::threads, worker_pool.h): the same bits as on
// one thread.

#include "af/geometry/shapes.h"
#include "dynamics/world_access.h"
#include "dynamics/worker_pool.h"
#include "scene_test_util.h"

#include <atomic>
#include <cstring>
#include <stdexcept>

namespace af {
namespace {

using test::humanoidAt;

// Three humanoids apart (three islands until they touch) and a tangled pair of a fourth and
// fifth (one island of two figures, solved by blocks once it exceeds exactRowLimit).
World crowd(int threads) {
    WorldSettings settings;
    settings.threads = threads;
    settings.exactRowLimit = 150;
    World world(settings);
    for (int i = 0; i < 3; ++i) world.addFigure(humanoidAt(Vec3(150 * i, 0, 10 + 7 * i), 40 * i, 90));
    world.addFigure(humanoidAt(Vec3(-200, 0, 8), 0, 90));
    world.addFigure(humanoidAt(Vec3(-170, -30, 30), 90, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    return world;
}

bool sameBits(const RigidBody& a, const RigidBody& b) {
    const auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
    return same(a.position, b.position) && same(a.orientation, b.orientation) &&
           same(a.linearVelocity, b.linearVelocity) && same(a.angularVelocity, b.angularVelocity);
}

// Steps the world `make` builds on 1, 2 and 3 threads side by side, checking that every body,
// the step's report and its solver counters are the same bits on each; returns the steps in
// which the world made an island of figure blocks.
int stepsOnOneTwoAndThreeThreads(World (*make)(int threads), int steps) {
    World one = make(1), two = make(2), three = make(3);
    int blockedSteps = 0;
    for (int i = 0; i < steps; ++i) {
        one.step();
        two.step();
        three.step();
        blockedSteps += detail::WorldAccess::counters(one).largeIslands > 0 ? 1 : 0;
        for (const World* other : {&two, &three}) {
            for (std::size_t b = 0; b < one.bodies().size(); ++b)
                if (!sameBits(one.bodies()[b], other->bodies()[b])) {
                    ADD_FAILURE() << "step " << i << " body " << b;
                    return blockedSteps;
                }
            EXPECT_EQ(one.lastStep().rows, other->lastStep().rows);
            EXPECT_EQ(one.lastStep().residual, other->lastStep().residual);
            EXPECT_EQ(detail::WorldAccess::counters(one).projectionPasses,
                      detail::WorldAccess::counters(*other).projectionPasses);
            EXPECT_EQ(detail::WorldAccess::counters(one).iterations, detail::WorldAccess::counters(*other).iterations);
        }
    }
    return blockedSteps;
}

TEST(WorldThreads, IslandsSteppedOnTwoOrThreeThreadsGiveTheSameBitsAsOnOne) {
    EXPECT_GT(stepsOnOneTwoAndThreeThreads(crowd, 100), 0) << "the pair never made an island of blocks";
}

// A pile alone is one island: its figure blocks are what the threads share out.
World pile(int threads) {
    WorldSettings settings;
    settings.threads = threads;
    settings.exactRowLimit = 150;
    World world(settings);
    for (int i = 0; i < 4; ++i) world.addFigure(humanoidAt(Vec3(0, 0, 20 + 30 * i), 37 * i, 90));
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    return world;
}

TEST(WorldThreads, APileSolvedByBlocksOnTwoOrThreeThreadsGivesTheSameBitsAsOnOne) {
    EXPECT_GT(stepsOnOneTwoAndThreeThreads(pile, 150), 20) << "the pile was not solved by blocks";
}

TEST(WorldThreads, APoolRunsEveryTaskOnceAndPassesOnTheFirstException) {
    WorkerPool pool(3);
    std::vector<std::atomic<int>> runs(1000);
    pool.run(runs.size(), [&](std::size_t i) { ++runs[i]; });
    for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 1);
    EXPECT_THROW(pool.run(100, [](std::size_t i) { if (i == 7) throw std::runtime_error("seven"); }),
                 std::runtime_error);
    std::atomic<int> after = 0;
    pool.run(10, [&](std::size_t) { ++after; });
    EXPECT_EQ(after.load(), 10) << "the pool works on after an exception";
}

TEST(WorldThreads, ThreadCountsOutOfRangeAreRefused) {
    WorldSettings settings;
    settings.threads = 0;
    EXPECT_THROW(World{settings}, std::invalid_argument);
    World world;
    settings.threads = 257;
    EXPECT_THROW(world.setSettings(settings), std::invalid_argument);
    EXPECT_EQ(world.settings().threads, 1);
}

}  // namespace
}  // namespace af
