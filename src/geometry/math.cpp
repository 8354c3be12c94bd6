#include "af/geometry/math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace af {

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

}  // namespace af
