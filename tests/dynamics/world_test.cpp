// Physics of whole steps: pendulum period and energy, a hanging chain's joint error, momentum
// of a free figure, determinism. Each test states its tolerance.

#include "world_test_util.h"

#include <cmath>
#include <numbers>
#include <cstring>
#include <random>

namespace af {
namespace {

using test::horizontalChain;
using test::pendulum;


// Swings the pendulum's body rigidly about the pivot by `degrees` about +X.
void tilt(World& world, const Vec3& pivot, Real degrees) {
    const Quat turn(Eigen::AngleAxis<Real>(degrees * std::numbers::pi / 180, Vec3::UnitX()));
    RigidBody& bob = detail::WorldAccess::bodies(world)[0];  // before the first step
    bob.position = pivot + turn * (bob.position - pivot);
    bob.orientation = turn * bob.orientation;
}

// Times of upward zero crossings of the bob's y coordinate, linearly interpolated.
std::vector<Real> upwardCrossings(World& world, int steps) {
    std::vector<Real> crossings;
    Real previous = world.bodies()[0].position.y();
    for (int i = 0; i < steps; ++i) {
        const Real t0 = world.time();
        world.step();
        const Real y = world.bodies()[0].position.y();
        if (previous < 0 && y >= 0) crossings.push_back(t0 + (world.time() - t0) * (-previous) / (y - previous));
        previous = y;
    }
    return crossings;
}

TEST(WorldPendulum, PeriodMatchesSmallAngleTheory) {
    const Real half = 2, length = 30;
    World world(pendulum(half, length), test::dynamicsOnly());
    tilt(world, Vec3(0, 0, length), 2);
    const RigidBody& bob = world.bodies()[0];
    const Real m = bob.mass();
    const Real inertiaAboutPivot = bob.inertia(0, 0) + m * length * length;
    const Real g = -world.settings().gravity.z();
    const Real expected = 2 * std::numbers::pi * std::sqrt(inertiaAboutPivot / (m * g * length));

    const std::vector<Real> crossings = upwardCrossings(world, static_cast<int>(12 * expected * 60));
    ASSERT_GE(crossings.size(), 10u);
    const Real measured = (crossings.back() - crossings.front()) / Real(crossings.size() - 1);
    EXPECT_NEAR(measured / expected, 1.0, 0.005) << "measured " << measured << " s, expected " << expected << " s";
}

// Semi-implicit Euler's energy wobbles within each swing (by about ω·dt/2, 5 % here); what must
// not happen is a drift. Compare the mean energy of the first and of the hundredth period.
TEST(WorldPendulum, EnergyDriftsLessThanOnePercentOverAHundredPeriods) {
    const Real half = 2, length = 30;
    World world(pendulum(half, length), test::dynamicsOnly());
    const Real bottom = test::potentialEnergy(world);
    tilt(world, Vec3(0, 0, length), 30);
    const Real swing = test::potentialEnergy(world) + world.kineticEnergy() - bottom;  // of the oscillation
    const RigidBody& bob = world.bodies()[0];
    const Real period = 2 * std::numbers::pi * std::sqrt((bob.inertia(0, 0) + bob.mass() * length * length) /
                                            (bob.mass() * -world.settings().gravity.z() * length));
    const int perPeriod = static_cast<int>(std::lround(period * 60));
    auto meanOverOnePeriod = [&] {
        Real sum = 0;
        for (int i = 0; i < perPeriod; ++i) {
            world.step();
            sum += test::potentialEnergy(world) + world.kineticEnergy() - bottom;
        }
        return sum / perPeriod;
    };
    const Real first = meanOverOnePeriod();
    for (int p = 0; p < 98; ++p) meanOverOnePeriod();
    const Real last = meanOverOnePeriod();
    EXPECT_LT(std::abs(last - first) / swing, 0.01) << "mean energy " << first << " -> " << last << " of " << swing;
    EXPECT_LT(world.maxJointError(), 1e-9);
}

// A chain of 20 hanging links released 30° from the vertical: a hard, chaotic swing.
Real runChain(SolverKind solver, Real seconds) {
    WorldSettings settings;
    settings.solver = solver;
    World world(test::hangingChain(20, 300), test::dynamicsOnly(settings));
    test::swingAbout(world, Vec3(0, 0, 300), 30);
    Real worst = 0;
    for (int i = 0; i < static_cast<int>(seconds * 60); ++i) {
        world.step();
        worst = std::max(worst, world.maxJointError());
    }
    if (solver == SolverKind::Exact) {
        EXPECT_EQ(world.solverFailures(), 0);
    }
    if (solver == SolverKind::Pgs) {
        EXPECT_GT(detail::WorldAccess::counters(world).iterations, 0) << "PGS solved the velocities";
    }
    return worst;
}

TEST(WorldChain, TwentyLinksKeepTheirJointsWithinATenThousandthOfAUnit) {
    const Real exact = runChain(SolverKind::Exact, 10);
    EXPECT_LT(exact, 1e-4);
    // With PGS for the velocities the projection (dense, as the chain is small) still closes the
    // joints to positionTolerance (1e-10) every step: measured 1.05e-10 (exact 1.02e-10).
    const Real pgs = runChain(SolverKind::Pgs, 10);
    EXPECT_LT(pgs, 5e-10);
    RecordProperty("max_joint_error_exact", std::to_string(exact));
    RecordProperty("max_joint_error_pgs", std::to_string(pgs));
    std::printf("hanging chain of 20, 10 s: max joint error exact %.3g, PGS %.3g units\n", exact, pgs);
}

// A 20-link chain released `degrees` from hanging, 10 s: the worst joint error, and the most
// energy it ever had above its start.
struct Whip {
    Real worstJoint = 0, worstGain = 0, start = 0;
    int failures = 0;
};
Whip whipFrom(Real degrees) {
    World world(test::hangingChain(20, 300), test::dynamicsOnly());
    test::swingAbout(world, Vec3(0, 0, 300), degrees);
    Whip whip;
    whip.start = test::potentialEnergy(world);
    for (int i = 0; i < 600; ++i) {
        world.step();
        whip.worstJoint = std::max(whip.worstJoint, world.maxJointError());
        whip.worstGain = std::max(whip.worstGain, test::potentialEnergy(world) + world.kineticEnergy() - whip.start);
    }
    whip.failures = world.solverFailures();
    return whip;
}

// Released horizontally, a long chain whips its end round far faster than it fell: the joints
// must hold and the motion must never have more energy than the fall released. The whip is
// chaotic: release angles 1e-10 degrees apart end in different whips, and some (e.g. +21e-10)
// spin the end links ~1.4 rad per step, which 8 projection passes did not close. One angle alone
// passed or failed by luck, so several run.
TEST(WorldChain, ChainReleasedHorizontallyWhipsWithoutGainingEnergy) {
    for (const int k : {-24, -13, -5, 0, 7, 15, 21, 23}) {
        SCOPED_TRACE(k);
        const Whip whip = whipFrom(90 + k * 1e-10);
        EXPECT_LT(whip.worstJoint, 1e-4);
        EXPECT_LE(whip.worstGain, 1e-6 * std::abs(whip.start)) << "energy gained " << whip.worstGain;
        EXPECT_EQ(whip.failures, 0);
    }
}

// Released from 30-80 degrees its end links turn up to 2 rad a step. These angles gained 4.3,
// 8.5, 8.7 and 10.8 % of the energy through SHAKE's velocity change before SHAKE was refused
// where it leaves more kinetic energy than the step had (Island::keepsMoreEnergy).
TEST(WorldChain, ChainReleasedFromSteepAnglesWhipsWithoutGainingEnergy) {
    for (const Real degrees : {32.5, 51.25, 57.5, 78.75}) {
        SCOPED_TRACE(degrees);
        const Whip whip = whipFrom(degrees);
        EXPECT_LT(whip.worstJoint, 1e-4);
        EXPECT_LE(whip.worstGain, 1e-6 * std::abs(whip.start)) << "energy gained " << whip.worstGain;
        EXPECT_EQ(whip.failures, 0);
    }
}

TEST(WorldChain, TwoRunsAreBitIdentical) {
    auto run = [] {
        World world(horizontalChain(8, 100), test::dynamicsOnly());
        for (int i = 0; i < 120; ++i) world.step();
        std::vector<Real> state;
        for (const RigidBody& b : world.bodies()) {
            state.insert(state.end(), b.position.data(), b.position.data() + 3);
            state.insert(state.end(), b.orientation.coeffs().data(), b.orientation.coeffs().data() + 4);
            state.insert(state.end(), b.linearVelocity.data(), b.linearVelocity.data() + 3);
        }
        return state;
    };
    const std::vector<Real> a = run(), b = run();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)), 0);
}

// Joint forces are internal: with no gravity and no air friction a tumbling chain keeps its
// momentum. The links are cubes, whose free rotation integrates exactly, so whatever changes
// the angular momentum would be the joints' doing.
// A body of no figure (World's bodies-and-joints constructor) takes its velocities by index.
TEST(WorldBodies, ABodyOfNoFigureTakesItsVelocitiesByIndex) {
    WorldSettings settings;
    settings.gravity.setZero();
    World world({RigidBody::dynamic(1, Mat3::Identity(), Vec3::Zero(), Quat::Identity())}, {}, settings);
    world.setVelocity(0, Vec3(60, 0, 0), Vec3(0, 0, 1));
    world.step();
    EXPECT_NEAR(world.bodies()[0].position.x(), 1, 1e-12) << "60 units/s for 1/60 s";
    EXPECT_LT((world.bodies()[0].angularVelocity - Vec3(0, 0, 1)).norm(), 1e-12) << "a free spin keeps its rate";
}

TEST(WorldChain, InternalForcesConserveMomentum) {
    WorldSettings settings;
    settings.gravity.setZero();
    World world(horizontalChain(6, 0, true, 5), test::dynamicsOnly(settings));
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> speed(-20, 20), spin(-2, 2);
    for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b) {
        const Vec3 linear = Vec3(speed(rng), speed(rng), speed(rng));
        const Vec3 angular = Vec3(spin(rng), spin(rng), spin(rng));
        world.setVelocity(b, linear, angular);
    }
    auto momentum = [&] {
        Vec3 p = Vec3::Zero(), l = Vec3::Zero();
        for (const RigidBody& b : world.bodies()) {
            p += b.linearMomentum();
            l += b.angularMomentum();
        }
        return std::pair{p, l};
    };
    // The random start breaks every joint; the first steps bring the velocities in line, and
    // their position corrections do move momentum. From then on the joints' impulses are internal.
    for (int i = 0; i < 10; ++i) world.step();
    const auto [p0, l0] = momentum();
    for (int i = 0; i < 120; ++i) world.step();
    const auto [p1, l1] = momentum();
    EXPECT_LE((p1 - p0).norm(), 1e-9 * p0.norm()) << p0.transpose() << " -> " << p1.transpose();
    EXPECT_LE((l1 - l0).norm(), 1e-6 * l0.norm()) << l0.transpose() << " -> " << l1.transpose();
    EXPECT_LT(world.maxJointError(), 1e-6);
}

}  // namespace
}  // namespace af
