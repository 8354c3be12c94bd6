#include "orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace af::view {

namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;
constexpr Real kMaxPitch = kPi / 2 - 0.01;  // straight up or down would lose the screen's up
constexpr Real kRadiansPerPixel = 0.008;

}  // namespace

void OrbitCamera::lookAt(const Vec3& eye, const Vec3& target, Real fovYDegrees) {
    const Vec3 d = target - eye;
    target_ = target;
    distance_ = std::max(d.norm(), Real(1e-3));
    yaw_ = std::atan2(d.y(), d.x());
    pitch_ = std::clamp(std::asin(std::clamp(d.z() / distance_, Real(-1), Real(1))), -kMaxPitch, kMaxPitch);
    fovY_ = fovYDegrees;
}

Vec3 OrbitCamera::forward() const {
    return {std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_)};
}
Vec3 OrbitCamera::right() const { return forward().cross(Vec3::UnitZ()).normalized(); }
Vec3 OrbitCamera::up() const { return right().cross(forward()); }
Vec3 OrbitCamera::eye() const { return target_ - distance_ * forward(); }

void OrbitCamera::rotate(Real dxPixels, Real dyPixels) {
    yaw_ -= dxPixels * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ - dyPixels * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(Real dxPixels, Real dyPixels, int height) {
    // The target moves with the cursor: one pixel is this many units at the target's depth.
    const Real unitsPerPixel = 2 * distance_ * std::tan(fovY_ * kPi / 360) / std::max(height, 1);
    target_ += unitsPerPixel * (-dxPixels * right() + dyPixels * up());
}

void OrbitCamera::look(Real dxPixels, Real dyPixels) {
    const Vec3 eyeBefore = eye();
    rotate(dxPixels, dyPixels);
    target_ = eyeBefore + distance_ * forward();
}

void OrbitCamera::fly(Real forwardUnits, Real rightUnits, Real upUnits) {
    target_ += forwardUnits * forward() + rightUnits * right() + upUnits * Vec3::UnitZ();
}

void OrbitCamera::zoom(Real steps) { distance_ = std::clamp(distance_ * std::pow(0.88, steps), Real(1), Real(1e6)); }

Eigen::Matrix4f OrbitCamera::viewMatrix() const {
    const Vec3 r = right(), u = up(), f = forward(), e = eye();
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<1, 3>(0, 0) = r.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -r.dot(e);
    m(1, 3) = -u.dot(e);
    m(2, 3) = f.dot(e);
    return m.cast<float>();
}

Eigen::Matrix4f OrbitCamera::projectionMatrix(Real aspect) const {
    const Real f = 1 / std::tan(fovY_ * kPi / 360), n = nearDepth(), far = distance_ * 1000;
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 0) = f / aspect;
    m(1, 1) = f;
    m(2, 2) = (far + n) / (n - far);
    m(2, 3) = 2 * far * n / (n - far);
    m(3, 2) = -1;
    return m.cast<float>();
}

std::optional<Eigen::Vector2d> OrbitCamera::project(const Vec3& world, int width, int height) const {
    const Vec3 d = world - eye();
    const Real depth = d.dot(forward());
    if (depth < nearDepth()) return std::nullopt;
    const Real f = 1 / std::tan(fovY_ * kPi / 360), aspect = Real(width) / height;
    return Eigen::Vector2d(width / 2.0 * (1 + f / aspect * d.dot(right()) / depth), height / 2.0 * (1 - f * d.dot(up()) / depth));
}

Ray OrbitCamera::ray(Real x, Real y, int width, int height) const {
    const Real f = 1 / std::tan(fovY_ * kPi / 360), aspect = Real(width) / height;
    const Real sx = (2 * x / width - 1) * aspect / f, sy = (1 - 2 * y / height) / f;
    return {eye(), (forward() + sx * right() + sy * up()).normalized()};
}

}  // namespace af::view
