#include "manifold_reduction.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace af::collision_detail {

namespace {

constexpr Real kDistinct = 1e-6;  // file units

// Twice the signed area of (p, q, r) in the plane.
Real signedArea(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
}

int deepestOf(std::span<const Candidate> candidates) {
    int i0 = 0;
    for (int i = 1; i < int(candidates.size()); ++i) {
        if (candidates[i].depth > candidates[i0].depth) {
            i0 = i;
        }
    }
    return i0;
}

// Whether every two of at most four points are farther apart across the plane than twice
// kDistinct, measured in 3-D without the tangent frame. Within 1e6 units of the working frame's
// origin, rounding moves these distances, and those reduceByArea measures, by a few 1e-9 units at
// most, far below kDistinct: where this says yes, reduceByArea finds every point distinct too.
bool clearlyDistinct(std::span<const Candidate> candidates, const Vec3& normal) {
    constexpr Real kFar = 1e12;  // squared distance from the origin within which the above holds
    const int n = int(candidates.size());
    std::array<Vec3, 4> across;  // each point less its component along the normal
    for (int i = 0; i < n; ++i) {
        const Vec3& p = candidates[i].point;
        if (!(dot3(p, p) <= kFar)) {
            return false;
        }
        across[i] = p - dot3(p, normal) * normal;
        for (int j = 0; j < i; ++j) {
            const Vec3 d = across[i] - across[j];
            if (!(dot3(d, d) > 4 * kDistinct * kDistinct)) {
                return false;
            }
        }
    }
    return true;
}

}  // namespace

int reduceToFour(std::span<const Candidate> candidates, const Vec3& normal, std::array<int, 4>& picked) {
    const int n = int(candidates.size());
    // A face or corner on a plane gives four points or fewer, all apart: they are the answer, the
    // deepest first, and the tangent frame reduceByArea works in is not needed.
    if (n == 0 || n > 4 || !clearlyDistinct(candidates, normal)) {
        return reduceByArea(candidates, normal, picked);
    }
    const int i0 = deepestOf(candidates);
    picked[0] = i0;
    int count = 1;
    for (int i = 0; i < n; ++i) {
        if (i != i0) {
            picked[count++] = i;
        }
    }
    return n;
}

int reduceByArea(std::span<const Candidate> candidates, const Vec3& normal, std::array<int, 4>& picked) {
    const int n = int(candidates.size());
    if (n == 0) {
        return 0;
    }
    const int i0 = deepestOf(candidates);
    picked[0] = i0;

    // Everything else happens across the contact plane: coordinates along two tangents.
    const Vec3 t1 = normal.unitOrthogonal();
    const Vec3 t2 = normal.cross(t1);
    thread_local std::vector<Eigen::Vector2d> flat;
    flat.resize(n);
    for (int i = 0; i < n; ++i) {
        flat[i] = {candidates[i].point.dot(t1), candidates[i].point.dot(t2)};
    }

    // Four or fewer distinct points: all of them, the deepest first.
    if (n <= 4) {
        int count = 1;
        bool distinct = true;
        for (int i = 0; i < n && distinct; ++i) {
            for (int j = i + 1; j < n && distinct; ++j) {
                distinct = (flat[j] - flat[i]).squaredNorm() > kDistinct * kDistinct;
            }
            if (i != i0) {
                picked[count++] = i;
            }
        }
        if (distinct) {
            return n;
        }
    }

    int i1 = -1;
    Real farthest = kDistinct * kDistinct;
    for (int i = 0; i < n; ++i) {
        const Real across = (flat[i] - flat[i0]).squaredNorm();
        if (across > farthest) {
            i1 = i;
            farthest = across;
        }
    }
    if (i1 < 0) {
        return 1;
    }
    picked[1] = i1;

    // Areas below kDistinct × the base length are points within kDistinct of a line.
    const Real areaTolerance = kDistinct * std::sqrt(farthest);
    int i2 = -1;
    Real largest = areaTolerance;
    for (int i = 0; i < n; ++i) {
        const Real area = std::abs(signedArea(flat[i0], flat[i1], flat[i]));
        if (area > largest) {
            i2 = i;
            largest = area;
        }
    }
    if (i2 < 0) {
        return 2;
    }
    picked[2] = i2;

    // Outside the triangle, a point adds the area it spans with the edge it is beyond.
    const Real orientation = signedArea(flat[i0], flat[i1], flat[i2]) > 0 ? 1 : -1;
    const std::array<int, 3> tri{i0, i1, i2};
    int i3 = -1;
    Real added = areaTolerance;
    for (int i = 0; i < n; ++i) {
        Real beyond = 0;
        for (int e = 0; e < 3; ++e) {
            beyond = std::max(beyond, -orientation * signedArea(flat[tri[e]], flat[tri[(e + 1) % 3]], flat[i]));
        }
        if (beyond > added) {
            i3 = i;
            added = beyond;
        }
    }
    if (i3 < 0) {
        return 3;
    }
    picked[3] = i3;
    return 4;
}

Manifold toWorldManifold(std::span<const Candidate> candidates, const Vec3& normal, const RigidPose& pose) {
    Manifold m;
    std::array<int, 4> picked{};
    m.count = reduceToFour(candidates, normal, picked);
    m.normal = pose.rotation * normal;
    for (int k = 0; k < m.count; ++k) {
        const Candidate& c = candidates[picked[k]];
        m.points[k] = {pose.apply(c.point), c.depth, c.id};
    }
    return m;
}

}  // namespace af::collision_detail
