#pragma once
// LCP problems for the tests and the benchmark: owning storage, deterministic random problems of
// several kinds, and a ragdoll-sized problem built from Jacobians the way the engine will build it.
// Header-only so that bench/bench_lcp.cpp can use the same scene.

#include "dynamics/lcp.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

namespace af::test {

/// An LCP that owns its arrays; view() gives the solvers' LcpProblem.
struct DenseLcp {
    int               n = 0;
    std::vector<Real> a, b, lo, hi, mu, cfm;
    std::vector<int>  findex;

    explicit DenseLcp(int size = 0)
        : n(size), a(static_cast<std::size_t>(size) * size, 0), b(size, 0), lo(size, -kLcpInfinity),
          hi(size, kLcpInfinity) {}

    Real& at(int i, int j) { return a[static_cast<std::size_t>(i) * n + j]; }
    Real  at(int i, int j) const { return a[static_cast<std::size_t>(i) * n + j]; }
    bool  isCoupled(int i) const { return !findex.empty() && findex[i] >= 0; }

    void couple(int row, int normal, Real coefficient) {
        if (findex.empty()) {
            findex.assign(n, -1);
            mu.assign(n, 0);
        }
        findex[row] = normal;
        mu[row] = coefficient;
    }

    LcpProblem view() const { return LcpProblem{n, a, b, lo, hi, findex, mu, cfm}; }
};

/// Deterministic on every platform (the standard distributions are not): splitmix64.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    Real uniform() { return static_cast<Real>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    Real uniform(Real lo, Real hi) { return lo + (hi - lo) * uniform(); }
    int  below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
    bool chance(Real p) { return uniform() < p; }

private:
    std::uint64_t state_;
};

using MatX = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

/// A vector of three uniform draws from [lo, hi) each, made z first, then y, then x. Spelled out
/// because a call's arguments are evaluated in an unspecified order (GCC right to left, clang left
/// to right), so Vec3(rng.uniform(), rng.uniform(), rng.uniform()) made other problems under each
/// compiler; this is GCC's order, the one the counts in the tests were measured with.
struct Interval {
    Real lo, hi;
};
inline Eigen::Matrix<Real, 3, 1> uniformVector(Rng& rng, Interval x, Interval y, Interval z) {
    const Real zDraw = rng.uniform(z.lo, z.hi);
    const Real yDraw = rng.uniform(y.lo, y.hi);
    const Real xDraw = rng.uniform(x.lo, x.hi);
    return {xDraw, yDraw, zDraw};
}

inline void setMatrix(DenseLcp& p, const MatX& m) {
    for (int i = 0; i < p.n; ++i) {
        for (int j = 0; j < p.n; ++j) {
            p.at(i, j) = 0.5 * (m(i, j) + m(j, i));  // exactly symmetric
        }
    }
}

/// MᵀM + εI with M uniform in [−1, 1]: dense, positive definite, condition number up to ~10³.
inline MatX randomGram(Rng& rng, int n) {
    MatX m(n, n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            m(i, j) = rng.uniform(-1, 1);
        }
    }
    const Real eps = rng.uniform(0.02, 0.5);
    return m.transpose() * m + eps * MatX::Identity(n, n);
}

/// J W Jᵀ like a constraint system: `bodies` bodies of 6 velocity components with positive
/// inverse masses, each row touching one or two of them. Singular when n > 6·bodies or rows
/// repeat; positive definite only with CFM.
inline MatX randomJacobianGram(Rng& rng, int n, int bodies) {
    MatX j = MatX::Zero(n, 6 * bodies);
    for (int r = 0; r < n; ++r) {
        const int first = rng.below(bodies);
        const int second = bodies > 1 && rng.chance(0.6) ? (first + 1 + rng.below(bodies - 1)) % bodies : -1;
        for (int c = 0; c < 6; ++c) {
            j(r, 6 * first + c) = rng.uniform(-1, 1);
            if (second >= 0) {
                j(r, 6 * second + c) = rng.uniform(-1, 1);
            }
        }
    }
    Eigen::Matrix<Real, Eigen::Dynamic, 1> w(6 * bodies);
    for (int k = 0; k < 6 * bodies; ++k) {
        w(k) = rng.uniform(0.1, 2.0);
    }
    return j * w.asDiagonal() * j.transpose();
}

/// Random bounds of every kind: equality, one-sided, boxed, fixed, including boxes that do not
/// contain 0.
inline void randomBounds(Rng& rng, DenseLcp& p, int row) {
    const Real u = rng.uniform();
    Real       lo = -kLcpInfinity;
    Real       hi = kLcpInfinity;
    if (u < 0.15) {
        // equality row
    } else if (u < 0.40) {
        lo = rng.chance(0.6) ? 0 : rng.uniform(-1, 0.5);
    } else if (u < 0.50) {
        hi = rng.chance(0.5) ? 0 : rng.uniform(-0.5, 1);
    } else if (u < 0.92) {
        lo = rng.uniform(-1, 0.3);
        hi = lo + rng.uniform(0.01, 1.5);
    } else {
        lo = hi = rng.uniform(-0.5, 0.5);
    }
    p.lo[row] = lo;
    p.hi[row] = hi;
}

/// A random positive definite A for p: a dense Gram, or (half the time) a Jacobian Gram of rows on
/// one or two bodies with CFM, as contacts and joints make.
inline void setRandomMatrix(Rng& rng, DenseLcp& p) {
    if (rng.chance(0.5)) {
        setMatrix(p, randomGram(rng, p.n));
        return;
    }
    setMatrix(p, randomJacobianGram(rng, p.n, 1 + rng.below(2)));
    p.cfm.resize(static_cast<std::size_t>(p.n));
    for (Real& c : p.cfm) c = rng.uniform(1e-3, 0.05);
}

/// A small uncoupled problem: n rows, positive definite (Gram, or Jacobian Gram plus CFM).
inline DenseLcp randomUncoupledProblem(Rng& rng, int n) {
    DenseLcp p(n);
    setRandomMatrix(rng, p);
    for (int i = 0; i < n; ++i) {
        randomBounds(rng, p, i);
        p.b[i] = rng.uniform(-1, 1);
    }
    return p;
}

/// A small problem with contacts: `contacts` triples (normal ≥ 0, two friction rows coupled to
/// it) followed by `others` rows of random kinds. A is a Jacobian Gram with CFM (contact-like)
/// or a dense Gram.
inline DenseLcp randomCoupledProblem(Rng& rng, int contacts, int others) {
    const int n = 3 * contacts + others;
    DenseLcp p(n);
    setRandomMatrix(rng, p);
    for (int c = 0; c < contacts; ++c) {
        const int normal = 3 * c;
        p.lo[normal] = 0;
        p.couple(normal + 1, normal, rng.uniform(0.05, 1.2));
        p.couple(normal + 2, normal, rng.uniform(0.05, 1.2));
    }
    for (int i = 3 * contacts; i < n; ++i) {
        randomBounds(rng, p, i);
    }
    for (int i = 0; i < n; ++i) {
        p.b[i] = rng.uniform(-1, 1);
    }
    // Normals mostly pushed into contact, so that friction has something to be bounded by.
    for (int c = 0; c < contacts; ++c) {
        p.b[3 * c] = rng.uniform(-0.3, 1.5);
    }
    return p;
}

/// A small physical problem: one or two rigid bodies (random mass and box inertia) touching the
/// ground at `contacts` points (normal +Z, friction along X and Y coupled to it, mu up to 1.2),
/// plus `jointRows` linear rows of a point joint between the bodies. A = J M⁻¹ Jᵀ with small
/// CFM, b = −J v for a random velocity that mostly moves into the ground.
inline DenseLcp randomContactProblem(Rng& rng, int contacts, int jointRows) {
    using Vec3 = Eigen::Matrix<Real, 3, 1>;
    const int n = 3 * contacts + jointRows;
    const int bodies = jointRows > 0 ? 2 : 1;
    MatX      jac = MatX::Zero(n, 6 * bodies);
    DenseLcp  p(n);
    p.cfm.assign(n, 0);
    auto linear = [&](int row, int body, const Vec3& r, const Vec3& dir, Real sign) {
        jac.block<1, 3>(row, 6 * body) = sign * dir.transpose();
        jac.block<1, 3>(row, 6 * body + 3) = sign * r.cross(dir).transpose();
    };
    for (int c = 0; c < contacts; ++c) {
        const int  body = rng.below(bodies);
        const Vec3 r = uniformVector(rng, {-0.5, 0.5}, {-0.5, 0.5}, {-0.3, -0.05});
        const int  normal = 3 * c;
        linear(normal, body, r, Vec3::UnitZ(), 1);
        p.lo[normal] = 0;
        p.cfm[normal] = rng.uniform(1e-6, 1e-3);
        for (int k = 0; k < 2; ++k) {
            linear(normal + 1 + k, body, r, Vec3::Unit(k), 1);
            p.couple(normal + 1 + k, normal, rng.uniform(0.05, 1.2));
            p.cfm[normal + 1 + k] = rng.uniform(1e-6, 1e-3);
        }
    }
    const Vec3 anchor0 = uniformVector(rng, {-0.3, 0.3}, {-0.3, 0.3}, {0, 0.3});
    const Vec3 anchor1 = uniformVector(rng, {-0.3, 0.3}, {-0.3, 0.3}, {-0.3, 0});
    for (int k = 0; k < jointRows; ++k) {
        const int row = 3 * contacts + k;
        linear(row, 0, anchor0, Vec3::Unit(k), -1);
        linear(row, 1, anchor1, Vec3::Unit(k), 1);
        p.cfm[row] = rng.uniform(1e-6, 1e-3);
    }
    Eigen::Matrix<Real, Eigen::Dynamic, 1> invMass(6 * bodies), v(6 * bodies);
    for (int body = 0; body < bodies; ++body) {
        const Real m = rng.uniform(0.5, 10);
        const Vec3 h = uniformVector(rng, {0.1, 0.6}, {0.1, 0.6}, {0.1, 0.6});
        const Vec3 h2 = h.cwiseProduct(h);
        invMass.segment<3>(6 * body).setConstant(1 / m);
        invMass.segment<3>(6 * body + 3) = (m / 3 * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y())).cwiseInverse();
        v.segment<3>(6 * body) = uniformVector(rng, {-2, 2}, {-2, 2}, {-2, 0.5});
        v.segment<3>(6 * body + 3) = uniformVector(rng, {-2, 2}, {-2, 2}, {-2, 2});
    }
    setMatrix(p, jac * invMass.asDiagonal() * jac.transpose());
    const Eigen::Matrix<Real, Eigen::Dynamic, 1> jv = jac * v;
    for (int r = 0; r < n; ++r) {
        p.b[r] = -jv(r);
    }
    return p;
}

/// The ragdoll-sized problem of the benchmark: the 16 bodies of docs/bench-scene.md (SI units) in
/// their T-pose, 15 joints (2 fixed = 6 rows, 9 ball-and-socket = 3 rows, 4 hinges = 5 rows:
/// 59 equality rows), 10 one-sided limit rows, and 8 ground contacts with 2 friction rows each
/// (24 rows): 93 rows. Body velocities are random around a fall onto the ground, some contacts
/// sliding; `seed` picks them, `jitter` scales an extra perturbation of b (the "next step").
inline DenseLcp makeRagdollProblem(std::uint64_t seed, Real jitter = 0) {
    using Vec3 = Eigen::Matrix<Real, 3, 1>;
    struct Body {
        Vec3 half, centre;
        Real mass;
    };
    const std::array<Body, 16> bodies = {{
        {{0.170, 0.100, 0.070}, {0.000, 0.000, 0.930}, 9.940},  {{0.150, 0.100, 0.110}, {0.000, 0.000, 1.110}, 9.730},
        {{0.205, 0.110, 0.140}, {0.000, 0.000, 1.360}, 15.120}, {{0.080, 0.100, 0.140}, {0.000, 0.000, 1.640}, 5.670},
        {{0.150, 0.050, 0.050}, {0.355, 0.000, 1.370}, 1.960},  {{0.125, 0.045, 0.045}, {0.630, 0.000, 1.370}, 1.120},
        {{0.065, 0.045, 0.020}, {0.820, 0.000, 1.370}, 0.420},  {{0.150, 0.050, 0.050}, {-0.355, 0.000, 1.370}, 1.960},
        {{0.125, 0.045, 0.045}, {-0.630, 0.000, 1.370}, 1.120}, {{0.065, 0.045, 0.020}, {-0.820, 0.000, 1.370}, 0.420},
        {{0.075, 0.075, 0.190}, {0.140, 0.000, 0.670}, 7.000},  {{0.060, 0.060, 0.200}, {0.140, 0.000, 0.280}, 3.255},
        {{0.050, 0.130, 0.040}, {0.140, 0.070, 0.040}, 1.015},  {{0.075, 0.075, 0.190}, {-0.140, 0.000, 0.670}, 7.000},
        {{0.060, 0.060, 0.200}, {-0.140, 0.000, 0.280}, 3.255}, {{0.050, 0.130, 0.040}, {-0.140, 0.070, 0.040}, 1.015},
    }};
    enum Kind { Fixed, Ball, Hinge };
    struct Joint {
        int  parent, child;
        Kind kind;
        Vec3 anchor, axis;
    };
    const std::array<Joint, 15> joints = {{
        {0, 1, Fixed, {0, 0, 1.00}, {1, 0, 0}},      {1, 2, Fixed, {0, 0, 1.22}, {1, 0, 0}},
        {2, 3, Ball, {0, 0, 1.50}, {0, 0, 1}},       {2, 4, Ball, {0.205, 0, 1.37}, {1, 0, 0}},
        {4, 5, Hinge, {0.505, 0, 1.37}, {0, 0, 1}},  {5, 6, Ball, {0.755, 0, 1.37}, {1, 0, 0}},
        {2, 7, Ball, {-0.205, 0, 1.37}, {1, 0, 0}},  {7, 8, Hinge, {-0.505, 0, 1.37}, {0, 0, 1}},
        {8, 9, Ball, {-0.755, 0, 1.37}, {1, 0, 0}},  {0, 10, Ball, {0.14, 0, 0.86}, {0, 0, 1}},
        {10, 11, Hinge, {0.14, 0, 0.48}, {1, 0, 0}}, {11, 12, Ball, {0.14, 0, 0.08}, {0, 0, 1}},
        {0, 13, Ball, {-0.14, 0, 0.86}, {0, 0, 1}},  {13, 14, Hinge, {-0.14, 0, 0.48}, {1, 0, 0}},
        {14, 15, Ball, {-0.14, 0, 0.08}, {0, 0, 1}},
    }};
    constexpr int kBodies = 16;
    constexpr int kRows = 2 * 6 + 9 * 3 + 4 * 5 + 10 + 8 * 3;
    MatX          jac = MatX::Zero(kRows, 6 * kBodies);
    DenseLcp      p(kRows);
    std::vector<Real> rowCfm(kRows, 0);
    const Real    dt = 1.0 / 60;
    int           row = 0;

    auto linear = [&](int body, const Vec3& point, const Vec3& dir, Real sign) {
        const Vec3 r = point - bodies[body].centre;
        jac.block<1, 3>(row, 6 * body) = sign * dir.transpose();
        jac.block<1, 3>(row, 6 * body + 3) = sign * r.cross(dir).transpose();
    };
    auto angular = [&](int body, const Vec3& dir, Real sign) {
        jac.block<1, 3>(row, 6 * body + 3) = sign * dir.transpose();
    };
    auto perpendiculars = [](const Vec3& axis) {
        const Vec3 t1 = axis.unitOrthogonal();
        return std::array<Vec3, 2>{t1, axis.cross(t1)};
    };
    for (const Joint& jt : joints) {
        for (int k = 0; k < 3; ++k) {
            linear(jt.parent, jt.anchor, Vec3::Unit(k), -1);
            linear(jt.child, jt.anchor, Vec3::Unit(k), 1);
            rowCfm[row++] = 1e-7 / dt;
        }
        if (jt.kind == Fixed) {
            for (int k = 0; k < 3; ++k) {
                angular(jt.parent, Vec3::Unit(k), -1);
                angular(jt.child, Vec3::Unit(k), 1);
                rowCfm[row++] = 1e-7 / dt;
            }
        } else if (jt.kind == Hinge) {
            for (const Vec3& t : perpendiculars(jt.axis)) {
                angular(jt.parent, t, -1);
                angular(jt.child, t, 1);
                rowCfm[row++] = 1e-7 / dt;
            }
        }
    }
    // Limits on the hinges (one each) and on six ball joints' swing: one-sided angular rows.
    const std::array<int, 10> limited = {4, 7, 10, 13, 2, 3, 6, 9, 12, 5};
    const int                 firstLimit = row;
    for (int l = 0; l < 10; ++l) {
        const Joint& jt = joints[limited[l]];
        const Vec3   dir = l < 4 ? jt.axis : perpendiculars(jt.axis)[l % 2];
        angular(jt.parent, dir, -1);
        angular(jt.child, dir, 1);
        p.lo[row] = 0;
        rowCfm[row++] = 1e-4 / dt;
    }
    // Ground contacts under feet (two each), pelvis, hands and head: as if lying on the floor.
    struct Contact {
        int  body;
        Vec3 offset;
    };
    const std::array<Contact, 8> contacts = {{
        {12, {0, 0.1, -0.04}}, {12, {0, -0.1, -0.04}}, {15, {0, 0.1, -0.04}}, {15, {0, -0.1, -0.04}},
        {0, {0, -0.1, -0.07}}, {6, {0, 0, -0.02}},     {9, {0, 0, -0.02}},     {3, {0, -0.1, 0}},
    }};
    const int firstContact = row;
    for (const Contact& c : contacts) {
        const Vec3 point = bodies[c.body].centre + c.offset;
        const int  normal = row;
        linear(c.body, point, Vec3::UnitZ(), 1);
        p.lo[row] = 0;
        rowCfm[row++] = 1e-6 / dt;
        for (int k = 0; k < 2; ++k) {
            linear(c.body, point, Vec3::Unit(k), 1);
            p.couple(row, normal, 0.8);
            rowCfm[row++] = 1e-7 / dt;
        }
    }

    // A = J M⁻¹ Jᵀ with box inertias in the T-pose (axes aligned with the world).
    Eigen::Matrix<Real, Eigen::Dynamic, 1> invMass(6 * kBodies);
    for (int k = 0; k < kBodies; ++k) {
        const Body& bd = bodies[k];
        const Vec3  h2 = bd.half.cwiseProduct(bd.half);
        const Vec3  inertia = bd.mass / 3 * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y());
        invMass.segment<3>(6 * k).setConstant(1 / bd.mass);
        invMass.segment<3>(6 * k + 3) = inertia.cwiseInverse();
    }
    setMatrix(p, jac * invMass.asDiagonal() * jac.transpose());
    p.cfm = rowCfm;

    // b = −(J v + bias): falling at about 1 m/s with random spin; feet and hands slide.
    Rng rng(seed);
    Eigen::Matrix<Real, Eigen::Dynamic, 1> v(6 * kBodies);
    for (int k = 0; k < kBodies; ++k) {
        v.segment<3>(6 * k) = uniformVector(rng, {-0.4, 0.4}, {-0.4, 0.4}, {-1.2, -0.8});
        v.segment<3>(6 * k + 3) = uniformVector(rng, {-1, 1}, {-1, 1}, {-1, 1});
    }
    for (int k : {6, 9, 12}) {
        v(6 * k) += 1.5;  // sliding along x
    }
    const Eigen::Matrix<Real, Eigen::Dynamic, 1> jv = jac * v;
    for (int r = 0; r < kRows; ++r) {
        Real bias = 0;
        if (r < firstLimit) {
            bias = rng.uniform(-0.01, 0.01);  // joint drift correction
        } else if (r < firstContact) {
            bias = rng.uniform(-0.5, 0.2);  // some limits violated, some not
        }
        p.b[r] = -(jv(r) + bias) + jitter * rng.uniform(-1, 1);
    }
    return p;
}

}  // namespace af::test
