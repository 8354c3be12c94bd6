#include "af/dynamics/rest.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace af {

namespace {

// The angle of the rotation between two orientations, in degrees. atan2 of the sine and cosine
// parts stays accurate for tiny and near-180° turns, where acos of the trace alone does not.
Real turnDegrees(const Mat3& from, const Mat3& to) {
    const Mat3 m = from.transpose() * to;
    const Vec3 twiceSinAxis(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
    const Real angle = std::atan2(Real(0.5) * twiceSinAxis.norm(), Real(0.5) * (m.trace() - 1));
    return angle * 180 / std::numbers::pi_v<Real>;
}

// Written as "not within" so that NaN counts as over the threshold.
bool over(const Vec3& v, Real threshold) { return !(v.norm() <= threshold); }

// Like std::max, but a NaN sticks: a NaN move must never look like no move.
Real largest(Real a, Real b) { return std::isnan(a) || std::isnan(b) ? std::numeric_limits<Real>::quiet_NaN() : std::max(a, b); }

}  // namespace

RestSettings restSettingsFrom(const AFSettings& s) {
    RestSettings r;
    r.suspendLinearVelocity = s.suspendLinearVelocity;
    r.suspendAngularVelocity = s.suspendAngularVelocity;
    r.suspendLinearAcceleration = s.suspendLinearAcceleration;
    r.suspendAngularAcceleration = s.suspendAngularAcceleration;
    r.noMoveTime = s.noMoveTime;
    r.noMoveTranslation = s.noMoveTranslation;
    r.noMoveRotation = s.noMoveRotation;
    r.minMoveTime = s.minMoveTime;
    r.maxMoveTime = s.maxMoveTime;
    return r;
}

bool RestMonitor::update(Real dt, std::span<const BodyMotion> bodies) {
    if (atRest_) return true;
    if (!(dt > 0)) return false;

    activateTime_ += dt;
    if (settings_.minMoveTime > 0 && activateTime_ < settings_.minMoveTime) return false;
    if (settings_.maxMoveTime > 0 && activateTime_ > settings_.maxMoveTime) return atRest_ = true;
    if (windowAllowsRest(dt, bodies)) return atRest_ = true;
    if (allBelowSuspendThresholds(bodies)) return atRest_ = true;
    return false;
}

bool RestMonitor::windowAllowsRest(Real dt, std::span<const BodyMotion> bodies) {
    if (!windowOpen_) {
        recorded_.resize(bodies.size());
        for (std::size_t i = 0; i < bodies.size(); ++i) recorded_[i] = bodies[i].pose;
        windowOpen_ = true;
        windowTime_ = 0;
        windowTranslation_ = 0;
        windowRotation_ = 0;
        return false;
    }
    if (bodies.size() != recorded_.size())
        throw std::invalid_argument("RestMonitor::update: the figure had " + std::to_string(recorded_.size()) +
                                    " bodies when the movement window opened and has " +
                                    std::to_string(bodies.size()) + " now");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const RigidPose& now = bodies[i].pose;
        windowTranslation_ = largest(windowTranslation_, (now.position - recorded_[i].position).norm());
        windowRotation_ = largest(windowRotation_, turnDegrees(recorded_[i].rotation, now.rotation));
    }
    // Doom's accumulator starts at dt on the recording step and the window closes on the first
    // step that finds it past noMoveTime; windowTime_ counts the same steps.
    windowTime_ += dt;
    if (!(windowTime_ > settings_.noMoveTime)) return false;
    windowOpen_ = false;
    return windowTranslation_ < settings_.noMoveTranslation && windowRotation_ < settings_.noMoveRotation;
}

bool RestMonitor::allBelowSuspendThresholds(std::span<const BodyMotion> bodies) const {
    return std::none_of(bodies.begin(), bodies.end(), [&](const BodyMotion& b) {
        return over(b.linearVelocity, settings_.suspendLinearVelocity) ||
               over(b.angularVelocity, settings_.suspendAngularVelocity) ||
               over(b.linearAcceleration, settings_.suspendLinearAcceleration) ||
               over(b.angularAcceleration, settings_.suspendAngularAcceleration);
    });
}

void RestMonitor::wake() {
    atRest_ = false;
    activateTime_ = 0;
    windowOpen_ = false;
    windowTime_ = 0;
}

}  // namespace af
