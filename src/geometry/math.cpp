#include "af/geometry/math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace af {

// Below this cos(pitch), yaw and roll turn about the same axis to within the angle whose cosine
// it is, so putting the whole turn into yaw (Doom's rule) moves the rebuilt rotation by less than
// π × 1e-12 rad; above it atan2 on the forward axis is accurate enough for roll to absorb the rest.
constexpr Real kGimbalLockCosine = 1e-12;

Mat3 rotationFromAngles(Real pitchDeg, Real yawDeg, Real rollDeg) {
    constexpr Real kDegToRad = std::numbers::pi_v<Real> / 180;
    const Real sp = std::sin(pitchDeg * kDegToRad), cp = std::cos(pitchDeg * kDegToRad);
    const Real sy = std::sin(yawDeg * kDegToRad), cy = std::cos(yawDeg * kDegToRad);
    const Real sr = std::sin(rollDeg * kDegToRad), cr = std::cos(rollDeg * kDegToRad);

    // Doom's rows (forward, left, up) of idAngles::ToMat3 (docs/conventions.md §0.2) become our columns.
    Mat3 r;
    r.col(0) << cp * cy, cp * sy, -sp;
    r.col(1) << sr * sp * cy - cr * sy, sr * sp * sy + cr * cy, sr * cp;
    r.col(2) << cr * sp * cy + sr * sy, cr * sp * sy - sr * cy, cr * cp;
    return r;
}

Vec3 anglesFromRotation(const Mat3& r) {
    constexpr Real kRadToDeg = 180 / std::numbers::pi_v<Real>;
    // Doom's axis A is Rᵀ, so A[i][j] = R(j, i).
    const Real sp = std::clamp(r(2, 0), Real(-1), Real(1));
    const Real cp = std::sqrt(r(0, 0) * r(0, 0) + r(1, 0) * r(1, 0));
    if (cp > 8192 * std::numeric_limits<float>::epsilon())
        return Vec3(-std::asin(sp), std::atan2(r(1, 0), r(0, 0)), std::atan2(r(2, 1), r(2, 2))) * kRadToDeg;
    return Vec3(-std::asin(sp), -std::atan2(r(0, 1), r(1, 1)), 0) * kRadToDeg;
}

Vec3 anglesFromRotationPrecise(const Mat3& r) {
    constexpr Real kRadToDeg = 180 / std::numbers::pi_v<Real>;
    // Pitch from atan2 rather than asin: asin loses half the digits where its slope grows near ±90°.
    const Real cp = std::hypot(r(0, 0), r(1, 0));
    const Real pitch = std::atan2(-r(2, 0), cp) * kRadToDeg;
    const Real yaw = (cp > kGimbalLockCosine ? std::atan2(r(1, 0), r(0, 0)) : -std::atan2(r(0, 1), r(1, 1))) * kRadToDeg;
    // R = Rz(yaw) · Ry(pitch) · Rx(roll) (docs/conventions.md §0.2), so what remains is Rx(roll).
    const Mat3 remainder = rotationFromAngles(pitch, yaw, 0).transpose() * r;
    const Real roll = std::atan2(remainder(2, 1), remainder(1, 1)) * kRadToDeg;
    return Vec3(pitch, yaw, roll);
}

}  // namespace af
