// Brush solids from half-spaces: vertices from plane triples, faces from the vertices on each
// plane (see brush.h).

#include "af/geometry/brush.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace af {

namespace {

constexpr Real kRelativeTolerance = 1e-6;
constexpr Real kTightestTolerance = 1e-10;
// Three unit normals whose determinant is below this meet in a line or not at all; a point
// from them would be all rounding error. A vertex of a real brush has a much larger one.
constexpr Real kMinTripleDeterminant = 1e-9;
// Two unit normals closer to parallel than this (|n1 × n2|) do not define a direction.
constexpr Real kMinPairCross = 1e-9;
// A unit direction escapes a half-space when it does not point out of it by more than this.
constexpr Real kEscapeSlack = 1e-9;

std::string describe(const Vec3& v) {
    std::ostringstream s;
    // + 0 turns −0 into 0 for the message.
    s << "(" << v.x() + 0 << " " << v.y() + 0 << " " << v.z() + 0 << ")";
    return s.str();
}

BrushPolytope failure(BrushProblem problem, std::string message) {
    BrushPolytope result;
    result.problem = problem;
    result.message = std::move(message);
    return result;
}

// A direction along which the solid goes on forever, if any: a non-zero u with n·u ≤ 0 for
// every plane. When such directions exist, either they include a line (the normals have rank
// below 3) or the cone they form has an edge, lying on two of the planes; so trying ±(n_i × n_j)
// for every pair, and the rank-1 case separately, finds one.
std::optional<Vec3> escapeDirection(const std::vector<BrushPlane>& planes) {
    auto escapes = [&](const Vec3& u) {
        return std::all_of(planes.begin(), planes.end(),
                           [&](const BrushPlane& p) { return p.normal.dot(u) <= kEscapeSlack; });
    };
    bool rankTwo = false;
    for (std::size_t i = 0; i < planes.size(); ++i) {
        for (std::size_t j = i + 1; j < planes.size(); ++j) {
            const Vec3 c = planes[i].normal.cross(planes[j].normal);
            if (c.norm() < kMinPairCross) continue;
            rankTwo = true;
            const Vec3 u = c.normalized();
            if (escapes(u)) return u;
            if (escapes(-u)) return Vec3(-u);
        }
    }
    if (rankTwo) return std::nullopt;
    if (planes.empty()) return Vec3::UnitX();
    // All normals parallel: every direction across them is free.
    const Vec3& n = planes.front().normal;
    return n.unitOrthogonal();
}

// The vertex list with `p` merged in: the index of a vertex within `tolerance`, or a new one.
int addVertex(std::vector<Vec3>& vertices, const Vec3& p, Real tolerance) {
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if ((vertices[i] - p).norm() <= tolerance) return int(i);
    vertices.push_back(p);
    return int(vertices.size()) - 1;
}

std::vector<Vec3> cornerPoints(const std::vector<BrushPlane>& planes, Real tolerance) {
    std::vector<Vec3> vertices;
    const std::size_t n = planes.size();
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            const Vec3 nij = planes[i].normal.cross(planes[j].normal);
            for (std::size_t k = j + 1; k < n; ++k) {
                const Real det = nij.dot(planes[k].normal);
                if (std::abs(det) < kMinTripleDeterminant) continue;
                // Cramer's rule for n_m · p = −d_m, m ∈ {i, j, k}.
                const Vec3 p = -(planes[i].d * planes[j].normal.cross(planes[k].normal) +
                                 planes[j].d * planes[k].normal.cross(planes[i].normal) + planes[k].d * nij) /
                               det;
                const bool inside = std::all_of(planes.begin(), planes.end(), [&](const BrushPlane& q) {
                    return q.normal.dot(p) + q.d <= tolerance;
                });
                if (inside) addVertex(vertices, p, tolerance);
            }
        }
    }
    return vertices;
}

// The vertices on `plane`, counter-clockwise seen from outside (around its outward normal).
std::vector<int> faceLoop(const BrushPlane& plane, const std::vector<Vec3>& vertices, Real tolerance) {
    std::vector<int> loop;
    Vec3 centre = Vec3::Zero();
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        if (std::abs(plane.normal.dot(vertices[v]) + plane.d) > tolerance) continue;
        loop.push_back(int(v));
        centre += vertices[v];
    }
    if (loop.size() < 3) return loop;
    centre /= Real(loop.size());
    const Vec3 a = plane.normal.unitOrthogonal();
    const Vec3 b = plane.normal.cross(a);  // a × b = normal, so increasing angle turns CCW
    auto angle = [&](int v) {
        const Vec3 r = vertices[v] - centre;
        return std::atan2(r.dot(b), r.dot(a));
    };
    std::sort(loop.begin(), loop.end(), [&](int x, int y) { return angle(x) < angle(y); });
    return loop;
}

Real loopArea(const std::vector<int>& loop, const std::vector<Vec3>& vertices) {
    Vec3 twiceArea = Vec3::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i)
        twiceArea += (vertices[loop[i]] - vertices[loop[0]]).cross(vertices[loop[(i + 1) % loop.size()]] - vertices[loop[0]]);
    return twiceArea.norm() / 2;
}

// Each directed edge once with its reverse once, and V − E + F = 2: the loops close up.
bool closedSurface(std::size_t vertexCount, const std::vector<std::vector<int>>& loops) {
    std::map<std::pair<int, int>, int> directed;
    std::vector<bool> used(vertexCount, false);
    for (const std::vector<int>& loop : loops) {
        for (std::size_t i = 0; i < loop.size(); ++i) {
            ++directed[{loop[i], loop[(i + 1) % loop.size()]}];
            used[loop[i]] = true;
        }
    }
    for (const auto& [edge, count] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        if (count != 1 || twin == directed.end() || twin->second != 1) return false;
    }
    const bool allUsed = std::all_of(used.begin(), used.end(), [](bool u) { return u; });
    return allUsed && int(vertexCount) - int(directed.size() / 2) + int(loops.size()) == 2;
}

// The solid of unit-normal planes that enclose a bounded region, with vertices merged and
// points counted on planes within `eps`.
BrushPolytope solidWithin(const std::vector<BrushPlane>& unit, Real eps) {
    std::vector<Vec3> vertices = cornerPoints(unit, eps);
    if (vertices.size() < 4)
        return failure(BrushProblem::empty, "the brush has no volume: its sides meet in " +
                                                std::to_string(vertices.size()) + " corner(s)");

    Real extent = 0;
    for (const Vec3& v : vertices) extent = std::max(extent, (v - vertices.front()).norm());

    BrushPolytope result;
    std::vector<std::vector<int>> loops;
    std::vector<std::vector<int>> vertexSets;  // sorted, to tell a repeated plane
    for (std::size_t i = 0; i < unit.size(); ++i) {
        std::vector<int> loop = faceLoop(unit[i], vertices, eps);
        std::vector<int> set = loop;
        std::sort(set.begin(), set.end());
        const bool face = loop.size() >= 3 && loopArea(loop, vertices) > eps * extent &&
                          std::find(vertexSets.begin(), vertexSets.end(), set) == vertexSets.end();
        if (!face) {
            result.droppedSides.push_back(int(i));
            continue;
        }
        loops.push_back(std::move(loop));
        vertexSets.push_back(std::move(set));
        result.faceSides.push_back(int(i));
    }
    if (loops.size() < 4)
        return failure(BrushProblem::empty, "the brush has no volume: only " + std::to_string(loops.size()) +
                                                " of its sides touch it in an area");
    if (!closedSurface(vertices.size(), loops))
        return failure(BrushProblem::empty, "the brush is too thin to build: its faces do not close up within " +
                                                std::to_string(eps) + " units");
    result.polytope = makePolytope(std::move(vertices), loops);
    return result;
}

}  // namespace

BrushPolytope polytopeFromPlanes(const std::vector<BrushPlane>& planes, Real tolerance) {
    std::vector<BrushPlane> unit;
    unit.reserve(planes.size());
    Real scale = 1;
    for (std::size_t i = 0; i < planes.size(); ++i) {
        const Real length = planes[i].normal.norm();
        if (!std::isfinite(length) || length == 0 || !std::isfinite(planes[i].d))
            return failure(BrushProblem::badPlane, "side " + std::to_string(i) + " has normal " +
                                                       describe(planes[i].normal) + " and d " +
                                                       std::to_string(planes[i].d) + "; no plane");
        unit.push_back({planes[i].normal / length, planes[i].d / length});
        scale = std::max(scale, std::abs(unit.back().d));
    }
    if (const std::optional<Vec3> away = escapeDirection(unit))
        return failure(BrushProblem::open, "the brush is open: no side closes it towards " + describe(*away));
    if (tolerance > 0) return solidWithin(unit, tolerance);

    // The default tolerance covers float-rounded planes that should meet in one corner, but can
    // swallow a real feature smaller than itself (a sliver far from the origin, where it is
    // largest); tighter ones, down to where double rounding begins, get such brushes right.
    BrushPolytope first = solidWithin(unit, kRelativeTolerance * scale);
    for (Real eps = kRelativeTolerance * scale / 10; !first.ok() && eps >= kTightestTolerance * scale; eps /= 10) {
        BrushPolytope tighter = solidWithin(unit, eps);
        if (tighter.ok()) return tighter;
    }
    return first;
}

std::vector<BrushPlane> brushPlanes(const BrushDef3& brush) {
    std::vector<BrushPlane> planes;
    planes.reserve(brush.sides.size());
    for (const BrushSide& side : brush.sides)
        planes.push_back({Vec3(side.plane[0], side.plane[1], side.plane[2]), side.plane[3]});
    return planes;
}

BrushPolytope polytopeFromBrush(const BrushDef3& brush, Real tolerance) {
    return polytopeFromPlanes(brushPlanes(brush), tolerance);
}

}  // namespace af
