// A resting figure's step takes the joint rows written at the end of the step before, at the
// same poses (Island::measureJointErrors); whatever moved the bodies in between makes it write
// them afresh.

#include "af/geometry/shapes.h"
#include "scene_test_util.h"

namespace af {
namespace {

// A body nudged between two resting steps opens its joints by the nudge. Rows written at its new
// pose hold that opening as it is (SHAKE closes only what the step itself opens, and the
// projection moves positions alone); rows left from before the nudge would see it as drift of
// the step, which SHAKE closes with a velocity.
TEST(RestRows, BodyNudgedBetweenRestingStepsGetsNoVelocity) {
    WorldSettings settings;
    settings.comeToRest = false;
    World world(test::humanoidAt(Vec3(0, 0, 40)), settings);
    world.collision().addPlane(Plane{Vec3::UnitZ(), 0});
    for (int i = 0; i < 400; ++i) world.step();
    ASSERT_LT(world.kineticEnergy(), 1e-12) << "the humanoid lies still";
    const std::size_t hand = world.bodies().size() - 1;
    world.bodies()[hand].position += Vec3(0.5, 0, 0);  // along the floor: it still rests on it
    world.step();
    EXPECT_GT(world.lastStep().projectionPasses, 0) << "the joints were opened";
    for (std::size_t b = 0; b < world.bodies().size(); ++b)
        // units/s: below 1e-9 measured; rows from before the nudge gave 0.3 and more.
        EXPECT_LT(world.bodies()[b].linearVelocity.norm(), 1e-3) << "body " << b;
}

}  // namespace
}  // namespace af
