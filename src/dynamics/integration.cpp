// Time integration of one rigid body: velocities (forces, gravity, the gyroscopic term, caps),
// positions (exact rotation for the step's ω) and Doom's air friction made rate independent.
// The why of the gyroscopic scheme is in rigid_body.h next to integrateVelocity.

#include "af/dynamics/rigid_body.h"

#include <Eigen/LU>

#include <cmath>
#include <limits>

namespace af {
namespace {

// Doom applies its per-step rules at this rate (docs/doom-physics.md §4.7, §4.10).
constexpr Real kDoomStepsPerSecond = 60;

// Newton on the gyroscopic equation converges quadratically from ω; two or three iterations
// reach rounding for any |ω| under the caps. The bound only matters for absurd input.
constexpr int kMaxNewtonIterations = 12;
// A residual this small (relative to |L|) is rounding; stop.
constexpr Real kNewtonTolerance = 4 * std::numeric_limits<Real>::epsilon();
// Above this the residual still carries information, so a stalled iteration keeps trying.
constexpr Real kNewtonStallLevel = 1e-9;

Mat3 skew(const Vec3& a) {
    Mat3 k;
    k << 0, -a.z(), a.y(),
         a.z(), 0, -a.x(),
         -a.y(), a.x(), 0;
    return k;
}

// exp of the rotation vector φ: a turn by |φ| about φ̂, as a unit quaternion. The one place both
// integrators take their rotation from, so integrateVelocity predicts exactly what
// integratePosition will do.
Quat rotationFromVector(const Vec3& phi) {
    const Real angle = phi.norm();
    const Real half = angle / 2;
    // sin(|φ|/2)/|φ| by its series where the quotient would be 0/0; the next term is below ε.
    const Real s = angle < 1e-4 ? Real(0.5) * (1 - half * half / 6) : std::sin(half) / angle;
    // Below 2⁻²⁷, 1 − half²/2 is within half an ulp of 1, which is cos(half) rounded: a resting
    // body's turn (the bench ragdoll's: 0.7k of its 206k instructions per step in std::cos).
    const Real c = half < 0x1p-27 ? 1 : std::cos(half);
    return Quat(c, s * phi.x(), s * phi.y(), s * phi.z());
}

// Left Jacobian of SO(3): exp([φ + δ]×) ≈ exp([J(φ) δ]×) exp([φ]×) for small δ.
Mat3 leftJacobian(const Vec3& phi) {
    const Real t2 = phi.squaredNorm();
    Real a = 0, b = 0;
    if (t2 < 1e-8) {
        a = Real(0.5) - t2 / 24;
        b = Real(1) / 6 - t2 / 120;
    } else {
        const Real t = std::sqrt(t2);
        a = (1 - std::cos(t)) / t2;
        b = (t - std::sin(t)) / (t2 * t);
    }
    const Mat3 k = skew(phi);
    return Mat3::Identity() + a * k + b * (k * k);
}

// Body-frame angular velocity ω' with I ω' = exp(−dt [ω']×) m, by Newton's method from `guess`.
// With g(ω) = exp(−dt [ω]×) m the Jacobian of the residual I ω − g(ω) is I − dt [g]× J(−dt ω).
// Returns the iterate with the smallest residual, so a failing iteration can only stop early,
// never return something worse than the start.
Vec3 solveGyroscopic(const Mat3& inertia, const Vec3& m, const Vec3& guess, Real dt) {
    const Real scale = m.norm();
    Vec3 w = guess;
    Vec3 best = guess;
    Real bestResidual = std::numeric_limits<Real>::infinity();
    for (int k = 0;; ++k) {
        const Vec3 phi = -dt * w;
        const Vec3 g = rotationFromVector(phi) * m;
        const Vec3 f = inertia * w - g;
        const Real r = f.norm();
        if (!std::isfinite(r)) {
            break;
        }
        const bool improved = r < bestResidual;
        if (improved) {
            best = w;
            bestResidual = r;
        }
        if (r <= kNewtonTolerance * scale || k == kMaxNewtonIterations ||
            (!improved && r <= kNewtonStallLevel * scale)) {
            break;
        }
        const Mat3 jacobian = inertia - dt * skew(g) * leftJacobian(phi);
        const Vec3 step = jacobian.partialPivLu().solve(f);
        if (!step.allFinite()) {
            break;
        }
        w -= step;
    }
    return best;
}

// Scales v down to length `cap`, keeping its direction. NaN caps compare false and do nothing.
void clampLength(Vec3& v, Real cap) {
    if (cap < 0) {
        cap = 0;
    }
    const Real len = v.norm();
    if (len > cap) {
        v *= cap / len;
    }
}

bool isStatic(const RigidBody& body) { return body.inverseMass == 0; }

}  // namespace

void clampVelocity(RigidBody& body, const IntegrationSettings& settings) {
    clampLength(body.linearVelocity, settings.maxLinearSpeed);
    clampLength(body.angularVelocity, settings.maxAngularSpeed);
}

void integrateVelocity(RigidBody& body, const Vec3& gravity, Real dt, const IntegrationSettings& settings) {
    if (isStatic(body)) {
        return;
    }
    body.linearVelocity += dt * (gravity + body.inverseMass * body.force);

    // A zero inverse inertia means a body that cannot turn: no torque, no gyroscopic change.
    if (!body.inverseInertia.isZero(0)) {
        if (settings.gyroscopic) {
            const Mat3 r = body.rotation();
            const Vec3 omega = r.transpose() * body.angularVelocity;
            const bool torqued = !body.torque.isZero(0);
            // Without torque the guess ω leaves the residual |Iω − exp(−dt[ω]×) Iω| ≤ dt|ω|·|Iω|
            // (a turn by dt|ω| moves a vector by at most that fraction of it): within Newton's
            // tolerance when dt|ω| is, and Newton keeps it. A resting bench ragdoll's slowest
            // bodies: 2.4k of its 208k instructions per step not spent to find that out, and
            // their momentum is not formed either.
            if (!torqued && dt * omega.norm() <= kNewtonTolerance) {
                body.angularVelocity = r * omega;
            } else {
                // The torque acts as an impulse at the start of the step, the free motion
                // follows: the world angular momentum about the centre of mass changes by
                // exactly dt·τ. Most bodies carry no torque (a ragdoll's, but for springs):
                // adding a zero impulse changes nothing, and skipping it saved 0.8k of a resting
                // bench ragdoll's 209k instructions per step.
                Vec3 momentum = body.inertia * omega;
                Vec3 guess = omega;
                if (torqued) {
                    const Vec3 torqueImpulse = dt * (r.transpose() * body.torque);
                    momentum += torqueImpulse;
                    guess += body.inverseInertia * torqueImpulse;
                }
                body.angularVelocity = r * solveGyroscopic(body.inertia, momentum, guess, dt);
            }
        } else {
            body.angularVelocity += dt * (body.inverseInertiaWorld() * body.torque);
        }
    }
    clampVelocity(body, settings);
}

void integratePosition(RigidBody& body, Real dt) {
    if (isStatic(body)) {
        return;
    }
    body.position += dt * body.linearVelocity;
    // Left multiplication: ω is a world vector, so the turn happens in world axes.
    body.orientation = (rotationFromVector(dt * body.angularVelocity) * body.orientation).normalized();
}

void applyAirFriction(RigidBody& body, Real dt) {
    if (isStatic(body) || !(dt > 0)) {
        return;
    }
    const auto keep = [dt](Real f) -> Real {
        if (!(f > 0)) {
            return 1;  // negative friction would feed energy in; NaN means unset
        }
        if (f >= 1) {
            return 0;
        }
        return std::pow(1 - f, dt * kDoomStepsPerSecond);
    };
    body.linearVelocity *= keep(body.linearFriction);
    body.angularVelocity *= keep(body.angularFriction);
}

}  // namespace af
