// af-console's screenshot scene (console_screenshot.h): the af_show* cvars' overlays sit where
// the joints and bodies are, and with every cvar off the picture is af-sim's.

#include "console_screenshot.h"

#include "console/show_geometry.h"

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
