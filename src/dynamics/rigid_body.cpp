// Rigid bodies: construction from mass properties, and the world-space quantities the solver and
// the tests read. Integration lives in integration.cpp.

#include "af/dynamics/rigid_body.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace af {
namespace {

// Eigenvalues below this fraction of the largest are raised to it. Real shapes stay far above it
// (a 1:100 rod has a ratio of about 6e-4); what falls below comes from inertiaScale or a
// degenerate hull, and would otherwise let the smallest torque spin the body without bound.
constexpr Real kMinInertiaRatio = 1e-6;

bool isDiagonal(const Mat3& m) {
    return m(0, 1) == 0 && m(0, 2) == 0 && m(1, 0) == 0 && m(1, 2) == 0 && m(2, 0) == 0 && m(2, 1) == 0;
}

struct InertiaPair {
    Mat3 inertia;
    Mat3 inverse;
};

// The symmetric part of `raw`, made positive definite, and its inverse.
InertiaPair usableInertia(const Mat3& raw) {
    const Mat3 sym = (raw + raw.transpose()) / 2;

    if (isDiagonal(sym)) {
        const Vec3 d = sym.diagonal();
        const Real floor = d.maxCoeff() * kMinInertiaRatio;
        if (d.maxCoeff() > 0 && d.minCoeff() >= floor) {
            // Exact reciprocals: a body spinning about a principal axis then stays exactly on it.
            return {sym, Vec3(1 / d.x(), 1 / d.y(), 1 / d.z()).asDiagonal()};
        }
    }

    const Eigen::SelfAdjointEigenSolver<Mat3> eig(sym);
    const Vec3 lambda = eig.eigenvalues();  // ascending
    const Real largest = lambda.z();
    if (eig.info() != Eigen::Success || !(largest > 0)) {
        return {Mat3::Identity(), Mat3::Identity()};
    }
    const Real floor = largest * kMinInertiaRatio;
    if (lambda.x() >= floor) {
        // Already fine: keep the caller's matrix as given and invert it directly (more accurate
        // than going through the eigenvectors), symmetrised against rounding.
        const Mat3 inv = sym.inverse();
        return {sym, (inv + inv.transpose()) / 2};
    }
    const Mat3& v = eig.eigenvectors();
    const Vec3 clamped = lambda.cwiseMax(floor);
    const Mat3 inertia = v * clamped.asDiagonal() * v.transpose();
    const Mat3 inverse = v * clamped.cwiseInverse().asDiagonal() * v.transpose();
    return {(inertia + inertia.transpose()) / 2, (inverse + inverse.transpose()) / 2};
}

Mat3 symmetricPart(const Mat3& m) { return (m + m.transpose()) / 2; }

}  // namespace

RigidBody RigidBody::dynamic(Real mass, const Mat3& inertia, const Vec3& position, const Quat& orientation) {
    if (!std::isfinite(mass) || !(mass > 0)) {
        throw std::invalid_argument("RigidBody::dynamic: mass must be finite and positive, got " +
                                    std::to_string(mass));
    }
    if (!inertia.allFinite()) {
        throw std::invalid_argument("RigidBody::dynamic: inertia tensor has a non-finite entry");
    }
    const Real qn = orientation.norm();
    if (!std::isfinite(qn) || !(qn > 0)) {
        throw std::invalid_argument("RigidBody::dynamic: orientation quaternion is zero or not finite");
    }

    RigidBody body;
    body.position = position;
    body.orientation = Quat(orientation.coeffs() / qn);
    body.inverseMass = 1 / mass;
    const InertiaPair pair = usableInertia(inertia);
    body.inertia = pair.inertia;
    body.inverseInertia = pair.inverse;
    return body;
}

Mat3 RigidBody::inverseInertiaWorld() const { return inverseInertiaWorld(rotation()); }

Mat3 RigidBody::inverseInertiaWorld(const Mat3& r) const {
    // Symmetrised so that solver matrices built from it stay exactly symmetric.
    return symmetricPart(r * inverseInertia * r.transpose());
}

Mat3 RigidBody::inertiaWorld() const {
    const Mat3 r = rotation();
    return symmetricPart(r * inertia * r.transpose());
}

Vec3 RigidBody::angularMomentum() const {
    if (inverseMass == 0) {
        return Vec3::Zero();
    }
    return mass() * position.cross(linearVelocity) + inertiaWorld() * angularVelocity;
}

Real RigidBody::kineticEnergy() const {
    if (inverseMass == 0) {
        return 0;
    }
    return (mass() * linearVelocity.squaredNorm() + angularVelocity.dot(inertiaWorld() * angularVelocity)) / 2;
}

}  // namespace af
