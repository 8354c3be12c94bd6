// The internal accessor of a World (src/dynamics/world_access.h): solver tuning set on a world
// that has stepped reaches its islands' solvers from the next step on.

#include "dynamics/world_access.h"
#include "world_test_util.h"

namespace af {
namespace {

TEST(WorldAccess, TuningSetBetweenStepsReachesTheSolversOfTheNextStep) {
    WorldSettings settings;
    settings.solver = SolverKind::Pgs;
    World world(test::hangingChain(20, 300), test::dynamicsOnly(settings));
    test::swingAbout(world, Vec3(0, 0, 300), 30);
    world.step();
    ASSERT_GT(detail::WorldAccess::counters(world).iterations, 1) << "the default tuning sweeps more than once";
    SolverTuning oneSweep;
    oneSweep.pgs.maxIterations = 1;
    detail::WorldAccess::setTuning(world, oneSweep);
    world.step();
    EXPECT_EQ(detail::WorldAccess::counters(world).iterations, 1);
}

}  // namespace
}  // namespace af
