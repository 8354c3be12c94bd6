#pragma once
// Shapes, poses, invariants every manifold must satisfy, and a brute-force separating-axis
// reference for the narrowphase tests.

#include "af/collision/collision_world.h"
#include "af/collision/narrowphase.h"
#include "af/geometry/shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>

namespace af::test {

// Contacts agree with the reference to this, units.
inline constexpr Real kTol = 1e-9;

// A ragdoll body's contents, and what it collides with (docs/formats.md, contents).
inline constexpr ContentsMask kCorpse = contents::Corpse;
inline constexpr ContentsMask kHits = contents::Solid | contents::Corpse;

inline Polytope box(const Vec3& half) { return makeBox(-half, half); }

inline Mat3 rotation(const Vec3& axis, Real degrees) {
    return Eigen::AngleAxis<Real>(degrees * std::numbers::pi / 180, axis.normalized()).toRotationMatrix();
}

inline RigidPose pose(const Vec3& position, const Mat3& rot = Mat3::Identity()) { return {position, rot}; }

// A rotation drawn uniformly (a normalised Gaussian quaternion).
inline Mat3 randomRotation(std::mt19937& rng) {
    std::normal_distribution<Real> g;
    return Eigen::Quaternion<Real>(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

inline Vec3 randomVector(std::mt19937& rng, Real lo, Real hi) {
    std::uniform_real_distribution<Real> u(lo, hi);
    return {u(rng), u(rng), u(rng)};
}

inline Real deepest(const Manifold& m) {
    Real d = -std::numeric_limits<Real>::infinity();
    for (int i = 0; i < m.count; ++i) {
        d = std::max(d, m.points[i].depth);
    }
    return d;
}

inline std::set<std::uint32_t> ids(const Manifold& m) {
    std::set<std::uint32_t> s;
    for (int i = 0; i < m.count; ++i) {
        s.insert(m.points[i].id);
    }
    return s;
}

// What holds for every manifold: at most four finite points with distinct ids, a finite unit
// normal, depths no shallower than −margin.
inline ::testing::AssertionResult wellFormed(const Manifold& m, Real margin) {
    if (m.count < 0 || m.count > Manifold::kMaxPoints) {
        return ::testing::AssertionFailure() << "count " << m.count;
    }
    if (!m.normal.allFinite() || std::abs(m.normal.norm() - 1) > 1e-12) {
        return ::testing::AssertionFailure() << "normal " << m.normal.transpose();
    }
    for (int i = 0; i < m.count; ++i) {
        const ManifoldPoint& p = m.points[i];
        if (!p.point.allFinite() || !std::isfinite(p.depth) || p.depth < -margin - 1e-9) {
            return ::testing::AssertionFailure() << "point " << i << " at " << p.point.transpose() << " depth "
                                                 << p.depth;
        }
    }
    if (int(ids(m).size()) != m.count) {
        return ::testing::AssertionFailure() << "repeated ids";
    }
    return ::testing::AssertionSuccess();
}

inline Polytope placed(const Polytope& p, const RigidPose& pose) { return transformed(p, pose.rotation, pose.position); }

// min over A − max over B along `normal` (from B towards A), shapes already in the world.
inline Real separationAlong(const Polytope& a, const Polytope& b, const Vec3& normal) {
    Real minA = std::numeric_limits<Real>::infinity(), maxB = -minA;
    for (const Vec3& v : a.vertices) {
        minA = std::min(minA, normal.dot(v));
    }
    for (const Vec3& v : b.vertices) {
        maxB = std::max(maxB, normal.dot(v));
    }
    return minA - maxB;
}

// The largest separation over every face normal of both and every cross product of two edges,
// both orientations: for polytopes with volume, minus the penetration depth when they overlap.
struct SatReference {
    Real separation = -std::numeric_limits<Real>::infinity();
    Vec3 normal = Vec3::Zero();  // from B towards A
};

inline SatReference bruteForceSat(const Polytope& a, const Polytope& b) {
    SatReference best;
    auto consider = [&](Vec3 axis) {
        if (axis.norm() < 1e-9) {
            return;
        }
        axis.normalize();
        for (const Vec3& n : {axis, Vec3(-axis)}) {
            const Real s = separationAlong(a, b, n);
            if (s > best.separation) {
                best = {s, n};
            }
        }
    };
    for (const Face& f : a.faces) {
        consider(f.normal);
    }
    for (const Face& f : b.faces) {
        consider(f.normal);
    }
    for (const auto& ea : a.edges) {
        for (const auto& eb : b.edges) {
            consider((a.vertices[ea[1]] - a.vertices[ea[0]]).cross(b.vertices[eb[1]] - b.vertices[eb[0]]));
        }
    }
    return best;
}

}  // namespace af::test
