#include "shape_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace af::collision_detail {

namespace {

// Parallel within this sine: one group. Tight, because the group's direction stands in for every
// member's when finding axes.
constexpr Real kGroupSine = 1e-9;

// The arcs of the edge's normal cone from the faces on either side (see EdgeArc), appended to
// `arcs`; marks the edge skipped when it has none to offer.
void addArcs(const Polytope& p, int edgeIndex, EdgeFeature& e, std::vector<EdgeArc>& arcs) {
    e.skip = e.direction.squaredNorm() <= kLengthTolerance * kLengthTolerance;
    if (e.skip) {
        return;
    }
    auto add = [&](const Vec3& from, const Vec3& to) { arcs.push_back({edgeIndex, from, to, 1}); };
    const bool has0 = e.faces[0] >= 0, has1 = e.faces[1] >= 0;
    // Outward within a face's plane: a counter-clockwise loop walks its edges with the face on
    // the left, so walkingDirection × normal points away from it.
    auto outward = [&](int side) {
        const Vec3 walk = side == 0 ? e.direction : Vec3(-e.direction);
        return Vec3(walk.cross(p.faces[e.faces[side]].normal).normalized());
    };
    if (has0 && has1) {
        const Vec3& n0 = p.faces[e.faces[0]].normal;
        const Vec3& n1 = p.faces[e.faces[1]].normal;
        const Real cosine = n0.dot(n1);
        if (std::abs(cosine) < 1 - kParallelSine * kParallelSine / 2) {
            add(n0, n1);
        } else if (cosine > 0) {
            e.skip = true;  // two coplanar faces: every axis it could give is their normal
        } else {
            const Vec3 m = outward(0);  // folded flat: half a great circle through m
            add(n0, m);
            add(m, n1);
        }
    } else if (has0 || has1) {
        const int side = has0 ? 0 : 1;
        add(p.faces[e.faces[side]].normal, outward(side));
    }
}

// Sorts `arcs` into groups of parallel edges and sets each arc's turn against its group.
void groupArcs(ShapeFeatures& s) {
    thread_local std::vector<int> groupOf;
    thread_local std::vector<EdgeArc> unsorted;
    unsorted.assign(s.arcs.begin(), s.arcs.end());
    groupOf.assign(unsorted.size(), -1);
    s.groups.clear();
    for (size_t k = 0; k < unsorted.size(); ++k) {
        const Vec3 d = s.edges[unsorted[k].edge].direction.normalized();
        int g = 0;
        while (g < int(s.groups.size()) && d.cross(s.groups[g].direction).squaredNorm() > kGroupSine * kGroupSine) {
            ++g;
        }
        if (g == int(s.groups.size())) {
            s.groups.push_back({d, 0, 0});
        }
        groupOf[k] = g;
        ++s.groups[g].count;
    }
    int next = 0;
    for (EdgeGroup& g : s.groups) {
        g.first = next;
        next += g.count;
        g.count = 0;
    }
    for (size_t k = 0; k < unsorted.size(); ++k) {
        EdgeGroup& g = s.groups[groupOf[k]];
        EdgeArc& arc = s.arcs[g.first + g.count++];
        arc = unsorted[k];
        arc.turn = arc.from.cross(arc.to).dot(g.direction) >= 0 ? 1 : -1;
    }
}

// A box's faces are square to its axes within this cosine, and its vertices on its corners
// within this fraction of its size: closer than rounding makes the closed forms and the vertex
// projections agree to the last few bits.
constexpr Real kBoxCosine = 1e-12;
constexpr Real kBoxCorner = 1e-12;

// Fills s.box when the polytope is a rectangular box (eight corners, six faces in three
// square-to-each-other pairs, three groups of four parallel edges), else leaves it invalid.
void describeBox(const Polytope& p, ShapeFeatures& s) {
    BoxFeatures& box = s.box;
    box.valid = false;
    if (p.vertices.size() != 8 || p.faces.size() != 6 || p.edges.size() != 12 || s.flat || s.groups.size() != 3 ||
        s.arcs.size() != 12) {
        return;
    }
    int axes = 0;
    std::array<int, 3> plus{-1, -1, -1}, minus{-1, -1, -1};
    for (int f = 0; f < 6; ++f) {
        const Vec3& n = p.faces[f].normal;
        int i = 0;
        while (i < axes && std::abs(std::abs(n.dot(box.axes.col(i))) - 1) > kBoxCosine) {
            ++i;
        }
        if (i == axes) {
            if (axes == 3) {
                return;
            }
            box.axes.col(axes++) = n;
        }
        const bool along = n.dot(box.axes.col(i)) > 0;
        int& slot = along ? plus[i] : minus[i];
        if (slot >= 0) {
            return;
        }
        slot = f;
        box.faceAxis[f] = i;
        box.faceSign[f] = along ? 1 : -1;
    }
    if (axes != 3 || std::abs(box.axes.col(0).dot(box.axes.col(1))) > kBoxCosine ||
        std::abs(box.axes.col(0).dot(box.axes.col(2))) > kBoxCosine ||
        std::abs(box.axes.col(1).dot(box.axes.col(2))) > kBoxCosine) {
        return;
    }
    // A box whose faces are square to the frame's axes takes them as its own, in their order, so
    // that queries can skip products with them (BoxFeatures::aligned).
    std::array<int, 3> coordinate{};
    bool squareToFrame = true;
    for (int k = 0; k < 3; ++k) {
        box.axes.col(k).cwiseAbs().maxCoeff(&coordinate[k]);
        squareToFrame = squareToFrame && std::abs(box.axes(coordinate[k], k)) == 1;
    }
    if (squareToFrame && coordinate[0] != coordinate[1] && coordinate[0] != coordinate[2] &&
        coordinate[1] != coordinate[2]) {
        std::array<int, 3> newPlus{}, newMinus{};
        for (int k = 0; k < 3; ++k) {
            const bool flipped = box.axes(coordinate[k], k) < 0;
            newPlus[coordinate[k]] = flipped ? minus[k] : plus[k];
            newMinus[coordinate[k]] = flipped ? plus[k] : minus[k];
        }
        plus = newPlus;
        minus = newMinus;
        box.axes.setIdentity();
        for (int i = 0; i < 3; ++i) {
            box.faceAxis[plus[i]] = box.faceAxis[minus[i]] = i;
            box.faceSign[plus[i]] = 1;
            box.faceSign[minus[i]] = -1;
        }
    }
    if (box.axes.col(0).cross(box.axes.col(1)).dot(box.axes.col(2)) < 0) {
        box.axes.col(2) = -box.axes.col(2);
        std::swap(plus[2], minus[2]);
        for (int f = 0; f < 6; ++f) {
            box.faceSign[f] = box.faceAxis[f] == 2 ? -box.faceSign[f] : box.faceSign[f];
        }
    }
    box.centre = Vec3::Zero();
    Real size = 0;
    for (int i = 0; i < 3; ++i) {
        const Real hi = p.faces[plus[i]].offset, lo = -p.faces[minus[i]].offset;
        box.half[i] = (hi - lo) / 2;
        box.centre += (hi + lo) / 2 * box.axes.col(i);
        size = std::max(size, std::abs(hi) + std::abs(lo));
    }
    const Real tolerance = kBoxCorner * std::max(size, Real(1));
    for (const Vec3& v : p.vertices) {
        const Vec3 local = box.axes.transpose() * (v - box.centre);
        if (((local.cwiseAbs() - box.half).cwiseAbs().array() > tolerance).any()) {
            return;
        }
    }
    for (auto& row : box.edge) {
        row.fill(-1);
    }
    for (int k = 0; k < 12; ++k) {
        const EdgeFeature& e = s.edges[k];
        const Vec3 along = box.axes.transpose() * e.direction.normalized();
        int i = 0;
        along.cwiseAbs().maxCoeff(&i);
        const Vec3 mid = box.axes.transpose() * ((p.vertices[e.v0] + p.vertices[e.v1]) / 2 - box.centre);
        int& slot = box.edge[i][(mid[(i + 1) % 3] > 0 ? 1 : 0) | (mid[(i + 2) % 3] > 0 ? 2 : 0)];
        if (slot >= 0) {
            return;
        }
        slot = k;
    }
    for (int g = 0; g < 3; ++g) {
        (box.axes.transpose() * s.groups[g].direction).cwiseAbs().maxCoeff(&box.groupAxis[g]);
    }
    box.aligned = box.axes == Mat3::Identity();
    box.valid = box.groupAxis[0] != box.groupAxis[1] && box.groupAxis[0] != box.groupAxis[2] &&
                box.groupAxis[1] != box.groupAxis[2];
}

}  // namespace

void prepare(const Polytope& polytope, ShapeFeatures& out) {
    const int nv = int(polytope.vertices.size());
    const int nf = int(polytope.faces.size());
    Vec3 sum = Vec3::Zero();
    for (const Vec3& v : polytope.vertices) {
        sum += v;
    }
    out.centre = nv > 0 ? Vec3(sum / Real(nv)) : Vec3::Zero();

    out.flat = false;
    for (const Face& f : polytope.faces) {
        out.flat = out.flat || f.normal.squaredNorm() == 0;
    }

    // Which face walks each directed edge u→v, in a V×V table: every edge is walked once in each
    // direction (polytope.h). Only the entries of real edges are ever read, so only they are reset.
    thread_local std::vector<std::int16_t> walker;
    walker.resize(size_t(nv) * size_t(nv));
    for (const std::array<int, 2>& e : polytope.edges) {
        walker[size_t(e[0]) * nv + e[1]] = -1;
        walker[size_t(e[1]) * nv + e[0]] = -1;
    }
    for (int f = 0; f < nf; ++f) {
        if (polytope.faces[f].normal.squaredNorm() == 0) {
            continue;
        }
        const std::vector<int>& loop = polytope.faces[f].loop;
        for (size_t i = 0, n = loop.size(); i < n; ++i) {
            walker[size_t(loop[i]) * nv + loop[i + 1 == n ? 0 : i + 1]] = std::int16_t(f);
        }
    }
    out.edges.resize(polytope.edges.size());
    out.arcs.clear();
    out.arclessEdges.clear();
    for (size_t k = 0; k < polytope.edges.size(); ++k) {
        EdgeFeature& e = out.edges[k];
        e.v0 = polytope.edges[k][0];
        e.v1 = polytope.edges[k][1];
        e.faces = {walker[size_t(e.v0) * nv + e.v1], walker[size_t(e.v1) * nv + e.v0]};
        e.direction = polytope.vertices[e.v1] - polytope.vertices[e.v0];
        const size_t before = out.arcs.size();
        addArcs(polytope, int(k), e, out.arcs);
        if (!e.skip && out.arcs.size() == before) {
            out.arclessEdges.push_back(int(k));
        }
    }
    groupArcs(out);
    describeBox(polytope, out);
}

void measureVertexGap(const Polytope& polytope, ShapeFeatures& out) {
    out.vertexGap = out.vertexReach = 0;
    const std::vector<Vec3>& v = polytope.vertices;
    if (v.size() < 2 || v.size() > std::size_t(kSmallPolytope)) {
        return;
    }
    Real gap = (v[1] - v[0]).norm();
    for (std::size_t i = 0; i < v.size(); ++i) {
        out.vertexReach = std::max(out.vertexReach, v[i].norm());
        for (std::size_t j = i + 1; j < v.size(); ++j) {
            gap = std::min(gap, (v[j] - v[i]).norm());
        }
    }
    out.vertexGap = gap;
}

Real faceArea(const Polytope& polytope, int f) {
    const std::vector<int>& loop = polytope.faces[f].loop;
    Vec3 area = Vec3::Zero();
    for (size_t i = 0; i < loop.size(); ++i) {
        area += polytope.vertices[loop[i]].cross(polytope.vertices[loop[(i + 1) % loop.size()]]);
    }
    return area.norm();
}

}  // namespace af::collision_detail
