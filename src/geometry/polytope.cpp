#include "af/geometry/polytope.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace af {

namespace {

// Below this fraction of (size of the shape)², a face's area vector counts as zero: such faces
// only occur in flattened shapes, where their direction is rounding noise.
constexpr Real kZeroAreaFraction = 1e-14;

Vec3 vertexMean(const std::vector<Vec3>& vertices) {
    Vec3 sum = Vec3::Zero();
    for (const Vec3& v : vertices) {
        sum += v;
    }
    return vertices.empty() ? sum : Vec3(sum / Real(vertices.size()));
}

// Six times the enclosed volume, by the divergence theorem over fanned faces, taken relative to
// `centre` so that far-away shapes do not lose digits.
Real sixVolume(const std::vector<Vec3>& vertices, const std::vector<std::vector<int>>& loops,
               const Vec3& centre) {
    Real sum = 0;
    for (const std::vector<int>& loop : loops) {
        for (size_t i = 1; i + 1 < loop.size(); ++i) {
            const Vec3 a = vertices[loop[0]] - centre;
            const Vec3 b = vertices[loop[i]] - centre;
            const Vec3 c = vertices[loop[i + 1]] - centre;
            sum += a.dot(b.cross(c));
        }
    }
    return sum;
}

// Newell's method: twice the area vector of a (possibly non-triangular) planar loop, robust to
// the loop's starting vertex and to slightly non-planar input.
Vec3 newellAreaVector(const std::vector<Vec3>& vertices, const std::vector<int>& loop,
                      const Vec3& centre) {
    Vec3 n = Vec3::Zero();
    for (size_t i = 0; i < loop.size(); ++i) {
        const Vec3 p = vertices[loop[i]] - centre;
        const Vec3 q = vertices[loop[(i + 1) % loop.size()]] - centre;
        n += p.cross(q);
    }
    return n;
}

}  // namespace

Polytope makePolytope(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& loops) {
    Polytope p;
    p.vertices = std::move(vertices);
    const Vec3 centre = vertexMean(p.vertices);

    // A builder writes loops for the unmirrored case; bounds given max-before-min mirror the
    // shape, which turns every loop inside out at once.
    const bool flip = sixVolume(p.vertices, loops, centre) < 0;

    Real sizeSq = 0;
    for (const Vec3& v : p.vertices) {
        sizeSq = std::max(sizeSq, (v - centre).squaredNorm());
    }

    p.faces.reserve(loops.size());
    for (const std::vector<int>& loop : loops) {
        Face f;
        f.loop = loop;
        if (flip) {
            std::reverse(f.loop.begin(), f.loop.end());
        }
        const Vec3 area = newellAreaVector(p.vertices, f.loop, centre);
        if (area.norm() > kZeroAreaFraction * sizeSq) {
            f.normal = area.normalized();
            Vec3 faceCentre = Vec3::Zero();
            for (int i : f.loop) {
                faceCentre += p.vertices[i];
            }
            f.offset = f.normal.dot(faceCentre / Real(f.loop.size()));
        }
        p.faces.push_back(std::move(f));

        for (size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i];
            const int b = loop[(i + 1) % loop.size()];
            p.edges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(p.edges.begin(), p.edges.end());
    p.edges.erase(std::unique(p.edges.begin(), p.edges.end()), p.edges.end());
    return p;
}

int supportIndex(const Polytope& polytope, const Vec3& dir) {
    int best = 0;
    Real bestDot = polytope.vertices[0].dot(dir);
    for (int i = 1; i < int(polytope.vertices.size()); ++i) {
        const Real d = polytope.vertices[i].dot(dir);
        if (d > bestDot) {
            best = i;
            bestDot = d;
        }
    }
    return best;
}

Vec3 support(const Polytope& polytope, const Vec3& dir) {
    return polytope.vertices[supportIndex(polytope, dir)];
}

Polytope transformed(const Polytope& polytope, const Mat3& rotation, const Vec3& translation) {
    Polytope p = polytope;
    for (Vec3& v : p.vertices) {
        v = rotation * v + translation;
    }
    for (Face& f : p.faces) {
        f.normal = rotation * f.normal;
        f.offset += f.normal.dot(translation);
    }
    return p;
}

Polytope translated(const Polytope& polytope, const Vec3& translation) {
    Polytope p = polytope;
    for (Vec3& v : p.vertices) {
        v += translation;
    }
    for (Face& f : p.faces) {
        f.offset += f.normal.dot(translation);
    }
    return p;
}

std::optional<Real> highestTopAt(std::span<const Polytope> shapes, Real x, Real y) {
    std::optional<Real> top;
    for (const Polytope& p : shapes) {
        if (p.vertices.empty()) continue;
        Vec3 lo = p.vertices[0], hi = lo;
        for (const Vec3& v : p.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        if (lo.x() <= x && x <= hi.x() && lo.y() <= y && y <= hi.y()) top = std::max(top.value_or(hi.z()), hi.z());
    }
    return top;
}

}  // namespace af
