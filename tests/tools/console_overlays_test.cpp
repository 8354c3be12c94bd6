// af-console's screenshot scene (console_screenshot.h): the af_show* cvars' overlays sit where
// the joints and bodies are, and with every cvar off the picture is af-sim's.

#include "console_overlays.h"
#include "console_screenshot.h"

#include "console/console_text.h"
#include "console/show_geometry.h"
#include "dynamics/world_test_util.h"

#include <gtest/gtest.h>

namespace af::console {
namespace {

struct Console {
    CommandSystem commands;
    Session session{{AF_SOURCE_DIR}, commands};
    Console() { EXPECT_TRUE(commands.execute("spawn ragdoll_humanoid\nwaitRest 5", "test.cfg").ok()); }
    const World& world() const { return session.world(); }
};

TEST(ConsoleOverlays, EveryShowCvarOffLeavesTheScenePlain) {
    Console c;
    const render::RenderScene scene = screenshotScene(c.session, {});
    EXPECT_TRUE(scene.overlay.dots.empty() && scene.overlay.lines.empty() && scene.overlay.labels.empty() && scene.overlay.polygons.empty());
    ASSERT_EQ(scene.bodies.size(), c.world().bodies().size());
    for (const render::RenderShape& b : scene.bodies) EXPECT_FALSE(b.colour) << "the palette, as af-sim draws";
}

TEST(ConsoleOverlays, ConstraintsAreDotsAtTheAnchorsNamedByTheirLabels) {
    Console c;
    ShowFlags flags;
    flags.constraints = flags.constraintNames = true;
    const render::RenderScene scene = screenshotScene(c.session, flags);
    const std::vector<Joint>& joints = c.world().joints();
    ASSERT_EQ(scene.overlay.dots.size(), joints.size());
    ASSERT_EQ(scene.overlay.labels.size(), joints.size());
    for (std::size_t k = 0; k < joints.size(); ++k) {
        EXPECT_LT((scene.overlay.dots[k].at - jointAnchor(joints[k], c.world().bodies())).norm(), 1e-9) << joints[k].name;
        EXPECT_EQ(scene.overlay.labels[k].text, joints[k].name);
    }
}

TEST(ConsoleOverlays, TreesLimitsAndVelocitiesHaveTheirShapes) {
    Console c;
    ShowFlags flags;
    flags.trees = true;
    EXPECT_EQ(screenshotScene(c.session, flags).overlay.lines.size(), c.world().definition(c.world().figureIds().front()).bodies.size() - 1)
        << "one parent → child line per body but the root";
    flags = {};
    flags.limits = true;
    std::size_t limited = 0;
    for (const Joint& j : c.world().joints()) limited += !limitReadings(j, c.world().bodies()).empty();
    EXPECT_EQ(screenshotScene(c.session, flags).overlay.polygons.size(), limited) << "a cone, pyramid or fan per limited joint";
    flags = {};
    flags.velocity = true;
    EXPECT_TRUE(screenshotScene(c.session, flags).overlay.lines.empty()) << "a ragdoll at rest has no arrows";
    ASSERT_TRUE(c.commands.execute("drag ragdoll_humanoid_1 rhand 0 0 80\nstep 5", "test.cfg").ok());
    EXPECT_FALSE(screenshotScene(c.session, flags).overlay.lines.empty());
    flags.active = true;
    ASSERT_TRUE(c.commands.execute("drag off\nwaitRest 10", "test.cfg").ok());
    flags.trees = true;
    EXPECT_TRUE(screenshotScene(c.session, flags).overlay.lines.empty()) << "af_showActive: nothing for a ragdoll at rest";
}

// af_showMass puts each body's mass beside its name (one label, as Doom prints them),
// af_showTotalMass one label per figure with the sum, and af_showInertia three principal axes per
// body through its centre, each as long both ways as the radius of gyration about it: so the
// lengths give back the body's moments (Σ over the axes of m·k² is the inertia's trace).
TEST(ConsoleOverlays, MassesTotalMassAndInertiaAxesSayWhatTheBodiesWeigh) {
    Console c;
    const World& world = c.world();
    const std::span<const RigidBody> bodies = world.bodies();
    ShowFlags flags;
    flags.bodyNames = flags.mass = flags.totalMass = true;
    const render::RenderScene named = screenshotScene(c.session, flags);
    ASSERT_EQ(named.overlay.labels.size(), bodies.size() + 1);
    const Figure& figure = world.definition(world.figureIds().front());
    Real total = 0;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        total += bodies[b].mass();
        EXPECT_EQ(named.overlay.labels[b].text, figure.bodies[b].name + " " + fixed(bodies[b].mass()));
    }
    EXPECT_EQ(named.overlay.labels.back().text, "total mass " + fixed(total));
    EXPECT_NEAR(total, 150, 0.01) << "the humanoid's totalMass";

    flags = {};
    flags.inertia = true;
    const render::RenderScene axes = screenshotScene(c.session, flags);
    ASSERT_EQ(axes.overlay.lines.size(), 3 * bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        Real trace = 0;
        for (int k = 0; k < 3; ++k) {
            const render::OverlayLine& line = axes.overlay.lines[3 * b + std::size_t(k)];
            EXPECT_LT(((line.from + line.to) / 2 - bodies[b].position).norm(), 1e-9) << "through the centre of mass";
            const Vec3 half = (line.to - line.from) / 2;
            trace += bodies[b].mass() * half.squaredNorm();
            for (int l = 0; l < k; ++l) {
                const render::OverlayLine& other = axes.overlay.lines[3 * b + std::size_t(l)];
                EXPECT_LT(std::abs(half.normalized().dot((other.to - other.from).normalized())), 1e-9) << "principal axes are ⟂";
            }
        }
        EXPECT_NEAR(trace, bodies[b].inertiaWorld().trace(), 1e-9 * bodies[b].inertiaWorld().trace()) << figure.bodies[b].name;
    }
}

// af_showContacts: under each contact point's red normal, an orange line along it as long as
// the point's normal impulse at kContactImpulseLength. Two boxes alike but for their density, 1
// and 2, resting on the floor: the heavier one's lines add up to twice the lighter one's, and
// each box's to its weight's impulse over the step, m·|g|·dt.
TEST(ConsoleOverlays, ContactImpulseLinesGrowWithTheWeightTheyHold) {
    const Vec3 half(8, 8, 8);
    const Figure boxes = test::figureOfBlocks({"origin", "second"}, test::boxBodyText("light", "origin", half, Vec3(-20, 0, 8.5), 0.01) +
                                                                        test::boxBodyText("heavy", "second", half, Vec3(20, 0, 8.5), 0.02));
    WorldSettings settings;
    settings.comeToRest = false;
    World world(boxes, settings);
    world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
    for (int i = 0; i < 120; ++i) world.step();

    render::RenderScene scene;
    ShowFlags flags;
    flags.contacts = true;
    addShowOverlays(scene, world, flags);
    ASSERT_EQ(scene.overlay.dots.size(), 8u) << "four corners under each box";
    Real length[2] = {0, 0};  // light, heavy
    int normals = 0;
    for (const render::OverlayLine& line : scene.overlay.lines) {
        const Vec3 along = line.to - line.from;
        EXPECT_LT(along.normalized().cross(Vec3::UnitZ()).norm(), 1e-12) << "along the floor's normal";
        if (line.arrow) {
            ++normals;
            continue;
        }
        length[line.from.x() > 0] += along.norm();
    }
    EXPECT_EQ(normals, 8);
    // Measured: both sums 2.2e-16 off, the ratio 2 exactly.
    const Real step = world.settings().gravity.norm() * world.settings().timeStep;
    for (int b = 0; b < 2; ++b)
        EXPECT_NEAR(length[b], kContactImpulseLength * world.bodies()[std::size_t(b)].mass() * step, 1e-14 * length[b]);
    EXPECT_NEAR(length[1] / length[0], 2, 1e-14);
}

TEST(ConsoleOverlays, TheHighlightedBodyTakesTheHighlightColourAndALabel) {
    Console c;
    ShowFlags flags;
    flags.highlightBody = "RHAND";
    const render::RenderScene scene = screenshotScene(c.session, flags);
    const int hand = c.world().definition(c.world().figureIds().front()).findBody("rhand");
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) EXPECT_EQ(scene.bodies[b].colour.has_value(), int(b) == hand) << b;
    ASSERT_EQ(scene.overlay.labels.size(), 1u);
    EXPECT_EQ(scene.overlay.labels.front().text, "rhand");
}

}  // namespace
}  // namespace af::console
