#include "af/geometry/math.h"

#include <cmath>
#include <numbers>

namespace af {

Mat3 rotationFromAngles(Real pitchDeg, Real yawDeg, Real rollDeg) {
    constexpr Real kDegToRad = std::numbers::pi_v<Real> / 180;
    const Real sp = std::sin(pitchDeg * kDegToRad), cp = std::cos(pitchDeg * kDegToRad);
    const Real sy = std::sin(yawDeg * kDegToRad), cy = std::cos(yawDeg * kDegToRad);
    const Real sr = std::sin(rollDeg * kDegToRad), cr = std::cos(rollDeg * kDegToRad);

    // Doom's rows (forward, left, up) of idAngles::ToMat3, §0.2, become our columns.
    Mat3 r;
    r.col(0) << cp * cy, cp * sy, -sp;
    r.col(1) << sr * sp * cy - cr * sy, sr * sp * sy + cr * cy, sr * cp;
    r.col(2) << cr * sp * cy + sr * sy, cr * sp * sy - sr * cy, cr * cp;
    return r;
}

}  // namespace af
