// Once warmed up to the shapes it sees, the narrowphase allocates nothing: it runs for every pair
// in every step. Counted by replacing the global operator new for this test program.

#include "narrowphase_test_util.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) {
        return p;
    }
    throw std::bad_alloc();
}
// Not inlined: GCC would otherwise pair an inlined free() with a `new` expression and warn
// (-Wmismatched-new-delete), not knowing that this operator new is malloc.
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace af {
namespace {

using test::box;
using test::pose;
using test::rotation;

TEST(NarrowphaseAllocation, NoneOnceWarm) {
    const Polytope cube = box(Vec3(5, 5, 5));
    const Polytope cylinder = makeCylinder(Vec3(-3, -3, -6), Vec3(3, 3, 6), 10);
    const Polytope sheet = makeBox(Vec3(-4, -3, 0), Vec3(4, 3, 0));  // flat: takes the libccd path
    const Plane floor{Vec3::UnitZ(), 0};
    const ConvexShape preparedCube(cube), preparedSheet(sheet);
    auto run = [&] {
        Real sum = 0;
        for (int k = 0; k < 20; ++k) {
            const RigidPose p = pose(Vec3(0.1 * k, 0, 9.8 + 0.1 * k), rotation(Vec3(1, 2, 3), 3.0 * k));
            sum += collide(cube, p, cube, pose(Vec3::Zero()), 1).count;
            sum += collide(cylinder, p, cube, pose(Vec3::Zero()), 1).count;
            sum += collide(sheet, p, cylinder, pose(Vec3::Zero()), 1).count;
            sum += collideWithPlane(cylinder, p, floor, 1).count;
            sum += collide(preparedSheet, p, preparedCube, pose(Vec3::Zero()), 1).count;
        }
        return sum;
    };
    const Real warm = run();
    const long before = allocations.load();
    const Real again = run();
    EXPECT_EQ(allocations.load() - before, 0);
    EXPECT_EQ(warm, again);
    EXPECT_GT(warm, 0);
}

}  // namespace
}  // namespace af
