#pragma once
// af-soak's random numbers: one stream per drop, from the drop's seed. Draws are made from the
// 64-bit Mersenne twister's raw output (the standard distributions are not the same on every
// standard library), one draw per statement, so that a seed gives the same drop everywhere.

#include "af/geometry/math.h"

#include <cmath>
#include <cstdint>
#include <random>

namespace af::soak {

class Random {
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}

    Real uniform(Real lo, Real hi) {
        const Real unit = static_cast<Real>(engine_() >> 11) * 0x1.0p-53;  // [0, 1)
        return lo + (hi - lo) * unit;
    }
    // lo..hi, both included.
    int between(int lo, int hi) {
        return lo + static_cast<int>(engine_() % static_cast<std::uint64_t>(hi - lo + 1));
    }
    bool chance(Real p) { return uniform(0, 1) < p; }
    // 10^uniform(lo, hi): a factor spread evenly over orders of magnitude.
    Real decades(Real lo, Real hi) { return std::pow(Real(10), uniform(lo, hi)); }
    // A direction, uniform on the sphere.
    Vec3 direction() {
        const Real z = uniform(-1, 1);
        const Real phi = uniform(0, 2 * Real(3.14159265358979323846));
        const Real r = std::sqrt(std::max(Real(0), 1 - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    // A rotation by up to `maxAngle` radians about a random axis (maxAngle π: any rotation).
    Mat3 rotation(Real maxAngle) {
        const Vec3 axis = direction();
        const Real angle = uniform(0, maxAngle);
        return Eigen::AngleAxis<Real>(angle, axis).toRotationMatrix();
    }

private:
    std::mt19937_64 engine_;
};

}  // namespace af::soak
