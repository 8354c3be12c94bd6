// collide(): the separating-axis search decides the normal and depth, libccd decides "within the
// margin" where the axes cannot (see narrowphase.h), and the axis kind decides the points.

#include "af/collision/narrowphase.h"

#include "ccd_query.h"
#include "collide_placed.h"
#include "contact_ids.h"
#include "face_clipping.h"
#include "manifold_reduction.h"
#include "separating_axis.h"

#include <algorithm>
#include <memory>
#include <utility>

namespace af {

using namespace collision_detail;

namespace {

// libccd sees A grown by the margin plus this much, so that touching shapes queried with a zero
// margin still count as within it.
constexpr Real kInflationSlack = 1e-6;

// Closest points of segments p0→p1 and q0→q1 (by minimising |p(s) − q(t)|² over [0, 1]²).
std::pair<Vec3, Vec3> closestPoints(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const Real a = d1.squaredNorm(), e = d2.squaredNorm();
    const Real b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
    const Real denom = a * e - b * b;
    Real s = denom > 0 ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
    Real t = e > 0 ? (b * s + f) / e : Real(0);
    if (t < 0) {
        t = 0;
        s = a > 0 ? std::clamp(-c / a, Real(0), Real(1)) : Real(0);
    } else if (t > 1) {
        t = 1;
        s = a > 0 ? std::clamp((b - c) / a, Real(0), Real(1)) : Real(0);
    }
    return {p0 + s * d1, q0 + t * d2};
}

void edgeContact(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& axis,
                 std::vector<Candidate>& out) {
    const EdgeFeature& ea = a.features->edges[axis.featureA];
    const EdgeFeature& eb = b.features->edges[axis.featureB];
    const auto [pa, pb] = closestPoints(a.vertex(ea.v0), a.vertex(ea.v1), b.vertex(eb.v0), b.vertex(eb.v1));
    out.push_back({Real(0.5) * (pa + pb), -axis.separation, edgePairId(axis.featureA, axis.featureB)});
}

// Of the faces at `edge`, the one whose normal is closest to `direction`, and that cosine.
std::pair<int, Real> faceAtEdgeAlong(const PlacedShape& shape, int edge, const Vec3& direction) {
    const Vec3 d = shape.toOwn(direction);
    std::pair<int, Real> best{-1, -1};
    for (const int f : shape.features->edges[edge].faces) {
        if (f >= 0 && shape.polytope->faces[f].normal.dot(d) > best.second) {
            best = {f, shape.polytope->faces[f].normal.dot(d)};
        }
    }
    return best;
}

// An edge-pair axis where both shapes have a face within this angle of it (cosine) is a face
// contact in all but name (face_clipping.h); 25° separates a tilted box from crossed edges.
constexpr Real kFaceContactCosine = 0.9;

void edgeFaceContact(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& axis, Real margin,
                     std::vector<Candidate>& out) {
    const auto [faceA, cosA] = faceAtEdgeAlong(a, axis.featureA, -axis.normal);
    const auto [faceB, cosB] = faceAtEdgeAlong(b, axis.featureB, axis.normal);
    if (std::min(cosA, cosB) < kFaceContactCosine) {
        return;
    }
    // The larger face is the reference, as for a face axis (separating_axis.h), so that a box
    // rocking between a face axis and such an edge axis keeps its ids.
    const Real areaA = faceArea(*a.polytope, faceA), areaB = faceArea(*b.polytope, faceB);
    if (areaB > areaA || (areaB == areaA && cosB >= cosA)) {
        clipFaces(b, faceB, a, faceA, axis.normal, true, margin, out);
    } else {
        clipFaces(a, faceA, b, faceB, -axis.normal, false, margin, out);
    }
}

enum class Anchor { a, b, both };

// One point from the support vertices along `normal`, when no feature gives better: at the
// anchor's vertex (or between both), midway between the two support planes.
void singlePoint(const PlacedShape& a, const PlacedShape& b, const Vec3& normal, Anchor anchor, Real margin,
                 std::vector<Candidate>& out) {
    const int ia = supportIndex(a, -normal);
    const int ib = supportIndex(b, normal);
    const Vec3 pa = a.vertex(ia);
    const Vec3 pb = b.vertex(ib);
    const Real depth = normal.dot(pb - pa);
    if (depth < -margin) {
        return;
    }
    const Vec3 along = (normal.dot(pa) + Real(0.5) * depth) * normal;  // the mid plane's position
    const Vec3 base = anchor == Anchor::a ? pa : anchor == Anchor::b ? pb : Vec3(Real(0.5) * (pa + pb));
    out.push_back({base - base.dot(normal) * normal + along, depth, singlePointId(ia, ib)});
}

// Whether `point` lies over face f of `shape`: inside the prism its side planes bound.
bool overFace(const PlacedShape& shape, int f, const Vec3& point) {
    const Vec3 normal = shape.normal(f);
    const std::vector<int>& loop = shape.polytope->faces[f].loop;
    Vec3 r1 = shape.vertex(loop.back());
    for (const int v : loop) {
        const Vec3 r0 = r1;
        r1 = shape.vertex(v);
        // On a counter-clockwise loop edge × normal points out of the face.
        if ((r1 - r0).cross(normal).dot(point - r0) > 0) {
            return false;
        }
    }
    return true;
}

}  // namespace

bool collision_detail::separationIsDistance(const PlacedShape& a, const PlacedShape& b, const SeparatingAxis& axis) {
    switch (axis.kind) {
    case AxisKind::faceA:
        return overFace(a, axis.featureA, b.vertex(supportIndex(b, axis.normal)));
    case AxisKind::faceB:
        return overFace(b, axis.featureB, a.vertex(supportIndex(a, -axis.normal)));
    case AxisKind::edges: {
        const EdgeFeature& ea = a.features->edges[axis.featureA];
        const EdgeFeature& eb = b.features->edges[axis.featureB];
        const Vec3 p0 = a.vertex(ea.v0), q0 = b.vertex(eb.v0);
        const Vec3 d1 = a.vertex(ea.v1) - p0, d2 = b.vertex(eb.v1) - q0, r = p0 - q0;
        const Real aa = d1.dot(d1), e = d2.dot(d2), bb = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
        const Real denom = aa * e - bb * bb;
        if (!(denom > 0)) {
            return false;
        }
        const Real s = (bb * f - c * e) / denom, t = (aa * f - bb * c) / denom;
        return s >= 0 && s <= 1 && t >= 0 && t <= 1;
    }
    case AxisKind::none:
    case AxisKind::free:
        break;
    }
    return false;
}

// The manifold of two prepared shapes; the working frame is A's body frame.
Manifold collision_detail::collidePlaced(const PlacedShape& a, const PlacedShape& b, const RigidPose& poseA, const RigidPose& poseB,
                       Real margin) {
    const std::optional<SeparatingAxis> found = findBestAxis(a, b, margin);
    if (!found) {
        return {};
    }
    SeparatingAxis axis = *found;
    // A positive separation is only a lower bound of the distance (the closest points may be two
    // vertices), and two flat shapes (two coplanar triangles) may have no separating axis among
    // their features: there libccd has the last word, unless the axis's own features show that
    // its separation is the distance.
    if (axis.kind == AxisKind::none || (a.flat() && b.flat()) ||
        (axis.separation > 0 && !separationIsDistance(a, b, axis))) {
        const CcdResult ccd = ccdPenetration(a, b, margin + kInflationSlack);
        if (!ccd.intersecting) {
            return {};
        }
        const Real separation = separationAlong(a, b, ccd.normal);
        if (axis.kind == AxisKind::none || separation > axis.separation + kLengthTolerance) {
            axis = {AxisKind::free, ccd.normal, separation, -1, -1};
        }
    }
    if (axis.separation > margin) {
        return {};
    }

    std::vector<Candidate>& candidates = scratch().candidates;
    candidates.clear();
    switch (axis.kind) {
    case AxisKind::faceA: {
        const Vec3 outward = -axis.normal;
        const int incident = mostOpposedFaceAround(b, supportIndex(b, axis.normal), outward);
        if (incident >= 0) {
            clipFaces(a, axis.featureA, b, incident, outward, false, margin, candidates);
        }
        if (candidates.empty()) {
            singlePoint(a, b, axis.normal, Anchor::b, margin, candidates);
        }
        break;
    }
    case AxisKind::faceB: {
        const int incident = mostOpposedFaceAround(a, supportIndex(a, -axis.normal), axis.normal);
        if (incident >= 0) {
            clipFaces(b, axis.featureB, a, incident, axis.normal, true, margin, candidates);
        }
        if (candidates.empty()) {
            singlePoint(a, b, axis.normal, Anchor::a, margin, candidates);
        }
        break;
    }
    case AxisKind::edges:
        edgeFaceContact(a, b, axis, margin, candidates);
        if (candidates.empty()) {
            edgeContact(a, b, axis, candidates);
        }
        break;
    case AxisKind::free:
    case AxisKind::none:
        singlePoint(a, b, axis.normal, Anchor::both, margin, candidates);
        break;
    }
    Manifold m = toWorldManifold(candidates, axis.normal, poseA);
    // A face normal straight from its own body's frame, not through A's: a box resting on a box
    // gets exactly the face normal, not one rotated there and back.
    if (axis.kind == AxisKind::faceA) {
        m.normal = -(poseA.rotation * a.polytope->faces[axis.featureA].normal);
    } else if (axis.kind == AxisKind::faceB) {
        m.normal = poseB.rotation * b.polytope->faces[axis.featureB].normal;
    }
    return m;
}

namespace {

// A and B placed in A's body frame.
std::pair<PlacedShape, PlacedShape> place(const Polytope& a, const ShapeFeatures& fa, const RigidPose& poseA,
                                          const Polytope& b, const ShapeFeatures& fb, const RigidPose& poseB) {
    const Mat3 toA = poseA.rotation.transpose();
    return {PlacedShape{&a, &fa, Mat3::Identity(), Vec3::Zero()},
            PlacedShape{&b, &fb, toA * poseB.rotation, toA * (poseB.position - poseA.position)}};
}

}  // namespace

ConvexShape::ConvexShape() : ConvexShape(Polytope{}) {}

ConvexShape::ConvexShape(Polytope polytope) : polytope_(std::move(polytope)) {
    auto features = std::make_shared<ShapeFeatures>();
    prepare(polytope_, *features);
    measureVertexGap(polytope_, *features);
    features_ = std::move(features);
}

Manifold collide(const ConvexShape& a, const RigidPose& poseA, const ConvexShape& b, const RigidPose& poseB,
                 Real margin) {
    if (a.polytope().vertices.empty() || b.polytope().vertices.empty()) {
        return {};
    }
    const auto [pa, pb] = place(a.polytope(), a.features(), poseA, b.polytope(), b.features(), poseB);
    return collidePlaced(pa, pb, poseA, poseB, std::max(margin, Real(0)));
}

Manifold collide(const Polytope& a, const RigidPose& poseA, const Polytope& b, const RigidPose& poseB,
                 Real margin) {
    if (a.vertices.empty() || b.vertices.empty()) {
        return {};
    }
    Scratch& s = scratch();
    prepare(a, s.a);
    prepare(b, s.b);
    const auto [pa, pb] = place(a, s.a, poseA, b, s.b, poseB);
    return collidePlaced(pa, pb, poseA, poseB, std::max(margin, Real(0)));
}

}  // namespace af
