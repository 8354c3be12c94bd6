// Contact rows with hand-made contacts: a box on a slope holds below the friction angle and
// slides as Coulomb says above it; a dropped box bounces only above the restitution threshold.

#include "dynamics/contact_rows.h"
#include "dynamics/world_access.h"
#include "world_test_util.h"

#include <cmath>
#include <numbers>

namespace af {
namespace {

constexpr Real kHalf = 5;

Figure box() {
    return test::figureFromText("articulatedFigure box {\nsettings { friction 0, 0, 0 }\n"
                                "body \"box\" { joint \"origin\" model box( ( -5, -5, -5 ), ( 5, 5, 5 ) ) "
                                "origin ( 0, 0, 5 ) density 0.2 }\n}\n",
                                test::namesOnlySkeleton({"origin"}));
}

// The ground is the plane z = 0; every corner of the box at or below it touches.
RowSource groundContacts(Real friction, Real restitution = 0) {
    return [friction, restitution](std::span<const RigidBody> bodies, ConstraintRows& rows) {
        const RigidBody& b = bodies[0];
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 local(corner & 1 ? kHalf : -kHalf, corner & 2 ? kHalf : -kHalf, corner & 4 ? kHalf : -kHalf);
            const Vec3 p = b.position + b.orientation * local;
            if (p.z() > 0.1) continue;
            Contact c;
            c.bodyA = 0;
            c.point = p;
            c.normal = Vec3::UnitZ();
            c.depth = -p.z();
            c.friction = friction;
            c.restitution = restitution;
            writeContactRows(c, bodies, ContactSettings{}, rows);
        }
    };
}

// Tilting gravity by `slope` degrees about Y is the same as tilting the ground.
Real slideAfter(Real slopeDegrees, Real friction, Real seconds) {
    WorldSettings settings;
    const Real a = slopeDegrees * std::numbers::pi / 180;
    settings.gravity = 1066 * Vec3(std::sin(a), 0, -std::cos(a));
    World world(box(), test::dynamicsOnly(settings));
    detail::WorldAccess::setContactSource(world, groundContacts(friction));
    const Real x0 = world.bodies()[0].position.x();
    for (int i = 0; i < static_cast<int>(seconds * 60); ++i) world.step();
    EXPECT_EQ(world.solverFailures(), 0);
    EXPECT_NEAR(world.bodies()[0].position.z(), kHalf, 0.1) << "the box must stay on the ground";
    return world.bodies()[0].position.x() - x0;
}

TEST(Contact, BoxHoldsOnASlopeBelowTheFrictionAngle) {
    const Real mu = 0.5;  // friction angle 26.6°
    EXPECT_LT(std::abs(slideAfter(20, mu, 2)), 0.05);
    EXPECT_LT(std::abs(slideAfter(26, mu, 2)), 0.05);
}

TEST(Contact, BoxSlidesAboveTheFrictionAngleAsCoulombSays) {
    const Real mu = 0.5, slope = 35, seconds = 1;
    const Real a = slope * std::numbers::pi / 180;
    const Real acceleration = 1066 * (std::sin(a) - mu * std::cos(a));
    const Real expected = 0.5 * acceleration * seconds * seconds;
    EXPECT_NEAR(slideAfter(slope, mu, seconds) / expected, 1.0, 0.03);
}

TEST(Contact, RestingBoxDoesNotSinkOrJitter) {
    World world(box(), test::dynamicsOnly());
    detail::WorldAccess::setContactSource(world, groundContacts(0.8));
    for (int i = 0; i < 300; ++i) world.step();
    EXPECT_NEAR(world.bodies()[0].position.z(), kHalf, ContactSettings{}.slop + 1e-6);
    EXPECT_LT(world.bodies()[0].linearVelocity.norm(), 1e-6);
    EXPECT_LT(world.bodies()[0].angularVelocity.norm(), 1e-6);
}

TEST(Contact, DroppedBoxBouncesWithItsRestitution) {
    World world(box(), test::dynamicsOnly());
    detail::WorldAccess::bodies(world)[0].position.z() = kHalf + 0.05;
    world.setVelocity(0, Vec3(0, 0, -300), world.bodies()[0].angularVelocity);
    detail::WorldAccess::setContactSource(world, groundContacts(0, 0.4));
    world.step();
    EXPECT_NEAR(world.bodies()[0].linearVelocity.z(), 0.4 * (300 + 1066.0 / 60), 1.0);
}

}  // namespace
}  // namespace af
