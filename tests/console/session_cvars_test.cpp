// The simulation cvars (Doom's af_* and g_gravity) change the session's world at once and hold
// across a map load; what each rule does to the motion is tested on the World
// (tests/dynamics/world_settings_test.cpp).

#include "console/session.h"

#include <gtest/gtest.h>

namespace af::console {
namespace {

struct CvarsConsole {
    std::string errors;
    CommandSystem commands{Output([](std::string_view) {}, [this](std::string_view l) { errors += std::string(l) + "\n"; })};
    Session session{{AF_SOURCE_DIR}, commands};
    bool run(std::string_view text) { return commands.execute(text, "test.cfg").ok(); }
    const WorldSettings& settings() const { return session.world().settings(); }
};

TEST(SessionCvars, WithoutGravityASpawnedRagdollStaysWhereItWasPut) {
    CvarsConsole c;
    ASSERT_TRUE(c.run("set g_gravity 0; spawn ragdoll_humanoid origin \"0 0 40\"")) << c.errors;
    const FigureId id = c.session.world().figureIds().at(0);
    const std::vector<RigidPose> before = c.session.world().bodyPoses(id);
    ASSERT_TRUE(c.run("step 30")) << c.errors;
    const std::vector<RigidPose> after = c.session.world().bodyPoses(id);
    for (std::size_t i = 0; i < before.size(); ++i) EXPECT_LT((after[i].position - before[i].position).norm(), 1e-9) << i;
    ASSERT_TRUE(c.run("set g_gravity 1066; step 30")) << c.errors;
    EXPECT_LT(c.session.world().body({id, 0}).position.z(), before[0].position.z() - 5) << "gravity back: it falls";
}

TEST(SessionCvars, EachCvarSetsItsWorldSettingAndHoldsAcrossAMapLoad) {
    CvarsConsole c;
    ASSERT_TRUE(c.run("set af_timeScale 0.5; set af_skipLimits 1; set af_skipFriction 1; set af_skipSelfCollision 1; "
                      "set af_forceFriction 2; set af_maxLinearVelocity 64; set af_maxAngularVelocity 1; "
                      "set af_useLinearTime 0; set g_gravity 500"))
        << c.errors;
    for (int pass = 0; pass < 2; ++pass) {
        SCOPED_TRACE(pass == 0 ? "as set" : "after a map load");
        const WorldSettings& s = c.settings();
        EXPECT_DOUBLE_EQ(s.timeStep, 0.5 / 60);
        EXPECT_FALSE(s.rows.limits);
        EXPECT_FALSE(s.rows.friction);
        EXPECT_FALSE(s.contact.friction);
        EXPECT_TRUE(s.collision.skipSelfCollision);
        EXPECT_EQ(s.rows.forcedFriction, 2);
        EXPECT_DOUBLE_EQ(s.integration.maxLinearSpeed, 64 / (0.5 / 60));
        EXPECT_DOUBLE_EQ(s.integration.maxAngularSpeed, 1 / (0.5 / 60));
        EXPECT_EQ(s.solver, SolverKind::Exact);
        EXPECT_EQ(s.gravity, Vec3(0, 0, -500));
        ASSERT_TRUE(c.run("map " AF_SOURCE_DIR "/maps/default.map")) << c.errors;
    }
    const Real t = c.session.world().time();
    ASSERT_TRUE(c.run("step"));
    EXPECT_DOUBLE_EQ(c.session.world().time() - t, 0.5 / 60) << "a step is 1/60 s times af_timeScale";
    ASSERT_TRUE(c.run("set af_forceFriction -1; reset af_useLinearTime"));
    EXPECT_EQ(c.settings().rows.forcedFriction, 0) << "-1, Doom's default, forces nothing";
    EXPECT_EQ(c.settings().solver, SolverKind::Tree);
}

TEST(SessionCvars, OutOfRangeValuesAreRefusedAndChangeNothing) {
    CvarsConsole c;
    const WorldSettings before = c.settings();
    for (const char* bad : {"set g_gravity nan", "set af_timeScale 0", "set af_timeScale inf", "set af_maxLinearVelocity -1",
                            "set af_forceFriction 1e9", "set af_skipLimits maybe"}) {
        c.errors.clear();
        EXPECT_FALSE(c.run(bad)) << bad;
        EXPECT_FALSE(c.errors.empty()) << bad;
    }
    EXPECT_EQ(c.settings().gravity, before.gravity);
    EXPECT_EQ(c.settings().timeStep, before.timeStep);
    EXPECT_EQ(c.settings().integration.maxLinearSpeed, before.integration.maxLinearSpeed);
    EXPECT_EQ(c.settings().rows, before.rows);
}

}  // namespace
}  // namespace af::console
