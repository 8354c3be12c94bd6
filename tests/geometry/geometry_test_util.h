#pragma once
// Shared checks and sample shapes for the geometry tests.

#include "af/geometry/shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace af::test {

// |a − b| ≤ rel·max(|b|, floor): relative comparison that survives expected values of zero.
inline ::testing::AssertionResult nearRel(Real a, Real b, Real rel, Real floor = 1) {
    const Real tol = rel * std::max(std::abs(b), floor);
    if (std::abs(a - b) <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << a << " vs expected " << b << " (tol " << tol << ")";
}

// Matrices and vectors compared entry by entry against tolerance rel·max(‖expected‖, floor).
template <typename A, typename B>
::testing::AssertionResult nearRelM(const A& a, const B& b, Real rel, Real floor = 1) {
    const Real tol = rel * std::max(Real(b.norm()), floor);
    const Real err = (a - b).cwiseAbs().maxCoeff();
    if (err <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "max error " << err << " > " << tol << "\nactual:\n"
                                         << a << "\nexpected:\n" << b;
}

// Vertex lists compared as sets (orders that Doom's shapes do not pin down must not matter).
inline ::testing::AssertionResult sameVertexSet(std::vector<Vec3> actual, std::vector<Vec3> expected,
                                                Real tol) {
    if (actual.size() != expected.size()) {
        return ::testing::AssertionFailure() << actual.size() << " vertices, expected " << expected.size();
    }
    for (const Vec3& e : expected) {
        auto it = std::find_if(actual.begin(), actual.end(),
                               [&](const Vec3& a) { return (a - e).cwiseAbs().maxCoeff() <= tol; });
        if (it == actual.end()) {
            return ::testing::AssertionFailure() << "missing vertex " << e.transpose();
        }
        actual.erase(it);
    }
    return ::testing::AssertionSuccess();
}

inline Mat3 rotationAbout(const Vec3& axis, Real radians) {
    return Eigen::AngleAxis<Real>(radians, axis.normalized()).toRotationMatrix();
}

struct NamedShape {
    std::string name;
    Polytope    polytope;
};

// One or more non-degenerate instances of every shape family, deliberately off-centre and
// anisotropic, including bounds given max-before-min.
inline std::vector<NamedShape> sampleShapes() {
    std::vector<NamedShape> s;
    s.push_back({"box", makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6))});
    s.push_back({"box inverted x", makeBox(Vec3(4, -2, -3), Vec3(-1, 5, 6))});
    s.push_back({"octahedron", makeOctahedron(Vec3(-1, -2, -3), Vec3(3, 4, 5))});
    s.push_back({"octahedron inverted yz", makeOctahedron(Vec3(-1, 4, 5), Vec3(3, -2, -3))});
    s.push_back({"dodecahedron", makeDodecahedron(Vec3(-1, 0, 2), Vec3(3, 2, 7))});
    s.push_back({"dodecahedron inverted z", makeDodecahedron(Vec3(-1, 0, 7), Vec3(3, 2, 2))});
    for (int n = 3; n <= kMaxCylinderSides; ++n) {
        s.push_back({"cylinder " + std::to_string(n), makeCylinder(Vec3(1, -2, -1), Vec3(5, 4, 3), n)});
    }
    for (int n = 3; n <= kMaxConeSides; ++n) {
        s.push_back({"cone " + std::to_string(n), makeCone(Vec3(3, 1, -2), Vec3(7, 4, 6), n)});
    }
    s.push_back({"cone inverted x", makeCone(Vec3(7, 1, -2), Vec3(3, 4, 6), 5)});
    s.push_back({"bone", makeBone(12, 3)});
    return s;
}

}  // namespace af::test
