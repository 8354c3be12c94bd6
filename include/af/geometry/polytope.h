#pragma once
// A closed convex polyhedron as plain data, with the operations collision and mass need.
//
// Frame: whatever frame the vertices are written in (for an .af body, its body frame; see
// shapes.h). Lengths are in file units (Doom units). Nothing here depends on Doom's limits: a
// Polytope can hold any number of vertices, although the .af shapes never exceed 32.

#include "af/geometry/math.h"

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace af {

/// One planar face. `loop` lists vertex indices counter-clockwise seen from outside, so the
/// right-hand rule around the loop gives `normal`. The face plane is `normal · p = offset`.
/// A face of zero area (a flattened shape, see Polytope) has a zero normal and offset 0.
struct Face {
    std::vector<int> loop;
    Vec3             normal = Vec3::Zero();  ///< outward, unit length (or zero, see above)
    Real             offset = 0;             ///< plane distance from the frame origin, along normal
};

/// Vertices, faces and edges of a convex polyhedron.
///
/// The faces are consistently oriented: every edge is used once in each direction by the two
/// faces that share it, and the divergence-theorem volume is ≥ 0. Builders may produce
/// degenerate polytopes when their inputs are flat (a box with zero height, a two-sided cone):
/// the topology stays that of the regular case, some faces get zero area, and the volume is 0.
struct Polytope {
    std::vector<Vec3>               vertices;
    std::vector<Face>               faces;
    std::vector<std::array<int, 2>> edges;  ///< each undirected edge once, as {lower, higher} index, sorted
};

/// Builds a Polytope from vertices and face loops: fills edges, flips every loop when the loops
/// as given enclose a negative volume (a mirrored input), and computes normals and offsets.
/// The loops must be a consistently oriented, closed, convex surface; this is not checked.
Polytope makePolytope(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& loops);

/// The vertex farthest along `dir` (the support mapping h(dir) used by GJK/EPA/MPR, e.g. libccd).
/// `dir` need not be unit length. Ties go to the lowest vertex index, so the answer is
/// deterministic. A zero `dir` returns vertex 0. Precondition: at least one vertex.
Vec3 support(const Polytope& polytope, const Vec3& dir);

/// Index of the vertex `support` returns.
int supportIndex(const Polytope& polytope, const Vec3& dir);

/// The polytope mapped by p ↦ rotation·p + translation. `rotation` must be a proper rotation
/// (orthonormal, det +1); normals are rotated and plane offsets updated accordingly.
Polytope transformed(const Polytope& polytope, const Mat3& rotation, const Vec3& translation);

/// The polytope moved by `translation`.
Polytope translated(const Polytope& polytope, const Vec3& translation);

// The top of the highest shape whose extent in x and y covers (x, y) (boxes, not exact outlines):
// the ground under a figure dropped there on a map of axis-aligned brushes; none when no shape is.
std::optional<Real> highestTopAt(std::span<const Polytope> shapes, Real x, Real y);

}  // namespace af
