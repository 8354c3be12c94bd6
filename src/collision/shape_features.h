#pragma once
// What the narrowphase needs of a polytope beyond its vertices and faces, none of it depending on
// the pose: the faces on either side of every edge, each edge's normal cone as arcs on the Gauss
// map, and the edges grouped by direction. All in the polytope's own frame.

#include "af/geometry/polytope.h"

#include <array>
#include <vector>

namespace af::collision_detail {

// Features count as the same within this distance (file units): ties between candidate axes,
// points on a clipping plane. Far above double rounding at body scale (the narrowphase works in
// A's body frame), far below anything visible.
inline constexpr Real kLengthTolerance = 1e-7;

// Below this sine two unit directions (face normals, edge directions) count as parallel or
// opposite: no arc between them, no axis spanned by them (their cross product would be rounding
// noise; the faces' own normals cover what such an axis could separate).
inline constexpr Real kParallelSine = 1e-6;

struct EdgeFeature {
    int v0 = 0, v1 = 0;                // polytope.edges order: v0 < v1
    std::array<int, 2> faces{-1, -1};  // walking v0→v1, walking v1→v0; −1 when without area
    Vec3 direction = Vec3::Zero();     // v1 − v0
    bool skip = false;  // zero length, or two coplanar faces (not a real edge)
};

// The directions in which an edge is the shape's support feature (its normal cone) form, on the
// unit sphere, the arc between the normals of its two faces. An edge of a flat shape has a face
// with no area or two opposite faces; its cone then runs through the outward direction m within
// the flat face's plane, as one or two quarter arcs (n → m, m → −n).
struct EdgeArc {
    int edge = 0;
    Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // unit; the arc is shorter than a half circle
    Real turn = 1;  // +1 when from × to points along the group's direction, −1 when against it
};

// Arcs grouped by their edges' direction (parallel or opposite within 1e-9 rad): the search for
// crossing arcs tests each arc against each group of the other shape, not against each arc.
struct EdgeGroup {
    Vec3 direction = Vec3::UnitX();  // unit, the first member's edge direction
    int first = 0, count = 0;        // into ShapeFeatures::arcs
};

// A polytope that is a rectangular box, described by its centre, axes and half extents so that
// box–box queries can use the closed forms of the separating-axis test instead of projecting
// vertices. Faces and edges keep the polytope's numbering, so that a query's answer names the same
// features whichever way it was found.
struct BoxFeatures {
    bool valid = false;
    Vec3 centre = Vec3::Zero();
    Mat3 axes = Mat3::Identity();    // columns: unit, right-handed, each the normal of a face
    Vec3 half = Vec3::Zero();        // half extent along each axis
    bool aligned = false;            // axes are exactly the frame's (a box made around its centre)
    std::array<int, 6> faceAxis{};   // per face: the axis it is square to
    std::array<Real, 6> faceSign{};  // per face: +1 when its normal is the axis, −1 when opposite
    std::array<int, 3> groupAxis{};  // per edge group (ShapeFeatures::groups): the axis it runs along
    // The edges along axis i: edge[i][k], bit 0 of k set on the + side of axis (i + 1) % 3, bit 1 on
    // the + side of axis (i + 2) % 3.
    std::array<std::array<int, 4>, 3> edge{};
};

struct ShapeFeatures {
    std::vector<EdgeFeature> edges;  // polytope.edges order
    std::vector<EdgeArc> arcs;       // group by group
    std::vector<EdgeGroup> groups;
    std::vector<int> arclessEdges;   // edges of length without arcs (segments: no face has area)
    Vec3 centre = Vec3::Zero();      // vertex mean, an interior point for libccd's MPR
    bool flat = false;               // some face has no area: a flat shape or a segment
    BoxFeatures box;
    // Of a ConvexShape of at most kSmallPolytope vertices (measureVertexGap), the smallest distance
    // between two of its vertices and the largest from the frame's origin; 0 otherwise, which
    // tells smallPlaneContact not to use them.
    Real vertexGap = 0;
    Real vertexReach = 0;
};

// A polytope with at most this many vertices (a box) gets the plane contact's shortcuts.
inline constexpr int kSmallPolytope = 8;

// Fills `out` from `polytope` (no allocation once `out` has held a shape at least as large).
void prepare(const Polytope& polytope, ShapeFeatures& out);

// Fills vertexGap and vertexReach of a polytope of at most kSmallPolytope vertices (quadratic in
// them: done once per ConvexShape, not in prepare(), which queries of unprepared shapes repeat).
void measureVertexGap(const Polytope& polytope, ShapeFeatures& out);

// Twice the area of face f (Newell's formula).
Real faceArea(const Polytope& polytope, int f);

}  // namespace af::collision_detail
