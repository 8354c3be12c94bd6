// Doom's springs in the world's step: a spring too stiff for the step is capped to what the step
// can integrate (docs/doom-physics.md §4.3), and Doom's own lamp never reaches the cap.

#include "../figure/figure_test_util.h"
#include "world_test_util.h"

#include <algorithm>

namespace af {
namespace {

using test::boxBodyText;
using test::figureOfBlocks;

// A 8-unit box (mass 512) hung from the world by a spring from the middle of its top face,
// `stretched` beyond its rest length of 4, in zero gravity: it only bobs along the spring's line.
World bobbingBox(Real stiffness, Real stretched, Real dt) {
    const Figure figure = figureOfBlocks(
        {"origin"}, boxBodyText("box", "origin", Vec3(4, 4, 4), Vec3::Zero()) +
                        "spring \"s\" { body1 \"box\" body2 \"world\" anchor1 ( 0, 0, 4 ) anchor2 " +
                        test::afVector(Vec3(0, 0, 8 + stretched)) + " friction 0 stretch " + test::afNumber(stiffness) +
                        " compress " + test::afNumber(stiffness) +
                        " damping 0 restLength 4 minLength 0 maxLength 0 }\n");
    WorldSettings settings;
    settings.gravity.setZero();
    settings.timeStep = dt;
    return World(figure, test::dynamicsOnly(settings));
}

// Stiffness 2e7 stretched by 2: Doom's law is 8e7 stiff there, against the 512·15² = 1.2e5 a
// step of 1/15 s can follow (ω·dt = 26). Explicitly each swing overshoots the last (the guard
// puts the box back in the second step); capped at c·x (c = m/dt²), the first step hands the
// box c·x²/2 and it bobs with that and no more: measured, exactly that at every swing's middle.
TEST(SpringStep, ASpringTooStiffForTheStepBobsWithoutGainingEnergy) {
    const Real dt = 1.0 / 15, stretched = 2;
    World world = bobbingBox(2e7, stretched, dt);
    const Real start = 0.5 * world.bodies()[0].mass() / (dt * dt) * stretched * stretched;
    Real firstSecond = 0, lastSecond = 0;
    for (int i = 0; i < 150; ++i) {
        world.step();
        const Real kinetic = world.kineticEnergy();
        if (i < 15) firstSecond = std::max(firstSecond, kinetic);
        if (i >= 135) lastSecond = std::max(lastSecond, kinetic);
        ASSERT_LE(kinetic, start * (1 + 1e-12)) << "step " << i << ": more kinetic energy than the stretch held";
        ASSERT_TRUE(world.lastStep().restored.empty()) << "step " << i << ": the guard put the box back";
    }
    EXPECT_GT(firstSecond, 0) << "the box did not move";
    EXPECT_LE(lastSecond, firstSecond * (1 + 1e-9)) << "the swing grew";
}

// The cap only touches springs Doom's explicit step could not follow: our lamp (stretch 2000) at
// 60 Hz swings and settles with every step's force Doom's own (measured: at most 0.74 of the cap).
TEST(SpringStep, DoomsLampAtSixtyHertzFeelsDoomsForceInEveryStep) {
    const FigureResult r = buildFigure(test::loadDecl("af/lamp.af"), test::loadAfPose("models/lamp/af_pose.md5anim"), "lamp.af");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    World world(*r.figure);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    const Real dt = world.settings().timeStep;
    int springs = 0;
    for (int i = 0; i < 300 && !world.atRest(); ++i) {
        for (const Joint& joint : world.joints()) {
            if (joint.type != ConstraintType::Spring) continue;
            std::vector<RigidBody> doom(world.bodies().begin(), world.bodies().end()), capped = doom;
            applySpringForces(joint, doom);
            applySpringForces(joint, capped, dt);
            for (std::size_t b = 0; b < doom.size(); ++b) ASSERT_EQ(doom[b].force, capped[b].force) << "step " << i;
            ++springs;
        }
        world.step();
    }
    EXPECT_GT(springs, 60) << "the lamp has a spring and swings for a second at least";
}

}  // namespace
}  // namespace af
