// Rigid bodies and their integration, checked against closed forms and conservation laws:
// semi-implicit Euler free fall, torque-free tumbling (angular momentum and energy), principal
// axes, speed caps, rate-independent air friction, exact rotation, and static bodies.

#include "af/dynamics/rigid_body.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

namespace af {
namespace {

constexpr Real kDt = Real(1) / 60;
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
constexpr Real kInf = std::numeric_limits<Real>::infinity();
const Vec3 kDoomGravity(0, 0, -1066);

using AngleAxis = Eigen::AngleAxis<Real>;

Quat someOrientation() { return Quat(AngleAxis(0.7, Vec3(1, 2, -1).normalized())); }

// inertia diag(1, 2, 3): three distinct principal moments, a valid (triangle-inequality) tensor.
RigidBody asymmetricBody(const Quat& orientation = someOrientation()) {
    return RigidBody::dynamic(2.5, Vec3(1, 2, 3).asDiagonal(), Vec3(3, -1, 2), orientation);
}

void step(RigidBody& body, Real dt, const Vec3& gravity = Vec3::Zero(), const IntegrationSettings& settings = {}) {
    integrateVelocity(body, gravity, dt, settings);
    integratePosition(body, dt);
}

bool finite(const RigidBody& b) {
    return b.position.allFinite() && b.orientation.coeffs().allFinite() && b.linearVelocity.allFinite() &&
           b.angularVelocity.allFinite();
}

// Angle in radians between two vectors (atan2 form: accurate for tiny angles).
Real angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// Rotation angle taking orientation a to orientation b.
Real rotationAngle(const Quat& a, const Quat& b) { return Eigen::AngleAxis<Real>(b * a.inverse()).angle(); }

// Runs a torque-free tumble and checks world angular momentum (magnitude and direction, relative
// tolerance `tol`) and that the kinetic energy never rises by more than rounding.
void expectTorqueFreeConservation(RigidBody body, int steps, Real tol) {
    const Vec3 l0 = body.angularMomentum();
    const Real e0 = body.kineticEnergy();
    Real previous = e0;
    Real worstMagnitude = 0, worstDirection = 0, worstRise = 0;
    for (int n = 0; n < steps; ++n) {
        step(body, kDt);
        const Vec3 l = body.angularMomentum();
        const Real e = body.kineticEnergy();
        worstMagnitude = std::max(worstMagnitude, std::abs(l.norm() - l0.norm()) / l0.norm());
        worstDirection = std::max(worstDirection, angleBetween(l, l0));
        worstRise = std::max(worstRise, (e - previous) / e0);
        previous = e;
    }
    EXPECT_LE(worstMagnitude, tol);
    EXPECT_LE(worstDirection, tol);
    EXPECT_LE(worstRise, 1e-14) << "kinetic energy rose within a step";
    EXPECT_LE(previous, e0);
}

TEST(RigidBodyIntegration, FreeFallFollowsTheExactSemiImplicitEulerFormula) {
    // Velocity first, then position with the new velocity: after n steps (t = n·dt)
    //   v_n = v0 + g t,   x_n = x0 + v0 t + ½ g t² + ½ g dt t,
    // the continuous parabola plus the scheme's own ½ g dt t.
    RigidBody body = RigidBody::dynamic(3, Mat3::Identity(), Vec3(1, 2, 3), Quat::Identity());
    const Vec3 x0 = body.position, v0(30, -20, 400);
    body.linearVelocity = v0;
    // 7 s: the speed stays under the default cap of 7680 units/s (reached after 7.6 s).
    for (int n = 1; n <= 420; ++n) {
        step(body, kDt, kDoomGravity);
        const Real t = n * kDt;
        const Vec3 x = x0 + v0 * t + kDoomGravity * (t * t / 2) + kDoomGravity * (kDt * t / 2);
        const Vec3 v = v0 + kDoomGravity * t;
        ASSERT_LE((body.position - x).norm(), 1e-11 * x.norm()) << "step " << n;
        ASSERT_LE((body.linearVelocity - v).norm(), 1e-12 * v.norm()) << "step " << n;
    }
}

TEST(RigidBodyIntegration, ForceAddsToGravityAsAcceleration) {
    RigidBody body = RigidBody::dynamic(4, Mat3::Identity(), Vec3::Zero(), Quat::Identity());
    body.force = Vec3(8, 0, 4264);  // 4264 / 4 = 1066 holds the body up against gravity
    step(body, kDt, kDoomGravity);
    EXPECT_NEAR(body.linearVelocity.x(), kDt * 2, 1e-15);
    EXPECT_NEAR(body.linearVelocity.y(), 0, 0);
    EXPECT_NEAR(body.linearVelocity.z(), 0, 1e-12);
    EXPECT_EQ(body.force, Vec3(8, 0, 4264)) << "integration must not clear the force";
}

TEST(RigidBodyIntegration, TorqueFreeBodyAboutAGeneralAxisKeepsAngularMomentumAndLosesEnergyOnly) {
    RigidBody body = asymmetricBody();
    body.angularVelocity = Vec3(0.9, -1.4, 2.1);
    body.linearVelocity = Vec3(0.5, -2, 1);  // m x × v must stay constant too
    expectTorqueFreeConservation(body, 600, 1e-6);
}

TEST(RigidBodyIntegration, TorqueFreeBodyNearItsIntermediateAxisKeepsAngularMomentum) {
    RigidBody body = asymmetricBody(Quat::Identity());
    body.angularVelocity = Vec3(0.02, 3, 0.02);  // unstable axis: the Dzhanibekov tumble
    expectTorqueFreeConservation(body, 600, 1e-6);
}

TEST(RigidBodyIntegration, FastSpinNearTheCapStillKeepsAngularMomentum) {
    RigidBody body = asymmetricBody();
    body.angularVelocity = Vec3(30, -50, 60);  // 84 rad/s, 1.4 rad per step
    expectTorqueFreeConservation(body, 600, 1e-6);
}

TEST(RigidBodyIntegration, ImplicitGyroscopicTermDampsATumbleOntoTheMajorAxis) {
    // The price of the implicit scheme: the energy it loses is the tumble (nutation), never the
    // momentum, so a free body ends up spinning about its largest-inertia axis (body z here) with
    // the least energy its |L| allows, |L|²/(2·I_max). A real free body would tumble forever.
    RigidBody body = asymmetricBody();
    body.angularVelocity = Vec3(2.7, -4.2, 6.3);  // 8 rad/s: settles within seconds
    body.linearVelocity.setZero();
    const Real l = body.angularMomentum().norm();  // v = 0: same about the origin and the centre
    for (int n = 0; n < 900; ++n) step(body, kDt);  // 15 s
    EXPECT_NEAR(body.kineticEnergy(), l * l / (2 * 3), 1e-9 * body.kineticEnergy());
    EXPECT_LE(angleBetween(body.angularVelocity, body.rotation() * Vec3::UnitZ()), 1e-4);
    EXPECT_NEAR(body.angularMomentum().norm(), l, 1e-12 * l);
}

TEST(RigidBodyIntegration, WithoutTheGyroscopicTermTheBodyStaysFinite) {
    IntegrationSettings settings;
    settings.gyroscopic = false;
    RigidBody body = asymmetricBody();
    body.angularVelocity = Vec3(0.9, -1.4, 2.1);
    for (int n = 0; n < 6000; ++n) {
        step(body, kDt, Vec3::Zero(), settings);
        ASSERT_TRUE(finite(body)) << "step " << n;
    }
    EXPECT_LE(body.angularVelocity.norm(), settings.maxAngularSpeed);
}

TEST(RigidBodyIntegration, SpinAboutAPrincipalAxisKeepsOmegaExactly) {
    for (int axis = 0; axis < 3; ++axis) {
        RigidBody body = asymmetricBody(Quat::Identity());
        body.angularVelocity = 2.3 * Vec3::Unit(axis);
        const Vec3 omega = body.angularVelocity;
        for (int n = 0; n < 600; ++n) step(body, kDt);
        EXPECT_EQ(body.angularVelocity, omega) << "axis " << axis;
    }
}

TEST(RigidBodyIntegration, SpinAboutATiltedPrincipalAxisKeepsOmegaToRounding) {
    for (int axis = 0; axis < 3; ++axis) {
        RigidBody body = asymmetricBody();
        body.angularVelocity = 2.3 * (body.rotation() * Vec3::Unit(axis));
        const Vec3 omega = body.angularVelocity;
        for (int n = 0; n < 600; ++n) step(body, kDt);
        EXPECT_LE((body.angularVelocity - omega).norm(), 1e-12 * omega.norm()) << "axis " << axis;
    }
}

// A body all but at rest (a resting ragdoll's limbs creep by 1e-14 rad/s) takes the implicit
// gyroscopic step as a fast one does: on both sides of dt|ω| = 4ε, where the solve keeps its
// guess without iterating, the body-frame ω' solves I ω' = exp(−dt[ω']×) I ω to rounding.
TEST(RigidBodyIntegration, AnAlmostStillBodyTurnsAsTheImplicitStepSays) {
    for (const Real turn : {1e-17, 5e-16, 9e-16, 2e-15, 1e-13}) {
        RigidBody body = asymmetricBody();
        body.angularVelocity = (turn / kDt) * Vec3(0.3, -0.8, 0.5).normalized();
        const Mat3 r = body.rotation();
        const Vec3 momentum = body.inertia * (r.transpose() * body.angularVelocity);
        integrateVelocity(body, Vec3::Zero(), kDt, {});
        const Vec3 omega = r.transpose() * body.angularVelocity;
        const Vec3 turned = Quat(AngleAxis(-kDt * omega.norm(), omega.normalized())) * momentum;
        EXPECT_LE((body.inertia * omega - turned).norm(), 8 * std::numeric_limits<Real>::epsilon() * momentum.norm())
            << "dt|ω| = " << turn;
    }
}

TEST(RigidBodyIntegration, TorqueChangesAngularMomentumByItsImpulse) {
    RigidBody body = asymmetricBody();
    body.linearVelocity.setZero();
    body.position.setZero();  // so L about the origin is L about the centre of mass
    body.torque = Vec3(0.4, -0.3, 0.2);
    for (int n = 1; n <= 120; ++n) {
        step(body, kDt);
        const Vec3 expected = body.torque * (n * kDt);
        ASSERT_LE((body.angularMomentum() - expected).norm(), 1e-12 * expected.norm()) << "step " << n;
    }
}

TEST(RigidBodyIntegration, SpeedCapsClampMagnitudeAndKeepDirection) {
    const IntegrationSettings settings;
    RigidBody body = asymmetricBody();
    const Vec3 v(3e4, -4e4, 1.2e4), w(-200, 100, 50);
    body.linearVelocity = v;
    body.angularVelocity = w;
    integrateVelocity(body, Vec3::Zero(), kDt, settings);
    EXPECT_NEAR(body.linearVelocity.norm(), 128 * 60, 1e-15 * 128 * 60);
    EXPECT_NEAR(body.angularVelocity.norm(), 1.57 * 60, 1e-15 * 1.57 * 60);
    EXPECT_LE(angleBetween(body.linearVelocity, v), 1e-15);
    // The gyroscopic update turns ω a little before the cap, so check the cap on its own.
    body.angularVelocity = w;
    clampVelocity(body, settings);
    EXPECT_NEAR(body.angularVelocity.norm(), 1.57 * 60, 1e-15 * 1.57 * 60);
    EXPECT_LE(angleBetween(body.angularVelocity, w), 1e-15);

    RigidBody slow = asymmetricBody();
    slow.linearVelocity = Vec3(1, 2, 3);
    slow.angularVelocity = Vec3(0.1, 0.2, 0.3);
    const RigidBody before = slow;
    clampVelocity(slow, settings);
    EXPECT_EQ(slow.linearVelocity, before.linearVelocity);
    EXPECT_EQ(slow.angularVelocity, before.angularVelocity);
}

TEST(RigidBodyIntegration, OddCapsDoNotBlowUp) {
    RigidBody body = asymmetricBody();
    body.linearVelocity = Vec3(1, 2, 3);
    body.angularVelocity = Vec3(4, 5, 6);
    IntegrationSettings none;
    none.maxLinearSpeed = kInf;
    none.maxAngularSpeed = kNaN;
    clampVelocity(body, none);
    EXPECT_EQ(body.linearVelocity, Vec3(1, 2, 3));
    EXPECT_EQ(body.angularVelocity, Vec3(4, 5, 6));
    IntegrationSettings negative;
    negative.maxLinearSpeed = -1;
    negative.maxAngularSpeed = 0;
    clampVelocity(body, negative);
    EXPECT_EQ(body.linearVelocity, Vec3::Zero());
    EXPECT_EQ(body.angularVelocity, Vec3::Zero());
}

TEST(RigidBodyIntegration, AirFrictionHalvesSpeedAfterTheSameTimeAtAnyRate) {
    // f chosen so that Doom's 60 Hz rule halves linear speed in 0.5 s and angular in 0.25 s.
    const Real linearF = 1 - std::pow(2.0, -1.0 / 30), angularF = 1 - std::pow(2.0, -1.0 / 15);
    for (const int hz : {30, 60, 240}) {
        RigidBody body = asymmetricBody();
        body.linearFriction = linearF;
        body.angularFriction = angularF;
        body.linearVelocity = Vec3(10, -20, 5);
        body.angularVelocity = Vec3(1, 2, -3);
        const Real dt = Real(1) / hz;
        for (int n = 0; n < hz / 2; ++n) applyAirFriction(body, dt);
        EXPECT_NEAR(body.linearVelocity.norm(), Vec3(10, -20, 5).norm() / 2, 1e-13) << hz << " Hz";
        EXPECT_NEAR(body.angularVelocity.norm(), Vec3(1, 2, -3).norm() / 4, 1e-14) << hz << " Hz";
    }
}

TEST(RigidBodyIntegration, AirFrictionAt60HzIsDoomsPerStepRule) {
    RigidBody body = asymmetricBody();
    body.linearFriction = 0.005;
    body.angularFriction = 0.02;
    body.linearVelocity = Vec3(10, -20, 5);
    body.angularVelocity = Vec3(1, 2, -3);
    applyAirFriction(body, kDt);
    EXPECT_LE((body.linearVelocity - Vec3(10, -20, 5) * (1 - 0.005)).norm(), 1e-14);
    EXPECT_LE((body.angularVelocity - Vec3(1, 2, -3) * (1 - 0.02)).norm(), 1e-15);
}

TEST(RigidBodyIntegration, AirFrictionOutsideZeroToOneIsClamped) {
    struct Case { Real f; Real keep; };
    for (const Case c : {Case{-0.5, 1}, Case{kNaN, 1}, Case{1, 0}, Case{3, 0}, Case{kInf, 0}}) {
        RigidBody body = asymmetricBody();
        body.linearFriction = c.f;
        body.angularFriction = c.f;
        body.linearVelocity = Vec3(10, -20, 5);
        body.angularVelocity = Vec3(1, 2, -3);
        applyAirFriction(body, kDt / 4);
        EXPECT_EQ(body.linearVelocity, Vec3(10, -20, 5) * c.keep) << "f = " << c.f;
        EXPECT_EQ(body.angularVelocity, Vec3(1, 2, -3) * c.keep) << "f = " << c.f;
    }
}

TEST(RigidBodyIntegration, ConstantOmegaTurnsByExactlyDtTimesOmegaPerStep) {
    RigidBody body = asymmetricBody();
    const Quat q0 = body.orientation;
    const Vec3 omega(0.3, -1.1, 0.8);
    body.angularVelocity = omega;
    integratePosition(body, kDt);
    EXPECT_NEAR(rotationAngle(q0, body.orientation), kDt * omega.norm(), 1e-15);
    const int steps = 1000;
    for (int n = 1; n < steps; ++n) integratePosition(body, kDt);
    const Quat expected = Quat(AngleAxis(steps * kDt * omega.norm(), omega.normalized())) * q0;
    EXPECT_LE((body.rotation() - expected.toRotationMatrix()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(body.angularVelocity, omega);
}

TEST(RigidBodyIntegration, OrientationStaysUnitLengthOver100000Steps) {
    // Position steps only (the velocity step does not touch the orientation), so the test stays
    // quick in the sanitizer build.
    RigidBody body = asymmetricBody();
    body.angularVelocity = Vec3(0.9, -1.4, 2.1);
    Real worstNorm = 0, worstOrthogonality = 0;
    for (int n = 0; n < 100000; ++n) {
        integratePosition(body, kDt);
        worstNorm = std::max(worstNorm, std::abs(body.orientation.norm() - 1));
        if (n % 1000 == 999) {
            const Mat3 r = body.rotation();
            worstOrthogonality = std::max(worstOrthogonality, (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff());
        }
    }
    EXPECT_LE(worstNorm, 4 * std::numeric_limits<Real>::epsilon());
    EXPECT_LE(worstOrthogonality, 8 * std::numeric_limits<Real>::epsilon());
}

TEST(RigidBodyIntegration, StaticBodyNeverMoves) {
    RigidBody body;  // inverseMass 0
    body.position = Vec3(1, 2, 3);
    body.orientation = someOrientation();
    body.linearVelocity = Vec3(5, 6, 7);
    body.angularVelocity = Vec3(1, -1, 2);
    body.force = Vec3(100, 0, 0);
    body.torque = Vec3(0, 50, 0);
    body.linearFriction = body.angularFriction = 0.5;
    const RigidBody before = body;
    for (int n = 0; n < 600; ++n) {
        step(body, kDt, kDoomGravity);
        applyAirFriction(body, kDt);
    }
    EXPECT_EQ(body.position, before.position);
    EXPECT_EQ(body.orientation.coeffs(), before.orientation.coeffs());
    EXPECT_EQ(body.linearVelocity, before.linearVelocity);
    EXPECT_EQ(body.angularVelocity, before.angularVelocity);
    EXPECT_EQ(body.kineticEnergy(), 0);
    EXPECT_EQ(body.angularMomentum(), Vec3::Zero());
}

TEST(RigidBodyIntegration, SameInputsGiveBitIdenticalTrajectories) {
    const auto run = [] {
        RigidBody body = asymmetricBody();
        body.angularVelocity = Vec3(0.9, -1.4, 2.1);
        body.linearVelocity = Vec3(0.5, -2, 100);
        body.torque = Vec3(0.1, 0, -0.2);
        body.linearFriction = body.angularFriction = 0.01;
        for (int n = 0; n < 1000; ++n) {
            step(body, kDt, kDoomGravity);
            applyAirFriction(body, kDt);
        }
        return body;
    };
    const RigidBody a = run(), b = run();
    EXPECT_EQ(std::memcmp(a.position.data(), b.position.data(), sizeof(Real) * 3), 0);
    EXPECT_EQ(std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(), sizeof(Real) * 4), 0);
    EXPECT_EQ(std::memcmp(a.angularVelocity.data(), b.angularVelocity.data(), sizeof(Real) * 3), 0);
}

TEST(RigidBodyConstruction, UsesTheSymmetricPartAndItsInverse) {
    Mat3 raw;
    raw << 2, 0.4, 0, 0.2, 3, -0.1, 0, 0.1, 4;
    const RigidBody body = RigidBody::dynamic(5, raw, Vec3(1, 2, 3), someOrientation());
    Mat3 sym;
    sym << 2, 0.3, 0, 0.3, 3, 0, 0, 0, 4;
    EXPECT_LE((body.inertia - sym).cwiseAbs().maxCoeff(), 1e-16);
    EXPECT_EQ(body.inertia, body.inertia.transpose());
    EXPECT_LE((body.inertia * body.inverseInertia - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(body.inverseInertia, body.inverseInertia.transpose());
    EXPECT_EQ(body.inverseMass, 0.2);
    EXPECT_EQ(body.linearVelocity, Vec3::Zero());
    EXPECT_EQ(body.angularVelocity, Vec3::Zero());
}

TEST(RigidBodyConstruction, DiagonalInertiaIsInvertedEntryByEntry) {
    const RigidBody body = asymmetricBody();
    EXPECT_EQ(body.inverseInertia, Vec3(1, 0.5, 1.0 / 3).asDiagonal().toDenseMatrix());
}

TEST(RigidBodyConstruction, NonPositiveDefiniteInertiaIsRepairedWithoutNaN) {
    // inertiaScale [[1,5,0],[0,1,0],[0,0,1]] applied to diag(1,2,3): symmetric part with
    // eigenvalues ≈ −1.05, 3, 4.05.
    Mat3 scaled;
    scaled << 1, 5, 0, 0, 2, 0, 0, 0, 3;
    Mat3 negativeDiagonal = Vec3(1, -2, 3).asDiagonal();
    for (const Mat3& raw : {scaled, negativeDiagonal}) {
        RigidBody body = RigidBody::dynamic(2, raw, Vec3::Zero(), Quat::Identity());
        ASSERT_TRUE(body.inertia.allFinite() && body.inverseInertia.allFinite());
        const Eigen::SelfAdjointEigenSolver<Mat3> eig(body.inertia);
        const Vec3 lambda = eig.eigenvalues();
        EXPECT_NEAR(lambda.x(), 1e-6 * lambda.z(), 1e-15 * lambda.z()) << "floor at 1e-6·λmax";
        EXPECT_LE((body.inertia * body.inverseInertia - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-9);
        // The positive part of the tensor is kept.
        const Eigen::SelfAdjointEigenSolver<Mat3> rawEig(Mat3((raw + raw.transpose()) / 2));
        EXPECT_NEAR(lambda.y(), rawEig.eigenvalues().y(), 1e-14);
        EXPECT_NEAR(lambda.z(), rawEig.eigenvalues().z(), 1e-14);
        body.angularVelocity = Vec3(1, 2, 3);
        body.torque = Vec3(0.1, 0.2, -0.3);
        for (int n = 0; n < 600; ++n) step(body, kDt);
        EXPECT_TRUE(finite(body));
    }
}

TEST(RigidBodyConstruction, InertiaWithoutAPositiveEigenvalueBecomesIdentity) {
    for (const Mat3& raw : {Mat3(Mat3::Zero()), Mat3(-Mat3::Identity())}) {
        const RigidBody body = RigidBody::dynamic(2, raw, Vec3::Zero(), Quat::Identity());
        EXPECT_EQ(body.inertia, Mat3::Identity());
        EXPECT_EQ(body.inverseInertia, Mat3::Identity());
    }
}

TEST(RigidBodyConstruction, BadMassOrNonFiniteInertiaIsRefused) {
    const Mat3 i = Mat3::Identity();
    EXPECT_THROW(RigidBody::dynamic(0, i, Vec3::Zero(), Quat::Identity()), std::invalid_argument);
    EXPECT_THROW(RigidBody::dynamic(-1, i, Vec3::Zero(), Quat::Identity()), std::invalid_argument);
    EXPECT_THROW(RigidBody::dynamic(kNaN, i, Vec3::Zero(), Quat::Identity()), std::invalid_argument);
    EXPECT_THROW(RigidBody::dynamic(kInf, i, Vec3::Zero(), Quat::Identity()), std::invalid_argument);
    Mat3 bad = i;
    bad(1, 2) = kNaN;
    EXPECT_THROW(RigidBody::dynamic(1, bad, Vec3::Zero(), Quat::Identity()), std::invalid_argument);
    EXPECT_THROW(RigidBody::dynamic(1, i, Vec3::Zero(), Quat(0, 0, 0, 0)), std::invalid_argument);
}

TEST(RigidBodyConstruction, OrientationIsNormalised) {
    const RigidBody body = RigidBody::dynamic(1, Mat3::Identity(), Vec3::Zero(), Quat(2, 0, 0, 0));
    EXPECT_EQ(body.orientation.coeffs(), Quat::Identity().coeffs());
}

TEST(RigidBodyQuantities, WorldInertiaMomentumAndEnergyMatchTheirDefinitions) {
    RigidBody body = asymmetricBody();
    body.linearVelocity = Vec3(0.5, -2, 1);
    body.angularVelocity = Vec3(0.9, -1.4, 2.1);
    const Mat3 r = body.rotation();
    const Mat3 iw = r * Vec3(1, 2, 3).asDiagonal() * r.transpose();
    EXPECT_LE((body.inertiaWorld() - iw).cwiseAbs().maxCoeff(), 1e-15 * 3);
    EXPECT_LE((body.inertiaWorld() * body.inverseInertiaWorld() - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15 * 8);
    EXPECT_EQ(body.inertiaWorld(), body.inertiaWorld().transpose());
    EXPECT_EQ(body.inverseInertiaWorld(), body.inverseInertiaWorld().transpose());
    const Vec3 l = 2.5 * body.position.cross(body.linearVelocity) + iw * body.angularVelocity;
    EXPECT_LE((body.angularMomentum() - l).norm(), 1e-14 * l.norm());
    const Real e = 0.5 * 2.5 * body.linearVelocity.squaredNorm() + 0.5 * body.angularVelocity.dot(iw * body.angularVelocity);
    EXPECT_NEAR(body.kineticEnergy(), e, 1e-14 * e);
    EXPECT_EQ(body.mass(), 2.5);
}

}  // namespace
}  // namespace af
