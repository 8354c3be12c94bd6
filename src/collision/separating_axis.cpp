#include "separating_axis.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace af::collision_detail {

namespace {

bool isArcless(const ShapeFeatures& f, int edge) {
    return std::find(f.arclessEdges.begin(), f.arclessEdges.end(), edge) != f.arclessEdges.end();
}

void keepBetter(SeparatingAxis& best, const SeparatingAxis& candidate) {
    if (candidate.separation > best.separation) {
        best = candidate;
    }
}

}  // namespace

std::optional<SeparatingAxis> findBestAxis(const PlacedShape& a, const PlacedShape& b, Real margin) {
    if (a.features->box.valid && b.features->box.valid) {
        return findBestBoxAxis(a, b, margin);
    }
    return findBestPolytopeAxis(a, b, margin);
}

std::optional<SeparatingAxis> findBestPolytopeAxis(const PlacedShape& a, const PlacedShape& b, Real margin) {
    SeparatingAxis faceA, faceB, edges;

    for (int f = 0; f < a.faceCount(); ++f) {
        if (!a.hasFace(f)) {
            continue;
        }
        const Vec3 n = a.normal(f);  // out of A, towards B
        const Real sep = -maxAlong(b, -n) - a.offset(f, n);
        if (sep > margin) {
            return std::nullopt;
        }
        keepBetter(faceA, {AxisKind::faceA, -n, sep, f, -1});
    }
    for (int f = 0; f < b.faceCount(); ++f) {
        if (!b.hasFace(f)) {
            continue;
        }
        const Vec3 n = b.normal(f);  // out of B, towards A
        const Real sep = -maxAlong(a, -n) - b.offset(f, n);
        if (sep > margin) {
            return std::nullopt;
        }
        keepBetter(faceB, {AxisKind::faceB, n, sep, -1, f});
    }

    // Edge pairs. Two edges span a face of the Minkowski difference A − B, the only edge pairs
    // that can give the best axis, when their arcs cross on the Gauss map (B's negated), at
    // ±L, L = dA × dB. Crossing needs each arc to straddle the other's great circle, the circle
    // square to the other edge's direction: that part depends only on an arc and a group of the
    // other shape, so it is tested |groups of A| × |arcs of B| + |arcs of A| × |groups of B| times.
    const ShapeFeatures& fa = *a.features;
    const ShapeFeatures& fb = *b.features;
    const int nga = int(fa.groups.size()), ngb = int(fb.groups.size());
    const int naa = int(fa.arcs.size()), nab = int(fb.arcs.size());
    thread_local std::vector<Vec3> dirA, dirB;     // group directions, working frame
    thread_local std::vector<Real> fromAlongA;     // B's arc j vs A's group g: from_j · d_g, at g·nab + j
    thread_local std::vector<Real> toAlongB;       // A's arc i vs B's group g: to_i · d_g, at i·ngb + g
    thread_local std::vector<unsigned char> straddlesA, straddlesB;
    dirA.resize(nga);
    dirB.resize(ngb);
    fromAlongA.resize(size_t(nga) * nab);
    straddlesA.resize(size_t(nga) * nab);
    toAlongB.resize(size_t(naa) * ngb);
    straddlesB.resize(size_t(naa) * ngb);
    for (int g = 0; g < nga; ++g) {
        dirA[g] = a.rotation * fa.groups[g].direction;
        const Vec3 d = b.toOwn(dirA[g]);
        for (int j = 0; j < nab; ++j) {
            const Real p = dot3(fb.arcs[j].from, d), q = dot3(fb.arcs[j].to, d);
            fromAlongA[size_t(g) * nab + j] = p;
            straddlesA[size_t(g) * nab + j] = p * q < 0;
        }
    }
    for (int g = 0; g < ngb; ++g) {
        dirB[g] = b.rotation * fb.groups[g].direction;
        const Vec3 d = a.toOwn(dirB[g]);
        for (int i = 0; i < naa; ++i) {
            const Real r = dot3(fa.arcs[i].from, d), t = dot3(fa.arcs[i].to, d);
            toAlongB[size_t(i) * ngb + g] = t;
            straddlesB[size_t(i) * ngb + g] = r * t < 0;
        }
    }
    bool beyondMargin = false;
    for (int ga = 0; ga < nga; ++ga) {
        const EdgeGroup& groupA = fa.groups[ga];
        for (int gb = 0; gb < ngb; ++gb) {
            const EdgeGroup& groupB = fb.groups[gb];
            Vec3 l = dirA[ga].cross(dirB[gb]);
            const Real len = l.norm();
            if (len <= kParallelSine) {
                continue;
            }
            l /= len;
            for (int j = groupB.first; j < groupB.first + groupB.count; ++j) {
                if (!straddlesA[size_t(ga) * nab + j]) {
                    continue;
                }
                const EdgeArc& arcB = fb.arcs[j];
                for (int i = groupA.first; i < groupA.first + groupA.count; ++i) {
                    const EdgeArc& arcA = fa.arcs[i];
                    // Same side of the sphere: with u = from × to of A's arc (turn along dA) and
                    // v likewise for B's, (−fromB · u)(toA · v) > 0.
                    if (!straddlesB[size_t(i) * ngb + gb] ||
                        -arcA.turn * arcB.turn * fromAlongA[size_t(ga) * nab + j] * toAlongB[size_t(i) * ngb + gb] <= 0) {
                        continue;
                    }
                    // Out of A: the sign of ±L inside A's arc. There A's support is its edge and
                    // B's support the other way is B's edge, so the edges alone give the separation.
                    const Vec3 lOwnA = a.toOwn(l);
                    const Real sign = dot3(lOwnA, arcA.from + arcA.to) >= 0 ? 1 : -1;
                    const Vec3 s = sign * l;
                    const EdgeFeature& ea = fa.edges[arcA.edge];
                    const EdgeFeature& eb = fb.edges[arcB.edge];
                    const Real sep = dot3(b.toOwn(s), b.polytope->vertices[eb.v0]) + dot3(s, b.translation) -
                                     sign * dot3(lOwnA, a.polytope->vertices[ea.v0]) - dot3(s, a.translation);
                    beyondMargin = beyondMargin || sep > margin;
                    keepBetter(edges, {AxisKind::edges, -s, sep, arcA.edge, arcB.edge});
                }
            }
            if (beyondMargin) {
                return std::nullopt;
            }
        }
    }

    // Edges of segment-like shapes have no arcs: score their pairs by projecting both shapes.
    auto projectEdges = [&](int i, int j) {
        const Vec3 da = a.rotation * fa.edges[i].direction;
        const Vec3 db = b.rotation * fb.edges[j].direction;
        Vec3 axis = da.cross(db);
        const Real len = axis.norm();
        if (len <= kParallelSine * da.norm() * db.norm()) {
            return;
        }
        axis /= len;
        const auto [loA, hiA] = interval(a, axis);
        const auto [loB, hiB] = interval(b, axis);
        const bool aBelow = loB - hiA >= loA - hiB;  // A on the low side of B along axis
        const SeparatingAxis candidate{AxisKind::edges, aBelow ? Vec3(-axis) : axis,
                                       aBelow ? loB - hiA : loA - hiB, i, j};
        beyondMargin = beyondMargin || candidate.separation > margin;
        keepBetter(edges, candidate);
    };
    for (const int i : fa.arclessEdges) {
        for (const EdgeArc& arc : fb.arcs) {
            projectEdges(i, arc.edge);
        }
        for (const int j : fb.arclessEdges) {
            projectEdges(i, j);
        }
    }
    for (const int j : fb.arclessEdges) {
        for (const EdgeArc& arc : fa.arcs) {
            projectEdges(arc.edge, j);
        }
    }
    if (beyondMargin) {
        return std::nullopt;
    }
    return chooseAxis(a, b, faceA, faceB, edges);
}

SeparatingAxis chooseAxis(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& faceA,
                          const SeparatingAxis& faceB, const SeparatingAxis& edges) {
    const ShapeFeatures& fa = *a.features;
    const ShapeFeatures& fb = *b.features;
    // Parallel faces tie (a box resting on a box): the larger face is the reference, as it would
    // be after the slightest tilt of either, so that ids do not change when one tilts.
    SeparatingAxis best = faceA;
    if (faceB.kind != AxisKind::none) {
        const Real lead = faceB.separation - faceA.separation;
        if (faceA.kind == AxisKind::none || lead > kLengthTolerance ||
            (lead >= -kLengthTolerance && faceArea(*b.polytope, faceB.featureB) > faceArea(*a.polytope, faceA.featureA))) {
            best = faceB;
        }
    }
    if (edges.kind != AxisKind::none &&
        (edges.separation > best.separation + kLengthTolerance || best.kind == AxisKind::none)) {
        best = edges;
        if (!isArcless(fa, best.featureA) && !isArcless(fb, best.featureB)) {
            // The pair's own axis, oriented as the group's.
            const EdgeFeature& ea = fa.edges[best.featureA];
            const EdgeFeature& eb = fb.edges[best.featureB];
            Vec3 axis = (a.rotation * ea.direction).cross(b.rotation * eb.direction).normalized();
            if (axis.dot(best.normal) > 0) {
                axis = -axis;
            }
            best.normal = -axis;
            best.separation = axis.dot(b.vertex(eb.v0) - a.vertex(ea.v0));
        }
    }
    return best;
}

}  // namespace af::collision_detail
